//! Exact transfer functions of the damped Euler-Bernoulli span
//! EI Y'''' - T Y'' + s (c_d + mu s) Y = 0 (T a constant axial tension, 0 in seed
//! 004) between any four of its eight end quantities.
//!
//! The end quantities are numbered as in seed 004 eq. 5.2: 1 y(0), 2 y'(0),
//! 3 EI y''(0), 4 EI y'''(0) - T y'(0), 5 y(L), 6 y'(L), 7 EI y''(L),
//! 8 EI y'''(L) - T y'(L) (the shear is the transverse force; T = 0 gives the
//! source's). With four
//! chosen as inputs, the other four are outputs: `H(s) = Phi_out(s) Phi_in(s)^-1`,
//! where `Phi` maps the coefficients of the general solution to the end quantities.
//!
//! Robust for large |beta L|: the solution is written on the four roots b_k of
//! b^4 = -s (c_d + mu s) / EI as `exp(b_k (x - x_k))` with x_k = L for Re b_k > 0
//! and 0 otherwise, so that every basis function is bounded by 1 on [0, L] and no
//! sinh or cosh can overflow.

use crate::contract::{UnitError, require_in_range};
use nalgebra::{Complex, Matrix4};

/// Complex numbers.
pub type C64 = Complex<f64>;

/// Properties of a span.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Span {
    /// EI (N m^2).
    pub flexural_rigidity: f64,
    /// mu (kg/m).
    pub mass_per_length: f64,
    /// c_d (N s/m^2).
    pub damping_per_length: f64,
    /// L (m).
    pub length: f64,
    /// Constant axial tension T (N), 0 in seed 004.
    pub tension: f64,
}

impl Span {
    /// Checks the properties: L 1e-2..1e5 m, then the section's ranges
    /// ([`check_section`](crate::beam::params::check_section)).
    pub fn validate(&self) -> Result<(), UnitError> {
        require_in_range("length", self.length, 1e-2, 1e5, "m")?;
        require_in_range("tension", self.tension, -1e10, 1e10, "N")?;
        crate::beam::params::check_section(
            self.flexural_rigidity,
            self.mass_per_length,
            self.damping_per_length,
        )
    }

    /// beta^4 = -s (c_d + mu s) / EI.
    pub fn beta4(&self, s: C64) -> C64 {
        -s * (self.damping_per_length + self.mass_per_length * s) / self.flexural_rigidity
    }

    /// Rows of the eight end quantities (1..8 as 0..7) against the four basis
    /// coefficients at s.
    pub fn boundary_matrix(&self, s: C64) -> [[C64; 4]; 8] {
        if self.tension != 0.0 {
            return self.tensioned_boundary_matrix(s);
        }
        let (l, ei) = (self.length, self.flexural_rigidity);
        let b4 = self.beta4(s);
        let root = if b4.norm() == 0.0 {
            C64::new(0.0, 0.0)
        } else {
            b4.powf(0.25)
        };
        let i = C64::new(0.0, 1.0);
        let roots = [root, root * i, -root, -root * i];
        let mut phi = [[C64::new(0.0, 0.0); 4]; 8];
        if root.norm() < 1e-12 / l {
            // s = 0: the static solution 1, x, x^2, x^3.
            for (end, x) in [(0usize, 0.0f64), (1, l)] {
                let r = 4 * end;
                phi[r] = [
                    C64::from(1.0),
                    C64::from(x),
                    C64::from(x * x),
                    C64::from(x * x * x),
                ];
                phi[r + 1] = [
                    C64::from(0.0),
                    C64::from(1.0),
                    C64::from(2.0 * x),
                    C64::from(3.0 * x * x),
                ];
                phi[r + 2] = [
                    C64::from(0.0),
                    C64::from(0.0),
                    C64::from(2.0 * ei),
                    C64::from(6.0 * ei * x),
                ];
                phi[r + 3] = [
                    C64::from(0.0),
                    C64::from(0.0),
                    C64::from(0.0),
                    C64::from(6.0 * ei),
                ];
            }
            return phi;
        }
        for (k, b) in roots.iter().enumerate() {
            let anchor = if b.re > 0.0 { l } else { 0.0 };
            for (end, x) in [(0usize, 0.0f64), (1, l)] {
                let e = (b * (x - anchor)).exp();
                phi[4 * end][k] = e;
                phi[4 * end + 1][k] = b * e;
                phi[4 * end + 2][k] = ei * b * b * e;
                phi[4 * end + 3][k] = ei * b * b * b * e;
            }
        }
        phi
    }

