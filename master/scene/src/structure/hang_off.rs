//! The hang-off of a structure's top given by its angle: `[structure] hang_off
//! = { angle_deg = 12.0 }` places the structure's end (its top) horizontally so
//! that, in the static equilibrium, the pipe's tangent there is `angle`
//! degrees from the vertical (a riser's hang-off angle), at the height the
//! scene gives it. The end's x displacement offset is found by the secant
//! method on the equilibrium's angle (at most `MAX_SOLVES` static solves, to
//! `TOLERANCE_DEG`) and written into the model, so every section, the twin
//! and the dynamics start from that top.

use super::statics::Equilibrium;
use serde::Deserialize;
use slender_units::Time;
use slender_units::beam::boundary::TimeFunction;
use slender_units::nonlinear::NonlinearParams;
use slender_units::nonlinear::params::{DofCondition, End, EndKind};

/// Static solves of the search, at most.
const MAX_SOLVES: usize = 40;
/// The angle's tolerance (deg).
const TOLERANCE_DEG: f64 = 1e-6;

/// `structure.hang_off` as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct HangOff {
    /// The pipe tangent's angle from the vertical at the top (deg).
    angle_deg: f64,
}

impl HangOff {
    /// The requested hang-off angle (deg from the vertical), checked.
    pub(super) fn angle(&self) -> Result<f64, String> {
        let angle = self.angle_deg;
        if !(angle > 0.0 && angle < 90.0) {
            return Err(format!(
                "`structure.hang_off.angle_deg` = {angle}: expected an angle between 0 and 90 deg from the vertical"
            ));
        }
        Ok(angle)
    }
}

/// Moves the end of `model` (the structure's `model` table, solved for its
/// statics) horizontally until its equilibrium at `t0` has its tangent
/// `angle` (deg) from the vertical; returns the shift (m) and that equilibrium.
pub(super) fn place(
    model: &mut NonlinearParams,
    angle: f64,
    t0: Time,
) -> Result<(f64, Equilibrium), String> {
    let length = model.length();
    let solve = |shift: f64, model: &NonlinearParams| -> Result<(f64, Equilibrium), String> {
        let mut trial = model.clone();
        end_offset(&mut trial, shift)?;
        let equilibrium = Equilibrium::solve(&trial, t0).map_err(|e| {
            format!("`structure.hang_off`: with the top moved by {shift:.4} m in x: {e}")
        })?;
        Ok((equilibrium.end_angle_from_vertical() - angle, equilibrium))
    };
    // Secant on the shift, each step at most a tenth of the structure's length.
    let step_limit = 0.1 * length;
    let (mut x0, (mut f0, mut best)) = (0.0, solve(0.0, model)?);
    let mut x1 = 1e-3 * length;
    for _ in 1..MAX_SOLVES {
        let (f1, equilibrium) = solve(x1, model)?;
        if f1.abs() < TOLERANCE_DEG {
            end_offset(model, x1)?;
            return Ok((x1, equilibrium));
        }
        best = equilibrium;
        let slope = (f1 - f0) / (x1 - x0);
        if slope == 0.0 || !slope.is_finite() {
            break;
        }
        let step = (-f1 / slope).clamp(-step_limit, step_limit);
        (x0, f0) = (x1, f1);
        x1 += step;
    }
    let reached = best.end_angle_from_vertical();
    Err(format!(
        "`structure.hang_off.angle_deg` = {angle}: the top's position was not found in {MAX_SOLVES} static solves (the tangent reached {reached:.4} deg); is the angle reachable with this length and depth?"
    ))
}

/// Adds `shift` (m) to the x displacement of the model's end (held, or given
/// as a constant or a time function's offset).
fn end_offset(model: &mut NonlinearParams, shift: f64) -> Result<(), String> {
    let refuse = |what: &str| {
        Err(format!(
            "`structure.hang_off`: the top is placed by moving the end's x, which {what}; expected `ends.end` pinned or fixed, or its `x` a displacement"
        ))
    };
    let end = &mut model.ends.end;
    if *end == End::default() {
        return refuse("is free");
    }
    let held = matches!(end.kind, EndKind::Pinned | EndKind::Fixed);
    match &mut end.x {
        None if held => {
            end.x = Some(DofCondition::Displacement(TimeFunction::Constant(shift)));
        }
        Some(DofCondition::Displacement(TimeFunction::Constant(d))) => *d += shift,
        Some(DofCondition::Displacement(TimeFunction::Expression(e))) => e.offset += shift,
        Some(
            DofCondition::Displacement(TimeFunction::Input(_))
            | DofCondition::Force(_)
            | DofCondition::VelocityFrom(_),
        ) => return refuse("is not given as a displacement"),
        None | Some(_) => return refuse("is free or not a displacement"),
    }
    Ok(())
}
