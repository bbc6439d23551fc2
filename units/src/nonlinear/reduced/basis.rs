//! The reduced section's basis about its start state q_s: the lowest modes
//! of the tangent K_t with the held DOFs fixed, an attachment vector per end
//! DOF loaded by a force, the static modal derivatives of the modes and the
//! constraint modes (what carries a transverse motion's axial stretch: without
//! them a stiff pipe's rotating modes strain it spuriously, the membrane
//! locking of linear bases), and a constraint mode per held DOF, last.

use super::super::NonlinearSection;
use super::products::dot;
use crate::contract::UnitError;
use crate::numerics::banded::{BandLdlt, SymmetricBand};

/// Relative size below which a basis vector is taken as dependent on the
/// ones before it (after orthogonalisation) and left out.
const DEPENDENCE: f64 = 1e-9;

/// The smallest singular value, relative to the largest, of the modal
/// derivatives' principal directions kept in the basis.
const DERIVATIVE_SHARE: f64 = 1e-5;

/// The displacement (m or rad, on columns scaled to a largest entry of 1) of
/// the second differences that give the modal derivatives.
const PROBE: f64 = 1e-3;

/// The basis, column-major (n x m): free columns, then one constraint column
/// per DOF of `held` in that order.
pub(super) fn columns(
    section: &NonlinearSection,
    k: &SymmetricBand,
    count: usize,
    held: &[usize],
) -> Result<Vec<f64>, UnitError> {
    let n = k.size();
    let mut with_held = k.clone();
    for &d in held {
        with_held.set_identity_row(d);
    }
    let factor = BandLdlt::new(&with_held).ok_or_else(|| {
        UnitError::Numerical(
            "reduced section: the tangent stiffness at the start is singular with its ends held"
                .into(),
        )
    })?;
    let mut modes: Vec<Vec<f64>> = super::super::modes::free_modes(section, k, count)?
        .into_iter()
        .map(|(_, shape)| scaled(shape))
        .collect();
    let constraints: Vec<Vec<f64>> = held
        .iter()
        .map(|&d| {
            // K_ff x_f = -K_fd with x_d = 1 and the other held DOFs at 0.
            let mut x: Vec<f64> = (0..n).map(|i| -k.get(i, d)).collect();
            held.iter().for_each(|&h| x[h] = 0.0);
            x[d] = 1.0;
            factor.solve_in_place(&mut x);
            x
        })
        .collect();
    let mut free = Vec::new();
    for d in section.loaded_end_dofs() {
        let mut x = vec![0.0; n];
        x[d] = 1.0;
        factor.solve_in_place(&mut x);
        free.push(x);
    }
    let moving: Vec<&Vec<f64>> = modes.iter().chain(&constraints).collect();
    let mut derivatives = Vec::new();
    for (i, a) in moving.iter().enumerate() {
        for b in &moving[i..] {
            let mut x = second_difference(section, a, b);
            held.iter().for_each(|&h| x[h] = 0.0);
            factor.solve_in_place(&mut x);
            derivatives.push(x);
        }
    }
    free.extend(principal_directions(derivatives, n));
    modes.append(&mut free);
    let mut basis = independent(modes, n);
    constraints.iter().for_each(|c| basis.extend(c));
    Ok(basis)
}

/// The static restoring force's second derivative along `a` and `b` at the
/// start state (elements and seabed, no drag), by central differences.
fn second_difference(section: &NonlinearSection, a: &[f64], b: &[f64]) -> Vec<f64> {
    let n = a.len();
    let zeros = vec![0.0; n];
    let mut out = vec![0.0; n];
    let mut q = vec![0.0; n];
    for (sa, sb, sign) in [
        (1.0, 1.0, 1.0),
        (1.0, -1.0, -1.0),
        (-1.0, 1.0, -1.0),
        (-1.0, -1.0, 1.0),
    ] {
        for i in 0..n {
            q[i] = section.state.q[i] + PROBE * (sa * a[i] + sb * b[i]);
        }
        let scale = sign / (4.0 * PROBE * PROBE);
        section.model.add_internal_force(&q, scale, None, &mut out);
        if !section.environment.is_empty() {
            let at = (q.as_slice(), zeros.as_slice(), section.state.t);
            let lambda = &section.state.lambda;
            section
                .environment
                .add_force(&section.model, at, lambda, scale, false, None, &mut out);
        }
    }
    // The derivative is -K_t^-1 of it.
    out.iter_mut().for_each(|x| *x = -*x);
    out
}

/// The derivatives' principal directions (left singular vectors) down to
/// `DERIVATIVE_SHARE` of the largest singular value: the derivatives of k
/// moving columns are k (k + 1) / 2 vectors, most of them nearly parallel
/// (the axial stretch of turning), and a basis of all would cost O(k^4) a
/// step. Each derivative enters at its own size (the displacement per unit
/// products of columns scaled to a largest entry of 1 m or rad).
fn principal_directions(derivatives: Vec<Vec<f64>>, n: usize) -> Vec<Vec<f64>> {
    if derivatives.is_empty() {
        return Vec::new();
    }
    let d = nalgebra::DMatrix::from_fn(n, derivatives.len(), |i, j| derivatives[j][i]);
    let svd = d.svd(true, false);
    let (Some(u), values) = (svd.u, svd.singular_values) else {
        return Vec::new();
    };
    let largest = values.iter().fold(0.0f64, |a, &v| a.max(v));
    (0..values.len())
        .filter(|&k| largest > 0.0 && values[k] > DERIVATIVE_SHARE * largest)
        .map(|k| u.column(k).iter().copied().collect())
        .collect()
}

/// `v` scaled to a largest entry of 1.
fn scaled(mut v: Vec<f64>) -> Vec<f64> {
    let largest = v.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    if largest > 0.0 {
        v.iter_mut().for_each(|x| *x /= largest);
    }
    v
}
/// The columns orthogonalised in order (Gram-Schmidt, twice), those dependent
/// on the ones before left out, each scaled to a largest entry of 1; as one
/// column-major block.
fn independent(columns: Vec<Vec<f64>>, n: usize) -> Vec<f64> {
    let mut kept: Vec<Vec<f64>> = Vec::new();
    for mut c in columns {
        let size = norm(&c);
        for _ in 0..2 {
            for k in &kept {
                let along = dot(&c, k) / dot(k, k);
                c.iter_mut().zip(k).for_each(|(x, y)| *x -= along * y);
            }
        }
        if norm(&c) > DEPENDENCE * size {
            kept.push(scaled(c));
        }
    }
    let mut basis = Vec::with_capacity(n * kept.len());
    kept.iter().for_each(|c| basis.extend(c));
    basis
}

fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}
