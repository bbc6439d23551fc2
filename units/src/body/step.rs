//! One step of the body's dynamics: the trapezoidal rule (Newmark's average
//! acceleration) on the velocity, the position moved by the mean velocity
//! and the rotation by the mean angular velocity's exponential map, solved
//! for the step's end velocity by Newton (its 6x6 Jacobian by differences).
//! Second order, no numerical damping, unconditionally stable for the linear
//! oscillator: a free body keeps its energy to the order of the step.

use super::dynamics::{Model, Motion};
use crate::contract::UnitError;
use nalgebra::{Matrix6, UnitQuaternion, Vector3, Vector6};

/// The body's motion and acceleration at one time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Kinematics {
    pub motion: Motion,
    /// (m/s^2, rad/s^2), global axes.
    pub acceleration: Vector6<f64>,
}

/// The loads a step's end sees: the fairleads' forces (N, x y z each) and
/// the external load at the reference point (N, N m).
pub(crate) struct EndLoads<'a> {
    pub forces: &'a [f64],
    pub external: Vector6<f64>,
}

/// The motion at the step's end for an end velocity `u1` from `start` over `h` (s).
pub(super) fn moved(start: &Motion, u1: &Vector6<f64>, h: f64) -> Motion {
    let mean = (start.velocity + u1) * 0.5;
    let spin = Vector3::new(mean[3], mean[4], mean[5]) * h;
    Motion {
        position: start.position + Vector3::new(mean[0], mean[1], mean[2]) * h,
        rotation: UnitQuaternion::from_scaled_axis(spin) * start.rotation,
        velocity: *u1,
    }
}

/// The trapezoidal rule's residual at the end velocity `u1`, and the end's
/// motion and acceleration.
pub(super) fn residual(
    model: &Model,
    start: &Kinematics,
    u1: &Vector6<f64>,
    h: f64,
    loads: &EndLoads<'_>,
) -> Result<(Vector6<f64>, Kinematics), UnitError> {
    let motion = moved(&start.motion, u1, h);
    let a1 = model.acceleration(&motion, loads.forces, &loads.external)?;
    let r = u1 - start.motion.velocity - (start.acceleration + a1) * (0.5 * h);
    Ok((
        r,
        Kinematics {
            motion,
            acceleration: a1,
        },
    ))
}

/// Advances `start` over `h` (s) to the step's end under `loads`; returns
/// the end's kinematics and the Newton iterations taken (at most `max`).
pub(crate) fn advance(
    model: &Model,
    start: &Kinematics,
    h: f64,
    loads: &EndLoads<'_>,
    max: u32,
) -> Result<(Kinematics, u32), UnitError> {
    let mut u1 = start.motion.velocity + start.acceleration * h;
    let scale = |u: &Vector6<f64>, a: &Vector6<f64>| u.amax() + h * a.amax();
    for iteration in 1..=max {
        let (r, end) = residual(model, start, &u1, h, loads)?;
        let jacobian = residual_jacobian(model, start, &u1, h, loads, &r)?;
        let delta = jacobian.lu().solve(&r).ok_or_else(|| {
            UnitError::Numerical("the body's step: a singular Newton matrix".into())
        })?;
        u1 -= delta;
        let size =
            scale(&u1, &end.acceleration).max(scale(&start.motion.velocity, &start.acceleration));
        // Relative to the motion, with a floor of 1e-13 h m/s where it is
        // at rest (the loads' rounding).
        if delta.amax() <= 1e-13 * (size + h) {
            let (_, end) = residual(model, start, &u1, h, loads)?;
            crate::contract::require_finite_state(
                "the body's motion",
                end.acceleration.as_slice(),
            )?;
            return Ok((end, iteration));
        }
    }
    Err(UnitError::Numerical(format!(
        "the body's step did not converge in {max} Newton iterations (raise `max_iterations` or shorten the step)"
    )))
}

/// d residual / d u1 by forward differences.
fn residual_jacobian(
    model: &Model,
    start: &Kinematics,
    u1: &Vector6<f64>,
    h: f64,
    loads: &EndLoads<'_>,
    r: &Vector6<f64>,
) -> Result<Matrix6<f64>, UnitError> {
    let mut jacobian = Matrix6::zeros();
    for j in 0..6 {
        let delta = 1e-7 * (1.0 + u1[j].abs());
        let mut moved = *u1;
        moved[j] += delta;
        let (rj, _) = residual(model, start, &moved, h, loads)?;
        jacobian.set_column(j, &((rj - r) / delta));
    }
    Ok(jacobian)
}
