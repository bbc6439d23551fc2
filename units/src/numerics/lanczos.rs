//! The largest eigenvalue of a symmetric pencil K x = lambda M x (M positive
//! definite, both banded) by Lanczos in the M inner product with full
//! reorthogonalisation, with an upper bound from the Ritz residual. Where power
//! iteration crawls on clustered top eigenvalues (a frame's highest axial
//! modes), Lanczos converges in tens of steps.

use super::banded::{BandLdlt, SymmetricBand};
use nalgebra::{DMatrix, SymmetricEigen};

/// The largest eigenvalue: its Ritz estimate and a bound above it.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct LargestEigenvalue {
    /// The Ritz value (a lower bound that converges to lambda_max).
    pub estimate: f64,
    /// estimate + |beta_m s_m|: lambda_max lies below it.
    pub upper_bound: f64,
    /// Lanczos steps taken.
    pub steps: usize,
}

/// Lanczos on M^-1 K (self-adjoint in x^T M y) from a start vector with every
/// mode in it, until the Ritz residual is below `tolerance` times the estimate or
/// after `max_steps` (at most the order). `None` when M is not positive definite
/// or nothing is finite.
pub fn largest_eigenvalue(
    k: &SymmetricBand,
    m: &SymmetricBand,
    tolerance: f64,
    max_steps: usize,
) -> Option<LargestEigenvalue> {
    let n = m.size();
    let mass = BandLdlt::new(m)?;
    let steps = max_steps.min(n).max(1);
    let mut basis: Vec<Vec<f64>> = Vec::with_capacity(steps);
    // M-orthonormal basis V and the M-products M V, for reorthogonalisation.
    let mut m_basis: Vec<Vec<f64>> = Vec::with_capacity(steps);
    let (mut alpha, mut beta) = (Vec::new(), Vec::new());
    let mut v: Vec<f64> = (0..n)
        .map(|i| 1.0 + ((i * 7919) % 13) as f64 / 13.0)
        .collect();
    let norm = m_norm(m, &v);
    v.iter_mut().for_each(|x| *x /= norm);
    let mut best = None;
    for j in 0..steps {
        let mut mv = vec![0.0; n];
        m.mul_add(1.0, &v, &mut mv);
        // w = M^-1 K v; alpha = v^T K v.
        let mut w = vec![0.0; n];
        k.mul_add(1.0, &v, &mut w);
        let a: f64 = w.iter().zip(&v).map(|(x, y)| x * y).sum();
        mass.solve_in_place(&mut w);
        basis.push(v);
        m_basis.push(mv);
        alpha.push(a);
        // Full reorthogonalisation (twice) in the M inner product.
        for _ in 0..2 {
            for (b, mb) in basis.iter().zip(&m_basis) {
                let c: f64 = w.iter().zip(mb).map(|(x, y)| x * y).sum();
                w.iter_mut().zip(b).for_each(|(x, y)| *x -= c * y);
            }
        }
        let b = m_norm(m, &w);
        if !(a.is_finite() && b.is_finite()) {
            return None;
        }
        let (theta, last) = top_ritz(&alpha, &beta);
        let bound = (b * last).abs();
        best = Some(LargestEigenvalue {
            estimate: theta,
            upper_bound: theta + bound,
            steps: j + 1,
        });
        if bound <= tolerance * theta.abs() || b <= 1e-14 * theta.abs() {
            break;
        }
        beta.push(b);
        v = w.iter().map(|x| x / b).collect();
    }
    best
}

fn m_norm(m: &SymmetricBand, x: &[f64]) -> f64 {
    m.quadratic_form(x).max(0.0).sqrt()
}

/// The largest eigenvalue of the tridiagonal (alpha, beta) and the last component
/// of its unit eigenvector.
fn top_ritz(alpha: &[f64], beta: &[f64]) -> (f64, f64) {
    let j = alpha.len();
    let t = DMatrix::from_fn(j, j, |r, c| {
        if r == c {
            alpha[r]
        } else if r + 1 == c || c + 1 == r {
            beta[r.min(c)]
        } else {
            0.0
        }
    });
    let eigen = SymmetricEigen::new(t);
    let top = eigen.eigenvalues.imax();
    (eigen.eigenvalues[top], eigen.eigenvectors[(j - 1, top)])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_the_top_of_a_clustered_spectrum_with_a_bound_above_it() {
        // Diagonal pencil with eigenvalues 1..n and a cluster at the top.
        let n = 200;
        let mut k = SymmetricBand::zeros(n, 1);
        let mut m = SymmetricBand::zeros(n, 1);
        for i in 0..n {
            let lambda = if i >= n - 5 {
                1000.0 - (n - 1 - i) as f64 * 1e-3
            } else {
                1.0 + i as f64
            };
            m.add(i, i, 2.0);
            k.add(i, i, 2.0 * lambda);
        }
        let top = largest_eigenvalue(&k, &m, 1e-10, 200).expect("converges");
        assert!((top.estimate - 1000.0).abs() < 1e-6, "{top:?}");
        assert!(top.upper_bound >= 1000.0 - 1e-9, "{top:?}");
        assert!(top.steps < 100, "{top:?}");
    }
}
