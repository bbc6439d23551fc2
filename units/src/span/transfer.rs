//! Exact transfer functions of the damped Euler-Bernoulli span
//! EI Y'''' + s (c_d + mu s) Y = 0 between any four of its eight end quantities.
//!
//! The end quantities are numbered as in seed 004 eq. 5.2: 1 y(0), 2 y'(0),
//! 3 EI y''(0), 4 EI y'''(0), 5 y(L), 6 y'(L), 7 EI y''(L), 8 EI y'''(L). With four
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
}

impl Span {
    /// Checks the properties: L 1e-2..1e5 m, then the section's ranges
    /// ([`check_section`](crate::beam::params::check_section)).
    pub fn validate(&self) -> Result<(), UnitError> {
        require_in_range("length", self.length, 1e-2, 1e5, "m")?;
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