    /// The boundary matrix with tension: the roots of EI b^4 - T b^2 + s (c_d +
    /// mu s) = 0 come in pairs +-r (r^2 = (T +- sqrt(T^2 - 4 EI s (c_d + mu s))) /
    /// (2 EI)). A pair with |r| L >= 1 uses exp(+-r (x - x_k)) anchored so each is
    /// at most 1 on [0, L]; a small pair uses cosh(r x) and sinh(r x) / r by their
    /// series, and when both pairs are small the second pair is replaced by the
    /// divided differences of the first's functions in r^2 (tending to x^2 / 2 and
    /// x^3 / 6), so the basis stays independent as T and s go to 0.
    fn tensioned_boundary_matrix(&self, s: C64) -> [[C64; 4]; 8] {
        let (l, ei, t) = (self.length, self.flexural_rigidity, self.tension);
        let q = s * (self.damping_per_length + self.mass_per_length * s) / ei;
        let tau = C64::from(t / ei);
        let disc = (tau * tau - 4.0 * q).sqrt();
        let squares = [(tau + disc) / 2.0, (tau - disc) / 2.0];
        let small = squares.map(|r2| r2.sqrt().norm() * l < 1.0);
        let mut phi = [[C64::new(0.0, 0.0); 4]; 8];
        for (end, x) in [(0usize, 0.0f64), (1, l)] {
            // Value and first three derivatives of the four basis functions at x.
            let mut columns = [[C64::new(0.0, 0.0); 4]; 4];
            for (pair, r2) in squares.iter().enumerate() {
                let r = r2.sqrt();
                let pair_columns = if !small[pair] {
                    [r, -r].map(|b| {
                        let anchor = if b.re > 0.0 { l } else { 0.0 };
                        let e = (b * (x - anchor)).exp();
                        [e, b * e, b * b * e, b * b * b * e]
                    })
                } else if pair == 1 && small[0] {
                    let (a, b) = (squares[0], squares[1]);
                    [
                        series(x, |m| divided(a, b, m, 0)),
                        series(x, |m| divided(a, b, m, 1)),
                    ]
                } else {
                    [
                        series(x, |m| even_power(*r2, m, 0)),
                        series(x, |m| even_power(*r2, m, 1)),
                    ]
                };
                columns[2 * pair] = pair_columns[0];
                columns[2 * pair + 1] = pair_columns[1];
            }
            for (k, col) in columns.iter().enumerate() {
                phi[4 * end][k] = col[0];
                phi[4 * end + 1][k] = col[1];
                phi[4 * end + 2][k] = ei * col[2];
                phi[4 * end + 3][k] = ei * col[3] - t * col[1];
            }
        }
        phi
    }

    /// The 4x4 transfer matrix from `inputs` to `outputs` (quantity numbers 1..8)
    /// at s; `H[o][i]` is output o's response to input i.
    pub fn transfer(
        &self,
        s: C64,
        inputs: [usize; 4],
        outputs: [usize; 4],
    ) -> Result<[[C64; 4]; 4], UnitError> {
        check_choice(inputs, outputs)?;
        let phi = self.boundary_matrix(s);
        let a = Matrix4::from_fn(|r, c| phi[inputs[r] - 1][c]);
        let inv = a.try_inverse().ok_or_else(|| {
            UnitError::Numerical(format!(
                "the inputs {inputs:?} do not determine the span at s = {s}"
            ))
        })?;
        let mut h = [[C64::new(0.0, 0.0); 4]; 4];
        for (o, &q) in outputs.iter().enumerate() {
            for i in 0..4 {
                h[o][i] = (0..4).map(|c| phi[q - 1][c] * inv[(c, i)]).sum();
            }
        }
        Ok(h)
    }

