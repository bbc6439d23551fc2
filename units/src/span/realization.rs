//! From a rational approximation in x = (beta L)^4 to a state-space system in s, with
//! unstable poles reflected into the left half-plane, and its exact discretisation
//! for an input ramped over each step.

use super::rational::RationalX;
use super::transfer::{C64, Span};
use crate::unit::UnitError;
use nalgebra::{DMatrix, DVector};

/// A real polynomial in s, ascending coefficients.
pub type Poly = Vec<f64>;

fn poly_mul(a: &[f64], b: &[f64]) -> Poly {
    let mut out = vec![0.0; a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            out[i + j] += x * y;
        }
    }
    out
}

/// p(x(s)) for x(s) = -(L^4 / EI)(c_d s + mu s^2).
fn substitute(p: &[f64], span: &Span) -> Poly {
    let k = -span.length.powi(4) / span.flexural_rigidity;
    let x = [0.0, k * span.damping_per_length, k * span.mass_per_length];
    let mut out = vec![0.0];
    for &c in p.iter().rev() {
        out = poly_mul(&out, &x);
        out[0] += c;
    }
    while out.len() > 1 && out.last().is_some_and(|v| *v == 0.0) {
        out.pop();
    }
    out
}

/// Least-squares residues (and a constant) for the given stable poles against the
/// exact H_{U2 -> U5} at log-spaced frequencies in [band / 1e4, band], weighted by
/// 1 / |H|, realised in real modal form (a 2x2 block per conjugate pair).
fn fit_residues(poles: &[C64], span: &Span, band: f64) -> Result<StateSpace, UnitError> {
    if !(band.is_finite() && band > 0.0) {
        return Err(UnitError::parameter(
            "band",
            band,
            "expected a finite angular frequency > 0 (rad/s)",
        ));
    }
    // One representative per real pole or conjugate pair.
    let mut groups: Vec<C64> = Vec::new();
    for &p in poles {
        if p.im.abs() <= 1e-9 * p.norm().max(1e-300) {
            groups.push(C64::new(p.re, 0.0));
        } else if p.im > 0.0 {
            groups.push(p);
        }
    }
    // The static gain H(0) (the rigid tilt of the span) is kept exactly: the constant
    // is eliminated, d = H(0) - sum_k r_k b_k(0), and the residues r_k fit
    // H(s) - H(0) on b_k(s) - b_k(0).
    let unknowns = groups
        .iter()
        .map(|p| if p.im == 0.0 { 1 } else { 2 })
        .sum::<usize>();
    let samples = (4 * unknowns).max(200);
    let mut rows: Vec<Vec<f64>> = Vec::with_capacity(2 * samples);
    let mut rhs: Vec<f64> = Vec::with_capacity(2 * samples);
    let one = C64::new(1.0, 0.0);
    let basis_at = |s: C64| -> Vec<C64> {
        let mut basis = Vec::with_capacity(unknowns);
        for &p in &groups {
            if p.im == 0.0 {
                basis.push(one / (s - p));
            } else {
                let (a, b) = (one / (s - p), one / (s - p.conj()));
                basis.push(a + b);
                basis.push(C64::new(0.0, 1.0) * (a - b));
            }
        }
        basis
    };
    let zero = C64::new(0.0, 0.0);
    let dc = span.transfer(zero, [1, 2, 7, 8], [3, 4, 5, 6])?[2][1];
    let basis0 = basis_at(zero);
    for k in 0..samples {
        let w = band * 10f64.powf(-4.0 + 4.0 * k as f64 / (samples - 1) as f64);
        let s = C64::new(0.0, w);
        let exact = span.transfer(s, [1, 2, 7, 8], [3, 4, 5, 6])?[2][1];
        let weight = 1.0 / exact.norm().max(1e-300);
        let basis: Vec<C64> = basis_at(s)
            .iter()
            .zip(&basis0)
            .map(|(b, b0)| b - b0)
            .collect();
        rows.push(basis.iter().map(|c| c.re * weight).collect());
        rows.push(basis.iter().map(|c| c.im * weight).collect());
        rhs.push((exact - dc).re * weight);
        rhs.push((exact - dc).im * weight);
    }
    let a = DMatrix::from_fn(rows.len(), unknowns, |r, c| rows[r][c]);
    let b = DVector::from_vec(rhs);
    let x = a
        .svd(true, true)
        .solve(&b, 1e-14)
        .map_err(|e| UnitError::Numerical(format!("residue fit failed: {e}")))?;
    // Real modal realisation.
    let n: usize = groups.iter().map(|p| if p.im == 0.0 { 1 } else { 2 }).sum();
    let mut am = DMatrix::zeros(n, n);
    let mut bm = DVector::zeros(n);
    let mut cm = DVector::zeros(n);
    let (mut row, mut k) = (0, 0);
    for &p in &groups {
        if p.im == 0.0 {
            am[(row, row)] = p.re;
            bm[row] = 1.0;
            cm[row] = x[k];
            row += 1;
            k += 1;
        } else {
            // r/(s-p) + conj as z' = p z + u, y = 2 Re(r z), z = x1 + i x2: the
            // rotation form keeps entries of size |p| (well conditioned for exp).
            let r = C64::new(x[k], x[k + 1]);
            am[(row, row)] = p.re;
            am[(row, row + 1)] = -p.im;
            am[(row + 1, row)] = p.im;
            am[(row + 1, row + 1)] = p.re;
            bm[row] = 1.0;
            cm[row] = 2.0 * r.re;
            cm[row + 1] = -2.0 * r.im;
            row += 2;
            k += 2;
        }
    }
    let d = dc.re
        - basis0
            .iter()
            .zip(x.iter())
            .map(|(b, r)| b.re * r)
            .sum::<f64>();
    Ok(StateSpace {
        a: am,
        b: bm,
        c: cm,
        d,
        poles: poles.to_vec(),
        repaired: 0,
    })
}

