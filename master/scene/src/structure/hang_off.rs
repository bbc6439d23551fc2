//! The hang-off of a structure's top given by its angle: `[structure] hang_off
//! = { angle_deg = 12.0 }` places the structure's end (its top) horizontally so
//! that, in the static equilibrium, the pipe's tangent there is `angle`
//! degrees from the vertical (a riser's hang-off angle), at the height the
//! scene gives it. The end's x displacement offset is found by the secant
//! method on the equilibrium's angle (at most `MAX_SOLVES` static solves, to
//! `TOLERANCE_DEG`) and written into the model, so every section, the twin
//! and the dynamics start from that top. Its second trial is where an
//! inextensible catenary puts the top (a structure starting on a flat
//! seabed), and a trial near the last one starts from its equilibrium: the
//! riser's top in 5 solves and 380 Newton iterations (10 and 2 370 from a
//! small first move and the stress-free shape each time; 0.29 -> 0.05 s).

use super::statics::Equilibrium;
use serde::Deserialize;
use slender_units::Time;
use slender_units::beam::boundary::TimeFunction;
use slender_units::contact::surface::Shape;
use slender_units::nonlinear::NonlinearParams;
use slender_units::nonlinear::params::{DofCondition, End, EndKind, StartShape};

/// Static solves of the search, at most.
const MAX_SOLVES: usize = 40;
/// The angle's tolerance (deg).
const TOLERANCE_DEG: f64 = 1e-6;
/// A trial starts from the last one's equilibrium where the top moves by at
/// most this fraction of the structure's length.
const NEAR: f64 = 0.005;

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
/// `angle` (deg) from the vertical; returns the shift (m), that equilibrium
/// and the static solves it took.
pub(super) fn place(
    model: &mut NonlinearParams,
    angle: f64,
    t0: Time,
) -> Result<(f64, Equilibrium, usize), String> {
    let length = model.length();
    let solve = |shift: f64,
                 model: &NonlinearParams,
                 near: Option<(&Equilibrium, f64)>|
     -> Result<(f64, Equilibrium), String> {
        let equilibrium = solve_near(model, shift, near, (length, t0))?;
        Ok((equilibrium.end_angle_from_vertical() - angle, equilibrium))
    };
    // Secant on the shift, each step at most a tenth of the structure's length.
    let step_limit = 0.1 * length;
    let (mut x0, (mut f0, mut best)) = (0.0, solve(0.0, model, None)?);
    // The second trial where a catenary puts the top, else a small move.
    let mut x1 = catenary_shift(model, &best, angle).unwrap_or(1e-3 * length);
    for solves in 2..=MAX_SOLVES {
        // `best` is the equilibrium at x0.
        let (f1, equilibrium) = solve(x1, model, Some((&best, x0)))?;
        if f1.abs() < TOLERANCE_DEG {
            end_offset(model, x1)?;
            return Ok((x1, equilibrium, solves));
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

/// The equilibrium of `model` (its length in m) at `t0` with its end moved
/// by `shift` (m) in x: from the `near` trial's equilibrium (at its shift)
/// moved to it where the move is at most `NEAR` of the length (Newton at full
/// load from there takes a few iterations where the continuation from the
/// stress-free shape takes hundreds; from farther it fails), else from the
/// model's own start shape.
fn solve_near(
    model: &NonlinearParams,
    shift: f64,
    near: Option<(&Equilibrium, f64)>,
    (length, t0): (f64, Time),
) -> Result<Equilibrium, String> {
    let mut trial = model.clone();
    end_offset(&mut trial, shift)?;
    if let Some((last, last_shift)) = near
        && (shift - last_shift).abs() <= NEAR * length
    {
        trial.start_shape = StartShape::Points;
        trial.start_points = last.nodes_moved_by(shift - last_shift);
    }
    Equilibrium::solve(&trial, t0)
        .map_err(|e| format!("`structure.hang_off`: with the top moved by {shift:.4} m in x: {e}"))
}

/// The top's shift (m) from `at_rest` (the equilibrium with none) that an
/// inextensible catenary of the structure's mean submerged weight gives for
/// the hang-off `angle` (deg from the vertical): the pipe laid straight from
/// its first node on a flat seabed (within 1e-3 of the length), then hanging to the top's height with
/// its tangent horizontal at touchdown. None where the structure does not
/// start on a flat seabed or would not reach it.
fn catenary_shift(model: &NonlinearParams, at_rest: &Equilibrium, angle: f64) -> Option<f64> {
    let Shape::Flat { height: seabed } = model.contact.as_ref()?.surface.shape else {
        return None;
    };
    let length = model.length();
    let (start, top) = (at_rest.position_at(0.0), at_rest.position_at(length));
    if (start[1] - seabed).abs() > 1e-3 * length {
        return None;
    }
    let weight: f64 = (model.segments.iter())
        .map(|s| s.submerged_weight * s.length)
        .sum::<f64>()
        / length;
    let (rise, slope) = (top[1] - seabed, (90.0 - angle).to_radians());
    if rise <= 0.0 || weight <= 0.0 {
        return None;
    }
    // Catenary parameter H / w (m), from the rise and the top's slope.
    let a = rise / (1.0 / slope.cos() - 1.0);
    let hanging = a * slope.tan();
    (hanging < length).then(|| start[0] + (length - hanging) + a * slope.tan().asinh() - top[0])
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The riser of `examples/structure_riser.toml` at 40 elements.
    fn riser() -> NonlinearParams {
        toml::from_str(
            r#"
static_start = true
start = [0.0, -1000.0]
segments = [{ length = 2000.0, angle_deg = 30.0, elements = 40, axial_stiffness = 4.0631e9, bending_stiffness = 4.6937e7, mass_per_length = 154.08, submerged_weight = 683.05, diameter = 0.3239 }]
ends.start = { kind = "pinned" }
ends.end = { kind = "pinned" }
contact = { method = { kind = "penalty", penalty = 1.0e6 }, surface = { shape = { kind = "flat", height = -1000.0 } } }
"#,
        )
        .unwrap()
    }

    #[test]
    fn a_riser_s_top_is_placed_from_a_catenary_s_estimate_in_a_few_solves() {
        let mut model = riser();
        let (shift, equilibrium, solves) = place(&mut model, 12.0, Time::ZERO).unwrap();
        assert!((equilibrium.end_angle_from_vertical() - 12.0).abs() < TOLERANCE_DEG);
        // The catenary's estimate (1 355.9 m from the anchor) within a metre;
        // the secant from a small first move took ten solves, most of them
        // continuations from the stress-free shape.
        let at_rest = Equilibrium::solve(&riser(), Time::ZERO).unwrap();
        let estimate = catenary_shift(&riser(), &at_rest, 12.0).unwrap();
        assert!((estimate - shift).abs() < 1.0, "{estimate} against {shift}");
        assert!(solves <= 6, "{solves} static solves");
    }

    #[test]
    fn no_estimate_without_a_seabed_under_the_first_node() {
        let mut lifted = riser();
        lifted.start = [0.0, -900.0];
        let at_rest = Equilibrium::solve(&lifted, Time::ZERO).unwrap();
        assert!(catenary_shift(&lifted, &at_rest, 12.0).is_none());
    }
}
