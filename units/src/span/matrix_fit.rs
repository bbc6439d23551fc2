//! The common-pole rational fit of the span's 4x4 transfer matrix (kind
//! `span_coupling`): vector fitting of the sixteen entries with shared poles,
//! improper entries with a feedthrough and a rate term, exact static values.

use super::fit::{check_order_and_band, sigma_zeros};
use super::transfer::{C64, Span};
use crate::contract::UnitError;
use crate::numerics::bounded;
use nalgebra::{DMatrix, DVector};

/// A common-pole rational fit of the 4x4 transfer matrix.
#[derive(Clone, Debug)]
pub struct MatrixFit {
    /// One pole of each conjugate pair (Im > 0), all with Re < 0 (1/s).
    pub poles: Vec<C64>,
    /// residues[o][i][k]: residue of output o, input i at pole k (its conjugate
    /// pair has the conjugate residue).
    pub residues: [[Vec<C64>; 4]; 4],
    /// Direct term D of each entry (H = sum of residue terms + D + E s).
    pub d: [[f64; 4]; 4],
    /// Proportional term E of each entry (s).
    pub e: [[f64; 4]; 4],
}

impl MatrixFit {
    /// The fitted 4x4 response at s.
    pub fn response(&self, s: C64) -> [[C64; 4]; 4] {
        let mut h = [[C64::new(0.0, 0.0); 4]; 4];
        for (o, row) in h.iter_mut().enumerate() {
            for (i, v) in row.iter_mut().enumerate() {
                *v = self
                    .poles
                    .iter()
                    .zip(&self.residues[o][i])
                    .map(|(&p, &r)| r / (s - p) + r.conj() / (s - p.conj()))
                    .sum::<C64>()
                    + self.d[o][i]
                    + s * self.e[o][i];
            }
        }
        h
    }
}

/// Real basis of a conjugate pole pair: 1/(s-p) + 1/(s-p*) and i(1/(s-p) - 1/(s-p*)).
fn basis(s: C64, poles: &[C64]) -> Vec<C64> {
    let one = C64::new(1.0, 0.0);
    let i = C64::new(0.0, 1.0);
    let mut b = Vec::with_capacity(2 * poles.len());
    for &p in poles {
        let (x, y) = (one / (s - p), one / (s - p.conj()));
        b.push(x + y);
        b.push(i * (x - y));
    }
    b
}

/// Fits the 4x4 transfer matrix from `inputs` to `outputs` with `order` poles
/// (even, 2..=40) over [band / 1e4, band] rad/s.
pub fn fit_matrix(
    span: &Span,
    inputs: [usize; 4],
    outputs: [usize; 4],
    order: usize,
    band: f64,
) -> Result<MatrixFit, UnitError> {
    span.validate()?;
    check_order_and_band(order, band)?;
    span.check_admissible(inputs)?;
    let samples = (8 * order).max(200);
    let omegas: Vec<f64> = (0..samples)
        .map(|k| band * 10f64.powf(-4.0 + 4.0 * k as f64 / (samples - 1) as f64))
        .collect();
    let data: Vec<[[C64; 4]; 4]> = omegas
        .iter()
        .map(|&w| span.transfer(C64::new(0.0, w), inputs, outputs))
        .collect::<Result<_, _>>()?;
    // Each entry weighted by its size over the band, so that all sixteen count.
    let mut scale = [[0.0_f64; 4]; 4];
    for h in &data {
        for o in 0..4 {
            for i in 0..4 {
                scale[o][i] = scale[o][i].max(h[o][i].norm());
            }
        }
    }
    let pairs = order / 2;
    let mut poles: Vec<C64> = (0..pairs)
        .map(|k| {
            let b = band * 10f64.powf(-4.0 + 4.0 * (k as f64 + 0.5) / pairs as f64);
            C64::new(-b / 100.0, b)
        })
        .collect();
    for _ in 0..15 {
        poles = relocate(&poles, &omegas, &data, &scale)?;
    }
    residues(span, poles, inputs, outputs, &omegas, &data, &scale)
}

