//! Vector fitting (Gustavsen and Semlyen 1999) of the exact span transfer function
//! over a band: poles are relocated iteratively to where the span resonates, kept
//! in the left half-plane, then the residues are fitted with the poles fixed.

use super::realization::StateSpace;
use super::transfer::{C64, Span};
use crate::contract::UnitError;
use crate::numerics::bounded;
use nalgebra::{DMatrix, DVector};

/// Poles of a vector fit of order `order` (even) to H_{U2 -> U5} over
/// [band / 1e4, band] rad/s.
pub fn fit_poles(span: &Span, order: usize, band: f64) -> Result<Vec<C64>, UnitError> {
    check_order_and_band(order, band)?;
    // Starting poles: conjugate pairs log-spaced over the band, lightly damped.
    let pairs = order / 2;
    let start: Vec<C64> = (0..pairs)
        .map(|k| {
            let b = band * 10f64.powf(-4.0 + 4.0 * (k as f64 + 0.5) / pairs as f64);
            C64::new(-b / 100.0, b)
        })
        .collect();
    relocate_poles(span, &start, band)
}

/// Vector fitting from given starting poles (one per conjugate pair, in the upper
/// half-plane) against H_{U2 -> U5} over [band / 1e4, band]: 20 relocations;
/// returns all poles, pairs listed together.
pub(super) fn relocate_poles(span: &Span, start: &[C64], band: f64) -> Result<Vec<C64>, UnitError> {
    let samples = (12 * start.len()).max(200);
    let omegas: Vec<f64> = (0..samples)
        .map(|k| band * 10f64.powf(-4.0 + 4.0 * k as f64 / (samples - 1) as f64))
        .collect();
    let h: Vec<C64> = omegas
        .iter()
        .map(|&w| {
            span.transfer(C64::new(0.0, w), [1, 2, 7, 8], [3, 4, 5, 6])
                .map(|m| m[2][1])
        })
        .collect::<Result<_, _>>()?;
    let mut poles = start.to_vec();
    for _ in 0..20 {
        poles = relocate(&poles, &omegas, &h)?;
    }
    let mut all = Vec::with_capacity(2 * poles.len());
    for p in poles {
        all.push(p);
        all.push(p.conj());
    }
    Ok(all)
}

/// One pole relocation: fit sigma(s) H(s) ~ sum c/(s-a) + d with
/// sigma(s) = 1 + sum ct/(s-a); the new poles are the zeros of sigma.
fn relocate(poles: &[C64], omegas: &[f64], h: &[C64]) -> Result<Vec<C64>, UnitError> {
    let n = 2 * poles.len();
    let unknowns = 2 * n + 1; // residues of the fit (n real), d, residues of sigma (n real)
    let one = C64::new(1.0, 0.0);
    let i = C64::new(0.0, 1.0);
    let mut a = DMatrix::zeros(2 * omegas.len(), unknowns);
    let mut b = DVector::zeros(2 * omegas.len());
    for (k, (&w, &hk)) in omegas.iter().zip(h).enumerate() {
        let s = C64::new(0.0, w);
        let weight = 1.0 / hk.norm().max(1e-300);
        let mut basis = Vec::with_capacity(n);
        for &p in poles {
            let (x, y) = (one / (s - p), one / (s - p.conj()));
            basis.push(x + y);
            basis.push(i * (x - y));
        }
        let mut row: Vec<C64> = basis.clone();
        row.push(one);
        row.extend(basis.iter().map(|&v| -hk * v));
        for (c, v) in row.iter().enumerate() {
            a[(2 * k, c)] = v.re * weight;
            a[(2 * k + 1, c)] = v.im * weight;
        }
        b[2 * k] = hk.re * weight;
        b[2 * k + 1] = hk.im * weight;
    }
    let x = bounded::least_squares("vector fitting", a, &b, 1e-14)?;
    sigma_zeros(poles, &x.as_slice()[n + 1..2 * n + 1])
}

/// Checks a fit's order (even, 2..=40) and band (rad/s, > 0).
pub(super) fn check_order_and_band(order: usize, band: f64) -> Result<(), UnitError> {
    if order < 2 || order % 2 != 0 || order > 40 {
        return Err(UnitError::parameter(
            "order",
            order,
            "expected an even order from 2 to 40",
        ));
    }
    if !(band.is_finite() && band > 0.0 && band <= 1e5) {
        return Err(UnitError::parameter(
            "band",
            crate::contract::unit::number(band),
            "expected an angular frequency > 0 and at most 1e5 rad/s",
        ));
    }
    Ok(())
}

/// The zeros of sigma(s) = 1 + sum_m c_m basis_m(s) (basis of conjugate pairs, as
/// in the fits), as the next poles: one per pair, reflected into the left
/// half-plane; real zeros become lightly damped pairs and the count is kept.
pub(super) fn sigma_zeros(poles: &[C64], c: &[f64]) -> Result<Vec<C64>, UnitError> {
    let n = 2 * poles.len();
    let mut am = DMatrix::zeros(n, n);
    let mut bv = DVector::zeros(n);
    let mut ct = DVector::zeros(n);
    for (j, p) in poles.iter().enumerate() {
        let r = 2 * j;
        // z' = p z + u, sigma = 1 + 2 Re(c z) with c = c_re + i c_im, z = x1 + i x2.
        am[(r, r)] = p.re;
        am[(r, r + 1)] = -p.im;
        am[(r + 1, r)] = p.im;
        am[(r + 1, r + 1)] = p.re;
        bv[r] = 1.0;
        ct[r] = 2.0 * c[r];
        ct[r + 1] = -2.0 * c[r + 1];
    }
    let zeros = bounded::complex_eigenvalues("vector fitting", am - bv * ct.transpose())?;
    let mut next: Vec<C64> = zeros
        .iter()
        .filter(|z| z.im > 0.0)
        .map(|z| C64::new(-z.re.abs().max(1e-6 * z.norm()), z.im))
        .collect();
    let reals: Vec<C64> = zeros.iter().filter(|z| z.im == 0.0).copied().collect();
    for pair in reals.chunks(2) {
        if next.len() < poles.len() {
            let m = pair
                .iter()
                .map(|z| z.re.abs())
                .fold(0.0, f64::max)
                .max(1e-6);
            next.push(C64::new(-m / 100.0, m));
        }
    }
    next.truncate(poles.len());
    while next.len() < poles.len() {
        next.push(poles[next.len()]);
    }
    Ok(next)
}

/// A vector-fitted span system of order `order` over the band.
pub fn fit(span: &Span, order: usize, band: f64) -> Result<StateSpace, UnitError> {
    let poles = fit_poles(span, order, band)?;
    StateSpace::from_poles(&poles, span, band)
}