    /// Checks that `inputs` determine the span: the map from the solution to the
    /// inputs is invertible at several test frequencies.
    pub fn check_admissible(&self, inputs: [usize; 4]) -> Result<(), UnitError> {
        let outputs = complement(inputs)?;
        for s in [
            C64::new(0.0, 0.37),
            C64::new(-0.2, 1.9),
            C64::new(0.0, 13.1),
        ] {
            self.transfer(s, inputs, outputs).map_err(|_| {
                UnitError::parameter(
                    "inputs",
                    format!("{inputs:?}"),
                    "these four end quantities do not give a well-posed span problem",
                )
            })?;
        }
        Ok(())
    }

    /// Seed 004 eq. 5.9: H_{U2 -> U5} with U1 = U7 = U8 = 0, in closed form (for
    /// checks; it overflows for large |beta L|, `transfer` does not).
    pub fn h_u2_u5_closed_form(&self, s: C64) -> C64 {
        let b = self.beta4(s).powf(0.25);
        let lb = b * self.length;
        (lb.sin() + lb.sinh()) / (b * (lb.cos() * lb.cosh() + 1.0))
    }
}

/// Terms of the series kept: |r x| < 1 makes term m smaller than 1 / m!.
const SERIES_TERMS: usize = 30;

/// Value and first three derivatives at x of f = sum_m c(m) x^m / m!.
fn series(x: f64, c: impl Fn(usize) -> C64) -> [C64; 4] {
    let mut out = [C64::new(0.0, 0.0); 4];
    for (k, o) in out.iter_mut().enumerate() {
        // The k-th derivative of x^m / m! is x^(m - k) / (m - k)!.
        let mut power = 1.0;
        for m in k..SERIES_TERMS {
            if m > k {
                power *= x / (m - k) as f64;
            }
            *o += c(m) * power;
        }
    }
    out
}

/// Coefficient m of cosh(r x) (parity 0) or sinh(r x) / r (parity 1) with
/// r^2 = a: a^n where m = 2n + parity, else 0.
fn even_power(a: C64, m: usize, parity: usize) -> C64 {
    if m % 2 != parity {
        return C64::new(0.0, 0.0);
    }
    a.powu(((m - parity) / 2) as u32)
}

/// Coefficient m of the divided difference in r^2 between a and b of cosh
/// (parity 0) or sinh / r (parity 1): (a^n - b^n) / (a - b) = sum_j a^j
/// b^(n-1-j), n = (m - parity) / 2, without the quotient's cancellation.
fn divided(a: C64, b: C64, m: usize, parity: usize) -> C64 {
    if m % 2 != parity || m < 2 {
        return C64::new(0.0, 0.0);
    }
    let n = (m - parity) / 2;
    (0..n)
        .map(|j| a.powu(j as u32) * b.powu((n - 1 - j) as u32))
        .sum()
}

/// The four quantities not in `inputs`, in increasing order.
pub fn complement(inputs: [usize; 4]) -> Result<[usize; 4], UnitError> {
    let rest: Vec<usize> = (1..=8).filter(|q| !inputs.contains(q)).collect();
    rest.try_into().map_err(|_| {
        UnitError::parameter(
            "inputs",
            format!("{inputs:?}"),
            "expected four distinct quantities among 1..8",
        )
    })
}

fn check_choice(inputs: [usize; 4], outputs: [usize; 4]) -> Result<(), UnitError> {
    let all: Vec<usize> = inputs.iter().chain(&outputs).copied().collect();
    if all.iter().any(|&q| !(1..=8).contains(&q)) {
        return Err(UnitError::parameter(
            "inputs",
            format!("{inputs:?} -> {outputs:?}"),
            "quantities are numbered 1..8",
        ));
    }
    if inputs.iter().any(|q| outputs.contains(q))
        || (1..=8).any(|q| inputs.iter().filter(|&&x| x == q).count() > 1)
    {
        return Err(UnitError::parameter(
            "inputs",
            format!("{inputs:?} -> {outputs:?}"),
            "an input cannot repeat or also be an output",
        ));
    }
    Ok(())
}
