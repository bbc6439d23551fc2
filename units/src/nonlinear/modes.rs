//! Modes of a nonlinear section about its current state (tangent stiffness,
//! the dynamics' mass, the kinematic end conditions held): what `Unit::modes`
//! reports and what a reduced section's basis starts from.

use super::NonlinearSection;
use crate::contract::{ModalAnalysis, Mode, UnitError};
use crate::numerics::banded::SymmetricBand;

/// Modes about the current state (tangent stiffness, the dynamics' mass) with the
/// kinematic end conditions held, longest period first.
pub(super) fn modes(section: &NonlinearSection, count: usize) -> Result<ModalAnalysis, UnitError> {
    let k = section.tangent_stiffness();
    let mut modes = Vec::new();
    for (w2, full) in free_modes(section, &k, count)? {
        let scale = full
            .chunks(3)
            .fold(0.0f64, |a, c| a.max(c[0].abs()).max(c[1].abs()))
            .max(1e-300);
        modes.push(Mode {
            period: 2.0 * std::f64::consts::PI / w2.sqrt(),
            shape: full
                .chunks(3)
                .map(|c| [c[0] / scale, c[1] / scale])
                .collect(),
        });
    }
    Ok(ModalAnalysis {
        positions: section.positions(),
        modes,
    })
}

/// The `count` lowest modes (w^2 in 1/s^2, shape over all DOFs, zero at the
/// held ones) of the tangent `k` and the dynamics' mass, the kinematic end
/// conditions held.
pub(super) fn free_modes(
    section: &NonlinearSection,
    k: &SymmetricBand,
    count: usize,
) -> Result<Vec<(f64, Vec<f64>)>, UnitError> {
    let held: Vec<usize> = section.held().map(|r| r.dof).collect();
    let n = section.model.dofs();
    let free: Vec<usize> = (0..n).filter(|d| !held.contains(d)).collect();
    let pick = |m: &SymmetricBand| {
        nalgebra::DMatrix::from_fn(free.len(), free.len(), |i, j| m.get(free[i], free[j]))
    };
    let (m, k) = (pick(&section.m), pick(k));
    let modes = crate::numerics::modal::lowest_modes(
        &m,
        &k,
        count,
        "the section has a zero-stiffness mode",
    )?;
    Ok(modes
        .into_iter()
        .map(|(w2, phi)| {
            let mut full = vec![0.0; n];
            for (a, &d) in free.iter().enumerate() {
                full[d] = phi[a];
            }
            (w2, full)
        })
        .collect())
}
