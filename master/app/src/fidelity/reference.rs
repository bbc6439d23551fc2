//! The reference's own discretisation error (issue 48): the monolithic
//! reference run again at half its element length and half its step (a
//! *level*: level k has 2^k times the model's elements at 1/2^k its step),
//! and the epsilon of each quantity between a level and the next finer one
//! taken as the coarser level's estimated error. For a method of order p in
//! its asymptotic range the coarser level's true error is that difference
//! times 2^p / (2^p - 1): between it and twice it for any p >= 1, so the
//! estimate is a lower bound within a factor of two.
//!
//! `estimate` (the default) runs one finer level and judges the combinations
//! against the model's own mesh, reporting that mesh's estimated error beside
//! theirs and flagging a tolerance below it; `converged` refines until the
//! difference between the two finest levels is below a fifth of the tolerance
//! on every judged quantity (at most `max_refinements` halvings) and judges
//! against the finest level (whose error is at most that difference for
//! p >= 1); `model` runs the reference as written and estimates nothing.

use super::{Outcome, rows};
use serde::Serialize;
use toml::{Table, Value};

/// What the study's reference is and how its own error is estimated.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum ReferenceMode {
    /// The monolithic run at the model's mesh and step, no estimate.
    Model,
    /// The same, with its error estimated from one finer level.
    Estimate,
    /// Refined until its estimated error is below a fifth of the tolerance.
    Converged,
}

impl std::str::FromStr for ReferenceMode {
    type Err = String;

    fn from_str(s: &str) -> Result<ReferenceMode, String> {
        match s {
            "model" => Ok(ReferenceMode::Model),
            "estimate" => Ok(ReferenceMode::Estimate),
            "converged" => Ok(ReferenceMode::Converged),
            _ => Err(format!(
                "`{s}`: expected `estimate` (the reference at the model's mesh, its error estimated from one run at half its element length and step), `converged` (refined until its estimated error is below a fifth of the tolerance) or `model` (as written, no estimate)"
            )),
        }
    }
}

/// The most halvings `converged` may make when the plan names none.
pub const DEFAULT_MAX_REFINEMENTS: u32 = 3;

/// One level of the reference.
#[derive(Clone, Debug, Serialize)]
pub struct ReferenceLevel {
    /// Halvings of the model's element length and of the step (0: the
    /// model as written).
    pub refinement: u32,
    /// Its synchronisation step (s).
    pub step: f64,
    /// The median of its timed repeats (s per simulated s) and their spread.
    pub cost_per_simulated_second: f64,
    /// (max - min) / median of the repeats' costs (NaN for one).
    pub cost_spread: f64,
    /// epsilon of each quantity against the next finer level: this level's
    /// estimated error (NaN for the finest).
    pub change: Vec<(String, f64)>,
    /// epsilon of each quantity against the level the rows are judged
    /// against (zero for that level itself).
    pub errors: Vec<(String, f64)>,
    /// Why the run failed, when it did.
    pub error: Option<String>,
}

/// What the study knows of its reference's own error.
#[derive(Clone, Debug, Serialize)]
pub struct ReferenceCheck {
    /// How the reference was chosen.
    pub mode: ReferenceMode,
    /// The levels run, coarsest (the model's mesh) first.
    pub levels: Vec<ReferenceLevel>,
    /// The level the rows are judged against.
    pub judging: u32,
    /// Per quantity, the estimated error of the level judged against (NaN
    /// where it could not be estimated).
    pub estimate: Vec<(String, f64)>,
    /// `converged`: whether the estimate is below a fifth of the tolerance
    /// on every judged quantity within the refinements allowed.
    pub converged: Option<bool>,
    /// The judged quantities whose estimated reference error is above a
    /// fifth of the tolerance, with that error.
    pub flagged: Vec<(String, f64)>,
    /// `converged`: the cheapest level coarser than the one judged against
    /// whose worst judged error against it is within the tolerance (the
    /// cheapest monolithic mesh good enough).
    pub cheapest_within: Option<u32>,
}

impl ReferenceLevel {
    /// The largest of its errors over the judged quantities (NaN when one is).
    pub fn worst(&self, judged: &[String]) -> f64 {
        (self.errors.iter())
            .filter(|(n, _)| judged.contains(n))
            .fold(
                0.0f64,
                |w, (_, e)| if e.is_nan() { f64::NAN } else { w.max(*e) },
            )
    }
}

/// The levels a study runs before it knows their changes: level 0 and, but
/// for `model`, level 1.
pub(super) fn first_levels(mode: ReferenceMode) -> u32 {
    match mode {
        ReferenceMode::Model => 1,
        ReferenceMode::Estimate | ReferenceMode::Converged => 2,
    }
}

