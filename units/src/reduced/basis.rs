//! Bases of a seed 002 section about its stress-free state (seed 002 ch. 4):
//! linear normal modes, modal derivatives in three forms, the Taylor basis's
//! columns and the linearly dependent derivatives among them.
//!
//! With modes phi_i (frequencies w_i, m_i = phi_i^T M phi_i) the derivatives are
//! - static: K0 x = -(dK_T/ds_j) phi_i (inertia dropped);
//! - modified (P2 eq. 36): the singular differentiated eigenproblem made
//!   regular by the restriction x^T phi_i = 0, a bordered system with
//!   K0 - w_i^2 M and right-hand side (m_i^-1 dk_i M - dK_T/ds_j) phi_i,
//!   dk_i = phi_i^T (dK_T/ds_j) phi_i;
//! - novel (P2 eq. 25, the Taylor expansion of the equations of motion):
//!   [K0 - (w_j + w_k)^2 M] x_jk = [m_j^-1 (phi_j^T K1(phi_k) phi_j -
//!   phi_j^T K1(phi_j) phi_k) M - K1(phi_k)] phi_j, x_jk the symmetric half sum
//!   (dphi_k/ds_j + dphi_j/ds_k) / 2.
//!
//! The Taylor basis's higher columns follow s_H = [s1 s1, s2 s1, s2 s2, s3 s1,
//! ...]: x_ii for i = j and 2 x_ij otherwise.

use super::polynomial::CubicSection;
use crate::contract::UnitError;
use crate::numerics::bounded::svd;
use crate::numerics::modal::lowest_modes;
use nalgebra::{DMatrix, DVector};

/// How mode shapes are scaled.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Normalisation {
    /// phi^T M phi = 1.
    Mass,
    /// phi^T K0 phi = 1 (amplitude proportional to 1 / omega: the scaling under
    /// which seed 002's cable shows its -3/8 and -1/4 dependence).
    Stiffness,
}

/// Which modal derivatives.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Derivative {
    /// Static modal derivatives (the mass term left out).
    Static,
    /// Modified modal derivatives (the mass term kept).
    Modified,
    /// Novel derivatives (the tangent's change along the mode, mass-orthogonalised).
    Novel,
}

/// The lowest linear normal modes about the stress-free state: circular
/// frequencies (rad/s) and shapes on the free DOFs, each signed so that its
/// first clearly nonzero entry is positive.
#[derive(Clone, Debug)]
pub struct LinearModes {
    /// Angular frequencies (rad/s), increasing.
    pub omegas: Vec<f64>,
    /// The mode shapes, one per frequency.
    pub shapes: Vec<DVector<f64>>,
}

/// The `count` lowest modes of K0 and M, scaled by `normalisation`.
pub fn linear_modes(
    section: &CubicSection,
    count: usize,
    normalisation: Normalisation,
) -> Result<LinearModes, UnitError> {
    shifted_modes(section, count, normalisation, 0.0)
}

/// The same for a section with rigid-body motion (free-free parts): the
/// lowest modes of (K0 + shift M) phi = lambda M phi, omega^2 = lambda - shift
/// (seed 002 T eqs. 5.10-5.11), so zero-frequency modes come out too. `shift`
/// (1/s^2) should be of the order of the first flexible omega^2. Rigid-body
/// modes can only be mass-normalised.
pub fn shifted_modes(
    section: &CubicSection,
    count: usize,
    normalisation: Normalisation,
    shift: f64,
) -> Result<LinearModes, UnitError> {
    if !(shift.is_finite() && shift >= 0.0) {
        return Err(UnitError::parameter(
            "shift",
            shift,
            "expected a finite value >= 0",
        ));
    }
    let shifted = &section.k0 + &section.mass * shift;
    let pairs = lowest_modes(&section.mass, &shifted, count, "the section is not held")?;
    let mut modes = LinearModes {
        omegas: Vec::new(),
        shapes: Vec::new(),
    };
    for (lambda, phi) in pairs {
        let w2 = (lambda - shift).max(0.0);
        let scale = match normalisation {
            Normalisation::Mass => 1.0,
            Normalisation::Stiffness if w2 > 0.0 => 1.0 / w2.sqrt(),
            Normalisation::Stiffness => {
                return Err(UnitError::parameter(
                    "normalisation",
                    "stiffness",
                    "expected mass normalisation: a rigid-body mode has no stiffness",
                ));
            }
        };
        let largest = phi.amax();
        let sign = phi
            .iter()
            .find(|v| v.abs() > 1e-6 * largest)
            .map_or(1.0, |v| v.signum());
        modes.omegas.push(w2.sqrt());
        modes.shapes.push(phi * (scale * sign));
    }
    Ok(modes)
}

