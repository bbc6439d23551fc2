//! The statics of a body on anchored lines: the offset (surge, sway, heave,
//! roll, pitch, yaw) at which the body's weight, buoyancy, restoring and
//! mean load balance the lines' pull, and the mooring's 6x6 stiffness there.
//!
//! Each line is its elastic catenary from its anchor ([`CatenarySection`]:
//! weight, EA and a seabed at the anchor's level; no bending, current or
//! seabed friction), as MoorPy's quasi-static model has it: the closed form
//! makes the equilibrium and the stiffness cheap enough to solve on every
//! scene load, and comparable with MoorPy to its solver's tolerance. A line
//! modelled dynamically (`line3d`) then solves its own statics with its end
//! at the fairlead so found.

use super::dynamics::{Model, Motion};
use super::params::BodyParams;
use crate::contract::UnitError;
use crate::line3d::catenary_section::CatenarySection;
use nalgebra::{Matrix6, UnitQuaternion, Vector3, Vector6};

/// A line from its anchor to fairlead `fairlead` of the body.
pub struct MooredLine {
    /// The index of the body's fairlead it hangs from.
    pub fairlead: usize,
    /// The line as its catenary from the anchor (its start).
    pub line: CatenarySection,
}

/// The body's static equilibrium on its lines.
#[derive(Clone, Debug, PartialEq)]
pub struct MooringStatics {
    /// The body's displacement from rest (m, rad).
    pub offset: [f64; 6],
    /// Each line's pull on the body at its fairlead (N, global).
    pub fairlead_forces: Vec<[f64; 3]>,
    /// The mooring's stiffness about the reference point: minus the
    /// derivative of the lines' load by the offset (N/m, N/rad, N m/m, N m/rad).
    pub stiffness: [[f64; 6]; 6],
    /// Newton iterations taken.
    pub iterations: u32,
}

/// The body at `offset` from its rest position, at rest.
fn pose(model: &Model, offset: &Vector6<f64>) -> Motion {
    Motion {
        position: model.reference + Vector3::new(offset[0], offset[1], offset[2]),
        rotation: UnitQuaternion::from_euler_angles(offset[3], offset[4], offset[5]),
        velocity: Vector6::zeros(),
    }
}

/// The global position (m) of fairlead `k` of a body at `offset`.
pub fn fairlead_position(body: &BodyParams, k: usize, offset: &[f64; 6]) -> [f64; 3] {
    let model = Model::new(body);
    let m = pose(&model, &Vector6::from(*offset));
    (m.position + m.rotation * model.fairleads[k]).into()
}

/// Each line's pull (N) on the body at `offset`.
fn line_forces(
    model: &Model,
    lines: &[MooredLine],
    offset: &Vector6<f64>,
) -> Result<Vec<[f64; 3]>, UnitError> {
    let m = pose(model, offset);
    lines
        .iter()
        .map(|l| {
            let at = m.position + m.rotation * model.fairleads[l.fairlead];
            l.line.end_force(&at.into())
        })
        .collect()
}

/// The lines' load at the reference point (N, N m) at `offset`.
fn mooring_load(
    model: &Model,
    lines: &[MooredLine],
    offset: &Vector6<f64>,
    forces: &mut [f64],
) -> Result<Vector6<f64>, UnitError> {
    forces.fill(0.0);
    for (l, f) in lines.iter().zip(line_forces(model, lines, offset)?) {
        for c in 0..3 {
            forces[3 * l.fairlead + c] += f[c];
        }
    }
    Ok(model.fairlead_loads(&pose(model, offset), forces))
}

/// The sum of every static load on the body at `offset` (N, N m).
fn residual(
    model: &Model,
    lines: &[MooredLine],
    offset: &Vector6<f64>,
    forces: &mut [f64],
) -> Result<Vector6<f64>, UnitError> {
    mooring_load(model, lines, offset, forces)?;
    model.loads(&pose(model, offset), forces, &Vector6::zeros())
}

/// Central differences of `f` by the offset: 1 mm and 1e-5 rad.
fn derivative(
    offset: &Vector6<f64>,
    mut f: impl FnMut(&Vector6<f64>) -> Result<Vector6<f64>, UnitError>,
) -> Result<Matrix6<f64>, UnitError> {
    let mut d = Matrix6::zeros();
    for j in 0..6 {
        let delta = if j < 3 { 1e-3 } else { 1e-5 };
        let (mut plus, mut minus) = (*offset, *offset);
        plus[j] += delta;
        minus[j] -= delta;
        d.set_column(j, &((f(&plus)? - f(&minus)?) / (2.0 * delta)));
    }
    Ok(d)
}

/// The mooring's stiffness at `offset` (N/m, N/rad, N m/m, N m/rad).
pub fn mooring_stiffness(
    body: &BodyParams,
    lines: &[MooredLine],
    offset: &[f64; 6],
) -> Result<[[f64; 6]; 6], UnitError> {
    let model = Model::new(body);
    let mut forces = vec![0.0; 3 * body.fairleads.len()];
    let d = derivative(&Vector6::from(*offset), |o| {
        mooring_load(&model, lines, o, &mut forces)
    })?;
    Ok(std::array::from_fn(|i| std::array::from_fn(|j| -d[(i, j)])))
}