/// Roots of a polynomial (companion-matrix eigenvalues).
fn roots(p: &[f64]) -> Vec<C64> {
    let n = p.len() - 1;
    if n == 0 {
        return Vec::new();
    }
    let lead = p[n];
    let companion = DMatrix::from_fn(n, n, |r, c| {
        if r + 1 == c {
            1.0
        } else if r == n - 1 {
            -p[c] / lead
        } else {
            0.0
        }
    });
    companion.complex_eigenvalues().iter().copied().collect()
}

/// A single-input single-output state-space system dx/dt = A x + B u, y = C x + D u.
#[derive(Clone, Debug)]
pub struct StateSpace {
    pub a: DMatrix<f64>,
    pub b: DVector<f64>,
    pub c: DVector<f64>,
    pub d: f64,
    /// Poles (1/s), after repair.
    pub poles: Vec<C64>,
    /// Poles that were in the right half-plane and were reflected.
    pub repaired: usize,
}

impl StateSpace {
    /// Realises H(s) ~ L num(x(s)) / den(x(s)) in controllable canonical form. An
    /// approximation with poles in the right half-plane is repaired: the poles are
    /// reflected to -Re and the residues refitted by least squares to the exact
    /// transfer function over [band / 1e4, band] (rad/s), realised in real modal form.
    pub fn realize(
        approximation: &RationalX,
        span: &Span,
        band: f64,
    ) -> Result<StateSpace, UnitError> {
        span.validate()?;
        let num: Poly = substitute(&approximation.num, span)
            .iter()
            .map(|c| c * span.length)
            .collect();
        let den = substitute(&approximation.den, span);
        let n = den.len() - 1;
        if n == 0 || num.len() > den.len() {
            return Err(UnitError::Numerical(
                "the approximation is not a proper transfer function in s".into(),
            ));
        }
        let mut poles = roots(&den);
        let repaired = poles.iter().filter(|p| p.re > 0.0).count();
        if repaired > 0 {
            poles.iter_mut().for_each(|p| p.re = -p.re.abs());
            let mut fitted = fit_residues(&poles, span, band)?;
            fitted.repaired = repaired;
            return Ok(fitted);
        }
        let lead = den[n];
        let (num, den): (Poly, Poly) = (
            num.iter().map(|c| c / lead).collect(),
            den.iter().map(|c| c / lead).collect(),
        );
        let bn = if num.len() == n + 1 { num[n] } else { 0.0 };
        let a = DMatrix::from_fn(n, n, |r, c| {
            if r + 1 == c {
                1.0
            } else if r == n - 1 {
                -den[c]
            } else {
                0.0
            }
        });
        let mut b = DVector::zeros(n);
        b[n - 1] = 1.0;
        let c = DVector::from_fn(n, |k, _| num.get(k).copied().unwrap_or(0.0) - bn * den[k]);
        Ok(StateSpace {
            a,
            b,
            c,
            d: bn,
            poles,
            repaired,
        })
    }

    /// The system with the given stable poles and least-squares residues against the
    /// exact H_{U2 -> U5} over [band / 1e4, band].
    pub fn from_poles(poles: &[C64], span: &Span, band: f64) -> Result<StateSpace, UnitError> {
        fit_residues(poles, span, band)
    }

    /// Order (number of states).
    pub fn order(&self) -> usize {
        self.b.len()
    }

    /// Whether every pole has a negative real part.
    pub fn is_stable(&self) -> bool {
        self.poles.iter().all(|p| p.re < 0.0)
    }

    /// Exact step over h for an input ramped from u0 to u1:
    /// x1 = Phi x0 + Gamma1 u0 + Gamma2 (u1 - u0), from one matrix exponential.
    pub fn discretize(&self, h: f64) -> (DMatrix<f64>, DVector<f64>, DVector<f64>) {
        let n = self.order();
        let mut m = DMatrix::zeros(n + 2, n + 2);
        m.view_mut((0, 0), (n, n)).copy_from(&(&self.a * h));
        m.view_mut((0, n), (n, 1)).copy_from(&(&self.b * h));
        m[(n, n + 1)] = 1.0;
        let e = m.exp();
        let phi = e.view((0, 0), (n, n)).into_owned();
        let g1 = e.column(n).rows(0, n).into_owned();
        let g2 = e.column(n + 1).rows(0, n).into_owned();
        (phi, g1, g2)
    }
}