/// Load-dependent Ritz vectors (Wilson, Yuan and Dickens 1982; seed 002 T sec.
/// 4.1.2): psi_1 = K^-1 f, then K psi* = M psi_i, each M-orthogonalised against
/// every earlier vector (twice, for round-off) and M-normalised. K is K0 +
/// `shift` M (a shift for sections with rigid-body motion; 0 otherwise).
pub fn ritz_vectors(
    section: &CubicSection,
    load: &DVector<f64>,
    count: usize,
    shift: f64,
) -> Result<Vec<DVector<f64>>, UnitError> {
    let k = &section.k0 + &section.mass * shift;
    let factor = k.cholesky().ok_or_else(|| {
        UnitError::Numerical(
            "Ritz vectors: K is not positive definite (a free-free section needs a shift)".into(),
        )
    })?;
    let m = &section.mass;
    let mut vectors: Vec<DVector<f64>> = Vec::with_capacity(count);
    let mut next = factor.solve(load);
    for i in 0..count {
        for _ in 0..2 {
            for q in &vectors {
                let c = q.dot(&(m * &next));
                next.axpy(-c, q, 1.0);
            }
        }
        let norm = next.dot(&(m * &next)).sqrt();
        if !(norm.is_finite() && norm > 0.0) {
            return Err(UnitError::Numerical(format!(
                "Ritz vector {}: nothing left after orthogonalisation (the load excites fewer shapes)",
                i + 1
            )));
        }
        let psi = next / norm;
        next = factor.solve(&(m * &psi));
        vectors.push(psi);
    }
    Ok(vectors)
}

/// Attachment vectors (static modes, the residual flexibility a truncated modal
/// basis lacks at concentrated loads): for each free DOF in `loaded` (indices
/// of the section's free DOFs), K0^-1 e, M-orthogonalised against `basis` and
/// the earlier ones (twice, for round-off) and M-normalised. A vector whose
/// M-norm falls below 1e-8 of its own before orthogonalisation lies in the span
/// already and is left out. A section with rigid-body motion has no K0^-1.
pub fn attachment_vectors(
    section: &CubicSection,
    loaded: &[usize],
    basis: &[DVector<f64>],
) -> Result<Vec<DVector<f64>>, UnitError> {
    let factor = section.k0.clone().cholesky().ok_or_else(|| {
        UnitError::Numerical(
            "attachment vectors: K0 is not positive definite (the section moves as a rigid body under its end loads: hold it where it is not loaded)".into(),
        )
    })?;
    let m = &section.mass;
    let mut vectors: Vec<DVector<f64>> = Vec::with_capacity(loaded.len());
    for &dof in loaded {
        let mut next = factor.solve(&DVector::from_fn(section.size(), |i, _| {
            f64::from(u8::from(i == dof))
        }));
        let before = next.dot(&(m * &next)).sqrt();
        for _ in 0..2 {
            for q in basis.iter().chain(&vectors) {
                let c = q.dot(&(m * &next)) / q.dot(&(m * q));
                next.axpy(-c, q, 1.0);
            }
        }
        let norm = next.dot(&(m * &next)).sqrt();
        if norm > 1e-8 * before {
            vectors.push(next / norm);
        }
    }
    Ok(vectors)
}

/// The highest angular frequency (rad/s) of K0 and M restricted to the span
/// of `columns` (free DOFs x n): 2 / omega is central differences' critical
/// step on them.
pub fn highest_frequency(section: &CubicSection, columns: &DMatrix<f64>) -> Result<f64, UnitError> {
    let k = columns.tr_mul(&(&section.k0 * columns));
    let m = columns.tr_mul(&(&section.mass * columns));
    let l = m.cholesky().ok_or_else(|| {
        UnitError::Numerical(
            "reduced basis: the reduced mass is not positive definite (dependent columns)".into(),
        )
    })?;
    let l = l.l();
    let inverse = l.clone().try_inverse().ok_or_else(|| {
        UnitError::Numerical("reduced basis: the reduced mass is singular".into())
    })?;
    let a = &inverse * k * inverse.transpose();
    let a = (&a + a.transpose()) * 0.5;
    let largest = a
        .symmetric_eigenvalues()
        .iter()
        .fold(0.0f64, |x, &y| x.max(y));
    Ok(largest.max(0.0).sqrt())
}