/// The body's equilibrium on `lines` by Newton from rest (at most 100
/// iterations; a step limited to 10 m and 0.1 rad), to a load below 1e-9
/// of the body's weight.
pub fn equilibrium(body: &BodyParams, lines: &[MooredLine]) -> Result<MooringStatics, UnitError> {
    let model = Model::new(body);
    let mut forces = vec![0.0; 3 * body.fairleads.len()];
    let scale = (body.mass * body.gravity).max(1.0);
    let mut offset = Vector6::zeros();
    for iteration in 1..=100 {
        let r = residual(&model, lines, &offset, &mut forces)?;
        if r.fixed_rows::<3>(0).amax() < 1e-9 * scale && r.fixed_rows::<3>(3).amax() < 1e-9 * scale
        {
            return Ok(MooringStatics {
                offset: offset.into(),
                fairlead_forces: line_forces(&model, lines, &offset)?,
                stiffness: mooring_stiffness(body, lines, &offset.into())?,
                iterations: iteration,
            });
        }
        let jacobian = derivative(&offset, |o| residual(&model, lines, o, &mut forces))?;
        let step = jacobian.lu().solve(&r).ok_or_else(|| {
            UnitError::Numerical(
                "the moored body's statics: a degree of freedom nothing restores (give the body a hydrostatic or additional stiffness, or lines that hold it)".into(),
            )
        })?;
        let limit = (step.fixed_rows::<3>(0).amax() / 10.0)
            .max(step.fixed_rows::<3>(3).amax() / 0.1)
            .max(1.0);
        offset -= step / limit;
    }
    Err(UnitError::Numerical(
        "the moored body's statics did not converge in 100 Newton iterations".into(),
    ))
}

/// The lines' load on the body at the reference point (N, N m) and each
/// line's tension at its fairlead (N), the body at `offset` (m, rad).
pub fn mooring_state(
    body: &BodyParams,
    lines: &[MooredLine],
    offset: &[f64; 6],
) -> Result<([f64; 6], Vec<f64>), UnitError> {
    let model = Model::new(body);
    let offset = Vector6::from(*offset);
    let mut forces = vec![0.0; 3 * body.fairleads.len()];
    let load = mooring_load(&model, lines, &offset, &mut forces)?;
    let tensions = line_forces(&model, lines, &offset)?
        .iter()
        .map(|f| Vector3::from(*f).norm())
        .collect();
    Ok((load.into(), tensions))
}

/// A mode of the moored body about its equilibrium.
#[derive(Clone, Debug, PartialEq)]
pub struct RigidMode {
    /// Undamped natural period (s); infinite where nothing restores it.
    pub period: f64,
    /// The degree of freedom it moves most (0-5: surge to yaw): the largest
    /// `x_d^2 M_dd` of its shape `x`.
    pub dominant: usize,
}

/// The moored body's undamped modes about `offset`, longest period first:
/// the generalised eigenproblem of the whole restoring (weight, buoyancy,
/// hydrostatics, springs and lines; its symmetric part) and the mass with
/// the added mass.
pub fn natural_modes(
    body: &BodyParams,
    lines: &[MooredLine],
    offset: &[f64; 6],
) -> Result<Vec<RigidMode>, UnitError> {
    let model = Model::new(body);
    let mut forces = vec![0.0; 3 * body.fairleads.len()];
    let at = Vector6::from(*offset);
    let k = -derivative(&at, |o| residual(&model, lines, o, &mut forces))?;
    let k = (k + k.transpose()) * 0.5;
    let mass = model.mass_matrix(&pose(&model, &at).rotation);
    let l = nalgebra::Cholesky::new(mass)
        .ok_or_else(|| {
            UnitError::Numerical("the body's mass matrix is not positive definite".into())
        })?
        .l();
    let l_inv = l
        .try_inverse()
        .ok_or_else(|| UnitError::Numerical("the body's mass matrix is singular".into()))?;
    let eigen = nalgebra::SymmetricEigen::new(l_inv * k * l_inv.transpose());
    let mut modes: Vec<RigidMode> = (0..6)
        .map(|i| {
            let x = l_inv.transpose() * eigen.eigenvectors.column(i);
            let shares: Vec<f64> = (0..6).map(|d| x[d] * x[d] * mass[(d, d)]).collect();
            let dominant = (0..6)
                .max_by(|&a, &b| shares[a].total_cmp(&shares[b]))
                .unwrap_or(0);
            let w2 = eigen.eigenvalues[i];
            RigidMode {
                period: if w2 > 0.0 {
                    2.0 * std::f64::consts::PI / w2.sqrt()
                } else {
                    f64::INFINITY
                },
                dominant,
            }
        })
        .collect();
    modes.sort_by(|a, b| b.period.total_cmp(&a.period));
    Ok(modes)
}
