//! The generalised symmetric eigenproblem K phi = w^2 M phi of a structure.

use crate::contract::UnitError;
use nalgebra::{DMatrix, DVector};

/// The `count` lowest eigenpairs (w^2, phi) of K phi = w^2 M phi, M positive
/// definite, by Cholesky reduction to a standard symmetric problem. A w^2 <= 0 is an
/// error naming `what` (a structure with a zero-stiffness mode).
pub fn lowest_modes(
    m: &DMatrix<f64>,
    k: &DMatrix<f64>,
    count: usize,
    what: &str,
) -> Result<Vec<(f64, DVector<f64>)>, UnitError> {
    let l = m
        .clone()
        .cholesky()
        .ok_or_else(|| UnitError::Numerical("mass matrix is not positive definite".into()))?
        .l();
    let linv = l
        .try_inverse()
        .ok_or_else(|| UnitError::Numerical("mass factor is singular".into()))?;
    let s = &linv * k * linv.transpose();
    let s = (&s + s.transpose()) * 0.5;
    let eig = crate::numerics::bounded::symmetric_eigen("modal analysis", s)?;
    let mut order: Vec<usize> = (0..eig.eigenvalues.len()).collect();
    order.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
    order
        .iter()
        .take(count)
        .map(|&i| {
            let w2 = eig.eigenvalues[i];
            if w2 <= 0.0 {
                return Err(UnitError::Numerical(format!(
                    "eigenvalue {w2:.3e} <= 0: {what}"
                )));
            }
            Ok((w2, linv.transpose() * eig.eigenvectors.column(i)))
        })
        .collect()
}