/// The modal derivative of `kind` for the mode pair (i, j), 0-based: for
/// `Novel` the symmetric x_ij with the equation written for (j, k) = (i, j).
pub fn derivative(
    section: &CubicSection,
    modes: &LinearModes,
    kind: Derivative,
    i: usize,
    j: usize,
) -> Result<DVector<f64>, UnitError> {
    let count = modes.shapes.len();
    if i >= count || j >= count {
        return Err(UnitError::parameter(
            "mode pair",
            format!("({i}, {j})"),
            &format!("expected indices below the {count} modes"),
        ));
    }
    let (phi_i, phi_j) = (&modes.shapes[i], &modes.shapes[j]);
    let (w_i, w_j) = (modes.omegas[i], modes.omegas[j]);
    let solve = |a: DMatrix<f64>, b: DVector<f64>| {
        a.lu().solve(&b).ok_or_else(|| {
            UnitError::Numerical(format!(
                "modal derivative ({i}, {j}): the operator is singular (an internal resonance?)"
            ))
        })
    };
    match kind {
        Derivative::Static => solve(
            section.k0.clone(),
            -section.tangent_derivative(phi_j, phi_i),
        ),
        Derivative::Modified => {
            let n = section.size();
            let dk_phi = section.tangent_derivative(phi_j, phi_i);
            let m_i = (phi_i.transpose() * &section.mass * phi_i)[0];
            let dk = phi_i.dot(&dk_phi);
            let rhs_top = &section.mass * phi_i * (dk / m_i) - dk_phi;
            let mut a = DMatrix::zeros(n + 1, n + 1);
            a.view_mut((0, 0), (n, n))
                .copy_from(&(&section.k0 - &section.mass * (w_i * w_i)));
            a.view_mut((0, n), (n, 1)).copy_from(phi_i);
            a.view_mut((n, 0), (1, n)).copy_from(&phi_i.transpose());
            let mut b = DVector::zeros(n + 1);
            b.rows_mut(0, n).copy_from(&rhs_top);
            Ok(solve(a, b)?.rows(0, n).into_owned())
        }
        Derivative::Novel => {
            // (j, k) of the equation = (i, j) here.
            let (phi_a, phi_b, w_a, w_b) = (phi_i, phi_j, w_i, w_j);
            let m_a = (phi_a.transpose() * &section.mass * phi_a)[0];
            let k1_b_a = section.k1(phi_b, phi_a);
            let coefficient = (phi_a.dot(&k1_b_a) - phi_a.dot(&section.k1(phi_a, phi_b))) / m_a;
            let rhs = &section.mass * phi_a * coefficient - k1_b_a;
            let w = w_a + w_b;
            solve(&section.k0 - &section.mass * (w * w), rhs)
        }
    }
}

/// The Taylor basis's higher columns for the first `n` modes, in the order of
/// s_H = [s1 s1, s2 s1, s2 s2, s3 s1, ...]: x_ii, and 2 x_ij for i > j.
pub fn derivative_columns(
    section: &CubicSection,
    modes: &LinearModes,
    kind: Derivative,
    n: usize,
) -> Result<Vec<DVector<f64>>, UnitError> {
    let mut columns = Vec::with_capacity(n * (n + 1) / 2);
    for i in 0..n {
        for j in 0..=i {
            let x = derivative(section, modes, kind, i, j)?;
            columns.push(if i == j { x } else { x * 2.0 });
        }
    }
    Ok(columns)
}

/// Linearly dependent columns by seed 002's SVD test, with every column scaled
/// to unit norm: as many columns depend on the others as the matrix has
/// singular values below `tolerance` (0 for an exact dependence, 1 for
/// orthogonal columns). Which ones: removed one at a time from the columns at
/// `from` on (the earlier ones, e.g. the modes, are kept), each time the one
/// whose removal leaves the largest smallest singular value (the latest on a
/// tie). Returns their indices, increasing.
pub fn dependent_columns(
    columns: &[DVector<f64>],
    tolerance: f64,
    from: usize,
) -> Result<Vec<usize>, UnitError> {
    if columns.is_empty() {
        return Ok(Vec::new());
    }
    let unit: Vec<DVector<f64>> = columns
        .iter()
        .map(|c| c / c.norm().max(f64::MIN_POSITIVE))
        .collect();
    let singular = |keep: &[usize]| -> Result<DVector<f64>, UnitError> {
        let m = DMatrix::from_columns(&keep.iter().map(|&k| unit[k].clone()).collect::<Vec<_>>());
        Ok(svd("dependent modal derivatives", m)?.singular_values)
    };
    let mut keep: Vec<usize> = (0..columns.len()).collect();
    let count = singular(&keep)?.iter().filter(|&&s| s < tolerance).count();
    let mut dependent = Vec::new();
    for _ in 0..count {
        let mut best: Option<(f64, usize)> = None;
        for (position, &k) in keep.iter().enumerate().filter(|(_, k)| **k >= from) {
            if keep.len() == 1 {
                break;
            }
            let mut rest = keep.clone();
            rest.remove(position);
            let smallest = singular(&rest)?.min();
            if best.is_none_or(|(s, _)| smallest >= s) {
                best = Some((smallest, k));
            }
        }
        let Some((_, k)) = best else { break };
        keep.retain(|&j| j != k);
        dependent.push(k);
    }
    dependent.sort_unstable();
    Ok(dependent)
}