/// One relocation of the common poles (fast vector fitting: each entry's block
/// is reduced by QR to the rows that involve the shared sigma function).
fn relocate(
    poles: &[C64],
    omegas: &[f64],
    data: &[[[C64; 4]; 4]],
    scale: &[[f64; 4]; 4],
) -> Result<Vec<C64>, UnitError> {
    let n = 2 * poles.len();
    let own = n + 2; // residues, d, e
    let cols = own + n + 1; // + sigma residues + right-hand side
    let mut stacked = DMatrix::zeros(16 * n, n);
    let mut rhs = DVector::zeros(16 * n);
    let bases: Vec<Vec<C64>> = omegas
        .iter()
        .map(|&w| basis(C64::new(0.0, w), poles))
        .collect();
    for o in 0..4 {
        for i in 0..4 {
            let weight = 1.0 / scale[o][i].max(1e-300);
            let mut m = DMatrix::zeros(2 * omegas.len(), cols);
            for (k, (&w, b)) in omegas.iter().zip(&bases).enumerate() {
                let h = data[k][o][i] * weight;
                let s = C64::new(0.0, w);
                let mut row: Vec<C64> = b.iter().map(|v| v * weight).collect();
                row.push(C64::new(weight, 0.0));
                row.push(s * weight);
                row.extend(b.iter().map(|&v| -h * v));
                row.push(h);
                for (c, v) in row.iter().enumerate() {
                    m[(2 * k, c)] = v.re;
                    m[(2 * k + 1, c)] = v.im;
                }
            }
            let r = m.qr().r();
            let block = 4 * o + i;
            for row in 0..n {
                for c in 0..n {
                    stacked[(block * n + row, c)] = r[(own + row, own + c)];
                }
                rhs[block * n + row] = r[(own + row, cols - 1)];
            }
        }
    }
    let x = bounded::least_squares("vector fitting", stacked, &rhs, 1e-14)?;
    sigma_zeros(poles, &x.as_slice()[..n])
}

/// Residues, D and E of every entry with the poles fixed; D corrected so that the
/// static response is exact.
fn residues(
    span: &Span,
    poles: Vec<C64>,
    inputs: [usize; 4],
    outputs: [usize; 4],
    omegas: &[f64],
    data: &[[[C64; 4]; 4]],
    scale: &[[f64; 4]; 4],
) -> Result<MatrixFit, UnitError> {
    let n = 2 * poles.len();
    let bases: Vec<Vec<C64>> = omegas
        .iter()
        .map(|&w| basis(C64::new(0.0, w), &poles))
        .collect();
    let static_gain = span.transfer(C64::new(0.0, 0.0), inputs, outputs)?;
    let at_zero = basis(C64::new(0.0, 0.0), &poles);
    let mut fit = MatrixFit {
        residues: Default::default(),
        d: [[0.0; 4]; 4],
        e: [[0.0; 4]; 4],
        poles,
    };
    for o in 0..4 {
        for i in 0..4 {
            // Only a load answering a motion grows without bound (stiffness and
            // inertia); compliances and transmissions vanish at high frequency, so
            // they get no feedthrough and their static value comes from the
            // residues (a heavily weighted row), keeping the model strictly proper
            // where the span is.
            let improper = is_motion(inputs[i]) && !is_motion(outputs[o]);
            let unknowns = if improper { n + 2 } else { n };
            let rows = 2 * omegas.len() + usize::from(!improper);
            let weight = 1.0 / scale[o][i].max(1e-300);
            let mut a = DMatrix::zeros(rows, unknowns);
            let mut b = DVector::zeros(rows);
            for (k, (&w, basis)) in omegas.iter().zip(&bases).enumerate() {
                let s = C64::new(0.0, w);
                let mut row = basis.clone();
                if improper {
                    row.push(C64::new(1.0, 0.0));
                    row.push(s);
                }
                for (c, v) in row.iter().enumerate() {
                    a[(2 * k, c)] = v.re * weight;
                    a[(2 * k + 1, c)] = v.im * weight;
                }
                b[2 * k] = data[k][o][i].re * weight;
                b[2 * k + 1] = data[k][o][i].im * weight;
            }
            if !improper {
                let static_weight = 1e4 * weight;
                for (c, v) in at_zero.iter().enumerate() {
                    a[(rows - 1, c)] = v.re * static_weight;
                }
                b[rows - 1] = static_gain[o][i].re * static_weight;
            }
            let x = bounded::least_squares("vector fitting", a, &b, 1e-14)?;
            fit.residues[o][i] = (0..n / 2)
                .map(|k| C64::new(x[2 * k], x[2 * k + 1]))
                .collect();
            let dynamic_at_zero: f64 = (0..n).map(|m| x[m] * at_zero[m].re).sum();
            if improper {
                fit.d[o][i] = static_gain[o][i].re - dynamic_at_zero;
                fit.e[o][i] = x[n + 1];
            } else {
                // Spread what the weighted row left of the static value over the
                // residues of the slowest pole pair (tiny), so H(0) stays exact.
                let gap = static_gain[o][i].re - dynamic_at_zero;
                let slowest = (0..n / 2)
                    .min_by(|&p, &q| fit.poles[p].norm().total_cmp(&fit.poles[q].norm()))
                    .unwrap_or(0);
                let unit_gain = at_zero[2 * slowest].re;
                if unit_gain != 0.0 {
                    fit.residues[o][i][slowest].re += gap / unit_gain;
                }
            }
        }
    }
    Ok(fit)
}

/// Whether end quantity `q` (1..8) is a motion (deflection or rotation).
pub(super) fn is_motion(q: usize) -> bool {
    matches!(q, 1 | 2 | 5 | 6)
}
