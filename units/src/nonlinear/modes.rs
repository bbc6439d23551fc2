//! Modes of a nonlinear section about its current state (tangent stiffness,
//! the dynamics' mass, the kinematic end conditions held): what `Unit::modes`
//! reports and what a reduced section's basis starts from.

use super::NonlinearSection;
use crate::contract::{ModalAnalysis, Mode, UnitError};
use crate::numerics::banded::SymmetricBand;
use crate::numerics::subspace::lowest_banded_modes;

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
/// conditions held: by subspace iteration on the banded matrices, or, where
/// that gives up (repeated eigenvalues, a tangent not positive definite), by
/// the dense reduction (which names the zero-stiffness mode).
pub(super) fn free_modes(
    section: &NonlinearSection,
    k: &SymmetricBand,
    count: usize,
) -> Result<Vec<(f64, Vec<f64>)>, UnitError> {
    let held: Vec<usize> = section.held().map(|r| r.dof).collect();
    match lowest_banded_modes(k, &section.m, &held, count) {
        Some(modes) => Ok(modes),
        None => dense_modes(section, k, &held, count),
    }
}

/// As [`free_modes`], by the dense reduction of the free DOFs' matrices.
fn dense_modes(
    section: &NonlinearSection,
    k: &SymmetricBand,
    held: &[usize],
    count: usize,
) -> Result<Vec<(f64, Vec<f64>)>, UnitError> {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nonlinear::NonlinearParams;
    use crate::numerics::lanczos::largest_eigenvalue;
    use crate::{Driver, Time};

    /// A sagging 300 m pipe on 150 elements, pinned at both ends 280 m apart,
    /// in its static equilibrium: the banded path's modes are the dense
    /// reduction's to round-off.
    #[test]
    fn the_banded_modes_of_a_sagging_pipe_are_the_dense_ones() {
        let text = "static_start = true\nsegments = [{ length = 300.0, elements = 150, axial_stiffness = 4.0e9, bending_stiffness = 4.0e7, mass_per_length = 150.0, submerged_weight = 800.0 }]\nends.start = { kind = \"pinned\" }\nends.end = { kind = \"pinned\", x = { displacement = { offset = -20.0 } } }";
        let params: NonlinearParams = toml::from_str(text).expect("parameters");
        let mut driver = Driver::new(NonlinearSection::new(params).expect("section"));
        driver.initialize(Time::ZERO).expect("statics");
        let section = driver.unit();
        let k = section.tangent_stiffness();
        let held: Vec<usize> = section.held().map(|r| r.dof).collect();
        let banded = lowest_banded_modes(&k, &section.m, &held, 6).expect("converges");
        let dense = dense_modes(section, &k, &held, 6).expect("dense");
        // The dense reduction's eigenvalues are off by about eps times the
        // largest one (the axial modes, 8e7 1/s^2 here: 4e-9 of the lowest) where the subspace's
        // are relative to their own size (the spring chain's to 1e-11).
        let top = largest_eigenvalue(&k, &section.m, 1e-6, 200).expect("largest");
        for ((w2, phi), (d2, dphi)) in banded.iter().zip(&dense) {
            let round_off = f64::EPSILON * top.upper_bound / d2;
            assert!(
                (w2 / d2 - 1.0).abs() < 1e-10 + round_off,
                "{w2} against {d2}, {top:?}"
            );
            let sign = phi
                .iter()
                .zip(dphi)
                .map(|(a, b)| a * b)
                .sum::<f64>()
                .signum();
            let largest = dphi.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            let miss = phi
                .iter()
                .zip(dphi)
                .fold(0.0f64, |a, (x, y)| a.max((x - sign * y).abs()));
            assert!(
                miss < 1e-7 * largest,
                "shape off by {miss:e} of {largest:e}"
            );
        }
    }
}
