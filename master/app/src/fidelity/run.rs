//! One run of a fidelity study: a combination's scene built, run (timed
//! `--repeats` times) and reduced to the quantities.

use super::{Choice, FidelityPlan, Outcome, Subject};
use crate::costs::repeated;
use crate::run::{RunOptions, run_scene};
use slender_scene::Draft;

/// Runs one combination (the reference for `None`) and reduces its
/// recording to the quantities; its cost is the median of `plan.repeats`
/// timed runs.
pub(super) fn run_one(
    draft: &Draft,
    subject: &dyn Subject,
    combination: Option<&[(String, Choice)]>,
    plan: &FidelityPlan,
) -> Outcome {
    let failed = |error: String| Outcome {
        time: Vec::new(),
        series: Vec::new(),
        iterations_per_step: f64::NAN,
        non_converged_steps: 0,
        start_change: None,
        cost: f64::NAN,
        cost_spread: f64::NAN,
        error: Some(error),
        warnings: Vec::new(),
    };
    let (table, reader) = match subject.run_table(draft.table(), combination) {
        Ok(t) => t,
        Err(e) => return failed(e),
    };
    let mut draft = draft.clone();
    draft.change(
        format!("the fidelity study's {}", combination_label(combination)),
        table,
    );
    let scene = match crate::study::scene_of(&draft, plan.duration) {
        Ok(s) => s,
        Err(e) => return failed(e.to_string()),
    };
    let options = RunOptions {
        output_dir: None,
        progress: false,
        realtime: false,
    };
    let result = match run_scene(&scene, &options) {
        Ok(r) => r,
        Err(e) => return failed(e.to_string()),
    };
    let series = reader(&result.recorder);
    let counters = &result.summary.counters;
    let again =
        || run_scene(&scene, &options).map_or(f64::NAN, |r| r.summary.cost_per_simulated_second);
    let (cost, cost_spread) = match result.summary.error {
        None => repeated(
            plan.repeats,
            result.summary.cost_per_simulated_second,
            again,
        ),
        Some(_) => (result.summary.cost_per_simulated_second, f64::NAN),
    };
    match series {
        Ok(series) => Outcome {
            time: result.recorder.time.clone(),
            series,
            iterations_per_step: counters.mean_iterations(),
            non_converged_steps: counters.non_converged_steps,
            start_change: counters.start_load.as_ref().map(|l| l.relative_change),
            cost,
            cost_spread,
            error: result.summary.error.clone(),
            warnings: result.summary.warnings.clone(),
        },
        Err(e) => failed(e),
    }
}

/// A combination in words (the reference's name for `None`).
pub(super) fn combination_label(combination: Option<&[(String, Choice)]>) -> String {
    match combination {
        None => "reference (monolithic)".to_owned(),
        Some(c) => c
            .iter()
            .map(|(s, c)| format!("{s}={}", c.label()))
            .collect::<Vec<_>>()
            .join(" "),
    }
}

/// A line of progress for a finished run: its cost, or why it failed.
pub(super) fn describe(o: &Outcome) -> String {
    match &o.error {
        Some(e) => format!("FAILED: {e}"),
        None if o.cost_spread.is_finite() => format!(
            "{:.3e} s per simulated s (median, spread {:.0} %)",
            o.cost,
            100.0 * o.cost_spread
        ),
        None => format!("{:.3e} s per simulated s", o.cost),
    }
}