/// The most levels a plan may run: its first ones, or for `converged` the
/// model's mesh and every refinement allowed.
pub(super) fn most_levels(plan: &super::FidelityPlan) -> u32 {
    match plan.reference {
        ReferenceMode::Converged => plan.max_refinements.max(1) + 1,
        mode => first_levels(mode),
    }
}

/// The run's label for progress lines and kept runs.
pub(super) fn label(level: u32) -> String {
    match level {
        0 => "reference (monolithic)".to_owned(),
        k => format!(
            "reference (monolithic, {}x the elements, 1/{} the step)",
            1u64 << k,
            1u64 << k
        ),
    }
}

/// Makes a reference run's scene level `level`: the step halved and the
/// element count of the model (each segment of a planar model, a 3D line's
/// or a mooring's lines') doubled `level` times. The error names what could
/// not be refined.
pub(crate) fn refine(table: &mut Table, level: u32) -> Result<(), String> {
    if level == 0 {
        return Ok(());
    }
    let factor = 1i64 << level;
    let simulation = (table.get_mut("simulation").and_then(Value::as_table_mut))
        .ok_or("the reference's refinement: the scene has no `[simulation]`")?;
    let step = (simulation.get("step"))
        .and_then(|s| s.as_float().or_else(|| s.as_integer().map(|i| i as f64)));
    let step = step.ok_or("the reference's refinement: `simulation.step`: expected a number")?;
    simulation.insert("step".into(), Value::Float(step / factor as f64));
    let mut counts = Vec::new();
    for (key, value) in table.iter_mut() {
        match (key.as_str(), value) {
            ("structure", Value::Table(s)) => counts.extend(s.get_mut("model").map(model_counts)),
            ("mooring", Value::Table(mooring)) => counts.push(mooring_counts(mooring)),
            _ => {}
        }
    }
    let counts: Vec<&mut Value> = counts.into_iter().flatten().collect();
    if counts.is_empty() {
        return Err(
            "the reference's refinement: the model gives no element count (`elements`) to double"
                .into(),
        );
    }
    for count in counts {
        let n = count.as_integer().ok_or(
            "the reference's refinement: an `elements` that is not a whole number".to_owned(),
        )?;
        *count = Value::Integer(n.saturating_mul(factor));
    }
    Ok(())
}

/// A structure model's element counts: each segment's, or its own.
fn model_counts(model: &mut Value) -> Vec<&mut Value> {
    let Some(model) = model.as_table_mut() else {
        return Vec::new();
    };
    if !model.contains_key("segments") {
        return model.get_mut("elements").into_iter().collect();
    }
    let segments = model.get_mut("segments").and_then(Value::as_array_mut);
    (segments.into_iter().flatten())
        .filter_map(Value::as_table_mut)
        .filter_map(|s| s.get_mut("elements"))
        .collect()
}

/// A mooring's lines' element counts: the shared model's and each line's own.
fn mooring_counts(mooring: &mut Table) -> Vec<&mut Value> {
    let mut counts = Vec::new();
    for (key, value) in mooring.iter_mut() {
        match (key.as_str(), value) {
            ("line", Value::Table(line)) => counts.extend(line.get_mut("elements")),
            ("lines", Value::Array(lines)) => {
                let models = (lines.iter_mut())
                    .filter_map(Value::as_table_mut)
                    .filter_map(|l| l.get_mut("model"))
                    .filter_map(Value::as_table_mut);
                counts.extend(models.filter_map(|m| m.get_mut("elements")));
            }
            _ => {}
        }
    }
    counts
}

/// Whether `converged` should refine again: some judged quantity's change
/// between the two finest levels is not (finite and) below a fifth of the
/// tolerance.
pub(super) fn wants_more(change: &[(String, f64)], judged: &[String], tolerance: f64) -> bool {
    (change.iter())
        .filter(|(n, _)| judged.contains(n))
        .any(|(_, d)| !(d.is_finite() && *d < tolerance / 5.0))
}

/// What the quantities of levels' outcomes are measured with.
pub(super) struct Measure<'a> {
    pub(super) names: &'a [&'a str],
    pub(super) scales: &'a [Option<f64>],
    pub(super) from: Option<f64>,
}

impl Measure<'_> {
    /// epsilon of each quantity of `run` against `reference`.
    pub(super) fn errors(&self, run: &Outcome, reference: &Outcome) -> Vec<(String, f64)> {
        (self.names.iter().enumerate())
            .map(|(i, n)| {
                let scale = self.scales.get(i).copied().flatten();
                let e = match (&run.error, &reference.error) {
                    (None, None) => rows::epsilon(run, reference, (i, self.from), scale),
                    _ => f64::NAN,
                };
                ((*n).to_owned(), e)
            })
            .collect()
    }
}

