//! Quantities whose reference is zero to round-off: a free end's force (1e-8
//! N where the structure carries kN) has no scale of its own, and epsilon
//! relative to it calls an exact partition 88 % off (issue 27). Such a quantity
//! is judged against its kind's scale instead: the largest RMS among the
//! reference's quantities of the same unit (forces, moments, lengths), which
//! the report states.

use super::Outcome;
use serde::Serialize;

/// Below this fraction of its kind's scale, a reference's RMS is round-off.
const ROUND_OFF: f64 = 1e-9;

/// A quantity judged against its kind's scale.
#[derive(Clone, Debug, Serialize)]
pub struct Floor {
    /// The quantity's name.
    pub quantity: String,
    /// The reference's RMS of the quantity and the scale it is judged
    /// against, in the quantity's unit.
    pub reference_rms: f64,
    /// The scale it is judged against.
    pub scale: f64,
    /// The quantity's unit of measure.
    pub unit: &'static str,
}

/// A quantity's unit, by its name (a body's motions end in the degree of
/// freedom's name).
fn unit_of(name: &str) -> &'static str {
    let ends = |suffixes: &[&str]| suffixes.iter().any(|s| name.ends_with(s));
    if name == "touchdown" || ends(&["_surge", "_sway", "_heave"]) {
        "m"
    } else if ends(&["_roll", "_pitch", "_yaw"]) {
        "rad"
    } else if name.ends_with("_moment") {
        "N m"
    } else {
        "N"
    }
}

/// The RMS of `x` over `time` (trapezoidal), 0 for fewer than two samples.
fn rms(time: &[f64], x: &[f64]) -> f64 {
    let span = time.last().unwrap_or(&0.0) - time.first().unwrap_or(&0.0);
    if time.len() < 2 || span <= 0.0 {
        return 0.0;
    }
    (crate::indicators::integral(time, |k| x[k].powi(2)) / span).sqrt()
}

/// Per quantity (in `names` order), the scale to judge it against where the
/// reference's own RMS is round-off; and the list for the report.
pub(super) fn floors(
    names: &[&str],
    reference: &Outcome,
    from: Option<f64>,
) -> (Vec<Option<f64>>, Vec<Floor>) {
    let own: Vec<f64> = (0..names.len())
        .map(|i| {
            reference.series.get(i).map_or(0.0, |x| {
                let (time, x) = crate::indicators::window(&reference.time, &[x], from);
                rms(time, x[0])
            })
        })
        .collect();
    let scale_of = |unit: &str| {
        (names.iter().zip(&own))
            .filter(|(n, _)| unit_of(n) == unit)
            .fold(0.0f64, |m, (_, r)| m.max(*r))
    };
    let mut list = Vec::new();
    let per_quantity = (names.iter().zip(&own))
        .map(|(name, &r)| {
            let unit = unit_of(name);
            let scale = scale_of(unit);
            let round_off = scale > 0.0 && r <= ROUND_OFF * scale;
            round_off.then(|| {
                list.push(Floor {
                    quantity: (*name).to_owned(),
                    reference_rms: r,
                    scale,
                    unit,
                });
                scale
            })
        })
        .collect();
    (per_quantity, list)
}

/// The RMS of a run's error `x - r` relative to `scale`.
pub(super) fn against_scale(time: &[f64], x: &[f64], r: &[f64], scale: f64) -> f64 {
    let difference: Vec<f64> = x.iter().zip(r).map(|(a, b)| a - b).collect();
    rms(time, &difference) / scale
}

/// The report's note on the quantities judged against their kind's scale.
pub fn note(floors: &[Floor]) -> Option<String> {
    if floors.is_empty() {
        return None;
    }
    let items: Vec<String> = floors
        .iter()
        .map(|f| {
            format!(
                "{} (reference RMS {:.2e} {}, at round-off; judged against {:.3e} {}, the largest of its kind)",
                f.quantity, f.reference_rms, f.unit, f.scale, f.unit
            )
        })
        .collect();
    Some(format!(
        "Judged as RMS error over their kind's scale: {}.",
        items.join("; ")
    ))
}
