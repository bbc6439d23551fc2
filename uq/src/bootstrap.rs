//! Bootstrap confidence intervals of an expansion's moments and Sobol'
//! indices: the selected basis is refitted by least squares on resamples of
//! the points (drawn with replacement from a seed), and each quantity's
//! central interval at the given level is read from the replicates.

use crate::UqError;
use crate::pce::{Pce, design_matrix};
use nalgebra::{DMatrix, DVector};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Central intervals (low, high) of each quantity.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Intervals {
    /// Of the output's mean.
    pub mean: (f64, f64),
    /// Of its variance.
    pub variance: (f64, f64),
    /// Of each input's first-order Sobol' index.
    pub first_order: Vec<(f64, f64)>,
    /// Of each input's total Sobol' index.
    pub total: Vec<(f64, f64)>,
}

/// Intervals at `level` (e.g. 0.95) from `replicates` resamples of the data
/// `pce` was fitted on.
pub fn intervals(
    pce: &Pce,
    (xi, y): (&[Vec<f64>], &[f64]),
    replicates: usize,
    level: f64,
    seed: u64,
) -> Result<Intervals, UqError> {
    if replicates < 10 || !(0.0..1.0).contains(&level) || xi.len() != y.len() {
        return Err(UqError::input(
            "bootstrap",
            format!(
                "{replicates} replicates at level {level} on {} points and {} outputs: expected >= 10 replicates, a level in (0, 1), as many outputs as points",
                xi.len(),
                y.len()
            ),
        ));
    }
    let degree = pce.indices.iter().flatten().copied().max().unwrap_or(0);
    let psi = design_matrix(&pce.families, &pce.indices, xi, degree);
    let n = y.len();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut samples: Vec<Pce> = Vec::with_capacity(replicates);
    for _ in 0..replicates {
        let rows: Vec<usize> = (0..n).map(|_| rng.random_range(0..n)).collect();
        let a = DMatrix::from_fn(n, psi.ncols(), |i, k| psi[(rows[i], k)]);
        let b = DVector::from_iterator(n, rows.iter().map(|&i| y[i]));
        // A resample that leaves the basis singular is drawn again next time.
        if let Some(c) = least_squares(a, &b) {
            samples.push(Pce {
                coefficients: c.iter().copied().collect(),
                ..pce.clone()
            });
        }
    }
    if samples.len() < replicates / 2 {
        return Err(UqError::Singular(format!(
            "{} of {replicates} resamples left the basis singular",
            replicates - samples.len()
        )));
    }
    let interval = |f: &dyn Fn(&Pce) -> f64| central(samples.iter().map(f).collect(), level);
    let dims = pce.families.len();
    Ok(Intervals {
        mean: interval(&|p| p.mean()),
        variance: interval(&|p| p.variance()),
        first_order: (0..dims).map(|i| interval(&|p| p.first_order(i))).collect(),
        total: (0..dims).map(|i| interval(&|p| p.total(i))).collect(),
    })
}

/// Least squares by QR; None when the columns are dependent.
fn least_squares(a: DMatrix<f64>, b: &DVector<f64>) -> Option<DVector<f64>> {
    let qr = a.qr();
    let r = qr.r();
    let scale = r[(0, 0)].abs();
    if r.diagonal().iter().any(|d| d.abs() <= 1e-12 * scale) {
        return None;
    }
    r.solve_upper_triangular(&(qr.q().transpose() * b))
}

/// The central interval holding `level` of the values.
fn central(mut values: Vec<f64>, level: f64) -> (f64, f64) {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    let at = |p: f64| values[((p * (n - 1) as f64).round() as usize).min(n - 1)];
    let tail = (1.0 - level) / 2.0;
    (at(tail), at(1.0 - tail))
}