/// The check of the reference from its levels' outcomes (coarsest first):
/// each level's change against the next, its errors against the level
/// judged against (`judging`), the estimate and the flagged quantities.
pub(super) fn check(
    (mode, outcomes, judging): (ReferenceMode, &[(f64, Outcome)], usize),
    measure: &Measure,
    (judged, tolerance): (&[String], f64),
) -> ReferenceCheck {
    let nan = || (measure.names.iter()).map(|n| ((*n).to_owned(), f64::NAN));
    let levels: Vec<ReferenceLevel> = (outcomes.iter().enumerate())
        .map(|(k, (step, o))| ReferenceLevel {
            refinement: k as u32,
            step: *step,
            cost_per_simulated_second: o.cost,
            cost_spread: o.cost_spread,
            change: match outcomes.get(k + 1) {
                Some((_, finer)) => measure.errors(o, finer),
                None => nan().collect(),
            },
            errors: measure.errors(o, &outcomes[judging].1),
            error: o.error.clone(),
        })
        .collect();
    // The judged level's estimate: its own change, or (the finest) the
    // change of the level below it, an upper bound for p >= 1.
    let estimate = match (levels.get(judging), judging.checked_sub(1)) {
        (Some(l), _) if judging + 1 < levels.len() => l.change.clone(),
        (_, Some(below)) => levels[below].change.clone(),
        _ => nan().collect(),
    };
    let flagged = (estimate.iter())
        .filter(|(n, e)| judged.contains(n) && *e > tolerance / 5.0)
        .cloned()
        .collect();
    let cheapest_within = (levels[..judging].iter())
        .filter(|l| l.error.is_none() && l.worst(judged) <= tolerance)
        .min_by(|a, b| {
            a.cost_per_simulated_second
                .total_cmp(&b.cost_per_simulated_second)
        })
        .map(|l| l.refinement);
    ReferenceCheck {
        cheapest_within,
        mode,
        converged: (mode == ReferenceMode::Converged)
            .then(|| !wants_more(&estimate, judged, tolerance)),
        judging: judging as u32,
        levels,
        estimate,
        flagged,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The scene `text` made level `level`.
    fn refined(text: &str, level: u32) -> Result<Table, String> {
        let mut table: Table = text.parse().unwrap();
        refine(&mut table, level).map(|()| table)
    }

    #[test]
    fn a_level_halves_the_step_and_doubles_every_element_count() {
        let text = "[simulation]\nduration = 1.0\nstep = 0.1\n[structure.model]\nsegments = [{ length = 10.0, elements = 5 }, { length = 5.0, elements = 3 }]\n";
        let table = refined(text, 2).unwrap();
        assert_eq!(table["simulation"]["step"].as_float(), Some(0.025));
        let segments = table["structure"]["model"]["segments"].as_array().unwrap();
        let counts: Vec<i64> = segments
            .iter()
            .map(|s| s["elements"].as_integer().unwrap())
            .collect();
        assert_eq!(counts, [20, 12]);
        // A step written as a whole number, and a 3D line's own count.
        let table = refined(
            "[simulation]\nduration = 2\nstep = 1\n[structure.model]\nelements = 4\n",
            1,
        )
        .unwrap();
        assert_eq!(table["simulation"]["step"].as_float(), Some(0.5));
        assert_eq!(
            table["structure"]["model"]["elements"].as_integer(),
            Some(8)
        );
    }

    #[test]
    fn a_moorings_shared_and_own_counts_are_refined() {
        let text = "[simulation]\nduration = 1.0\nstep = 0.2\n[mooring.line]\nelements = 50\n[[mooring.lines]]\nname = \"a\"\n[[mooring.lines]]\nname = \"b\"\nmodel = { elements = 30 }\n";
        let table = refined(text, 1).unwrap();
        assert_eq!(table["mooring"]["line"]["elements"].as_integer(), Some(100));
        let b = &table["mooring"]["lines"].as_array().unwrap()[1];
        assert_eq!(b["model"]["elements"].as_integer(), Some(60));
    }

    #[test]
    fn a_model_without_an_element_count_is_refused_by_name() {
        let text = "[simulation]\nduration = 1.0\nstep = 0.1\n[structure.model]\nlength = 3.0\n";
        let e = refined(text, 1).unwrap_err();
        assert!(e.contains("`elements`"), "{e}");
    }

    #[test]
    fn converged_refines_until_every_judged_change_is_below_a_fifth() {
        let judged = vec!["m".to_owned()];
        let change = |d: f64| vec![("m".to_owned(), d), ("other".to_owned(), 1.0)];
        assert!(wants_more(&change(2.1e-3), &judged, 1e-2));
        assert!(!wants_more(&change(1.9e-3), &judged, 1e-2));
        assert!(wants_more(&change(f64::NAN), &judged, 1e-2));
    }
}
