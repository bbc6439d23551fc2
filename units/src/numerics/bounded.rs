//! nalgebra's iterative decompositions with a bound on their iterations.
//!
//! `DMatrix::svd` and `complex_eigenvalues` iterate until
//! they converge, without limit: on a matrix with non-finite entries (extreme
//! parameters overflow) they never return. These wrappers check the entries first
//! and stop after a number of iterations that a convergent problem of that size
//! never needs, with an error that says which decomposition failed. Where they
//! converge they return exactly what the unbounded calls return (same tolerance).

use crate::contract::UnitError;
use nalgebra::{Complex, DMatrix, DVector, SVD, Schur};

/// Iterations allowed for an n x m problem: far more than QR-type iterations need
/// (a few per eigen- or singular value), far fewer than a hang.
fn max_iterations(n: usize, m: usize) -> usize {
    1000 + 100 * n.max(m)
}

fn finite(what: &str, m: &DMatrix<f64>) -> Result<(), UnitError> {
    if m.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(UnitError::Numerical(format!(
            "{what}: the matrix has non-finite entries (parameters out of range?)"
        )))
    }
}

/// The singular value decomposition with U and V, or an error.
pub fn svd(
    what: &str,
    m: DMatrix<f64>,
) -> Result<SVD<f64, nalgebra::Dyn, nalgebra::Dyn>, UnitError> {
    finite(what, &m)?;
    let limit = max_iterations(m.nrows(), m.ncols());
    // The tolerance of `SVD::new`.
    SVD::try_new(m, true, true, 5.0 * f64::EPSILON, limit).ok_or_else(|| {
        UnitError::Numerical(format!(
            "{what}: the singular value decomposition did not converge in {limit} iterations"
        ))
    })
}

/// Least squares `m x = b` by SVD (singular values below `eps` dropped).
pub fn least_squares(
    what: &str,
    m: DMatrix<f64>,
    b: &DVector<f64>,
    eps: f64,
) -> Result<DVector<f64>, UnitError> {
    svd(what, m)?
        .solve(b, eps)
        .map_err(|e| UnitError::Numerical(format!("{what}: {e}")))
}

/// The (complex) eigenvalues of a square matrix, or an error.
pub fn complex_eigenvalues(
    what: &str,
    m: DMatrix<f64>,
) -> Result<DVector<Complex<f64>>, UnitError> {
    finite(what, &m)?;
    let limit = max_iterations(m.nrows(), m.ncols());
    Schur::try_new(m, f64::EPSILON, limit)
        .map(|s| s.complex_eigenvalues())
        .ok_or_else(|| {
            UnitError::Numerical(format!(
                "{what}: the eigenvalues did not converge in {limit} iterations"
            ))
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn non_finite_matrices_are_refused_at_once() {
        let m = DMatrix::from_element(3, 3, f64::INFINITY);
        assert!(svd("test", m.clone()).is_err());
        assert!(complex_eigenvalues("test", m).is_err());
    }

    #[test]
    fn results_match_the_unbounded_calls() {
        let m = DMatrix::from_fn(4, 4, |r, c| {
            ((r * 7 + c * 3) % 5) as f64 + if r == c { 4.0 } else { 0.0 }
        });
        let ours = complex_eigenvalues("test", m.clone()).unwrap();
        assert_eq!(ours, m.clone().complex_eigenvalues());
        let b = DVector::from_element(4, 1.0);
        assert_eq!(
            least_squares("test", m.clone(), &b, 1e-14).unwrap(),
            m.svd(true, true).solve(&b, 1e-14).unwrap()
        );
    }
}
