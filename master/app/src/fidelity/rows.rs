//! A fidelity study's rows: each run's epsilon per quantity against the
//! reference, the worst over the judged quantities, the speed-up, the Pareto
//! front and the tolerance; and each row's combination as labels.

use super::{Choice, FidelityRow, Outcome, Structure, Subject, Task};
use crate::indicators::{indicator, interpolate, normalized_error};

/// The report's rows: errors against `finer` (a finer reference judged
/// against) or else against the reference at the model's mesh (task 0),
/// speed-ups against the latter, the Pareto front and the tolerance.
pub(super) fn rows_of(
    subject: &dyn Subject,
    (tasks, outcomes, finer): (&[Task], &[Outcome], Option<&Outcome>),
    (names, scales): (&[&str], &[Option<f64>]),
    (tolerance, judged, from): (f64, &[String], Option<f64>),
) -> Vec<FidelityRow> {
    let reference = &outcomes[0];
    let judge = finer.unwrap_or(reference);
    let mut rows: Vec<FidelityRow> = tasks
        .iter()
        .zip(outcomes)
        .map(|(task, o)| {
            let errors: Vec<(String, f64)> = names
                .iter()
                .enumerate()
                .map(|(i, n)| {
                    let e = if task.is_none() && finer.is_none() {
                        0.0
                    } else {
                        epsilon(o, judge, (i, from), scales.get(i).copied().flatten())
                    };
                    ((*n).to_owned(), e)
                })
                .collect();
            let judged_errors = errors.iter().filter(|(n, _)| judged.contains(n));
            let worst = judged_errors.map(|e| e.1).fold(0.0f64, |a, e| {
                if e.is_nan() || a.is_nan() {
                    f64::NAN
                } else {
                    a.max(e)
                }
            });
            FidelityRow {
                combination: subject.labels(task.as_deref()),
                reference: task.is_none(),
                worst_error: worst,
                errors,
                cost_per_simulated_second: o.cost,
                cost_spread: o.cost_spread,
                speed_up: reference.cost / o.cost,
                iterations_per_step: o.iterations_per_step,
                non_converged_steps: o.non_converged_steps,
                start_change: o.start_change,
                pareto: false,
                within_tolerance: false,
                error: o.error.clone(),
                warnings: o.warnings.clone(),
            }
        })
        .collect();
    let usable = |r: &FidelityRow| {
        !r.reference
            && r.error.is_none()
            && r.worst_error.is_finite()
            && r.cost_per_simulated_second.is_finite()
    };
    for k in 0..rows.len() {
        let r = &rows[k];
        let ok = usable(r);
        let beaten = rows.iter().any(|o| {
            usable(o)
                && o.worst_error <= r.worst_error
                && o.cost_per_simulated_second <= r.cost_per_simulated_second
                && (o.worst_error < r.worst_error
                    || o.cost_per_simulated_second < r.cost_per_simulated_second)
        });
        rows[k].pareto = ok && !beaten;
        rows[k].within_tolerance = ok && rows[k].worst_error <= tolerance;
    }
    rows
}

/// epsilon of quantity `i` of run `o` against the reference, at the run's
/// times from `from` (s) on: relative to the reference itself, or to
/// `scale` where the reference is zero to round-off (`floors`).
pub(super) fn epsilon(
    o: &Outcome,
    reference: &Outcome,
    (i, from): (usize, Option<f64>),
    scale: Option<f64>,
) -> f64 {
    let (Some(x), Some(r)) = (o.series.get(i), reference.series.get(i)) else {
        return f64::NAN;
    };
    if o.time.is_empty() || reference.time.is_empty() {
        return f64::NAN;
    }
    let resampled: Vec<f64> = o
        .time
        .iter()
        .map(|&t| interpolate(&reference.time, r, t))
        .collect();
    let (time, x) = crate::indicators::window(&o.time, &[x], from);
    let (_, r) = crate::indicators::window(&o.time, &[&resampled], from);
    match scale {
        Some(scale) => super::floors::against_scale(time, x[0], r[0], scale),
        None => indicator("", normalized_error(time, &x, &r)).relative_error,
    }
}

/// Every section's choice in a run: the combination's, else the scene's.
pub(super) fn combination_of(
    structure: &Structure,
    combination: Option<&[(String, Choice)]>,
) -> Vec<(String, String)> {
    let Some(combination) = combination else {
        return vec![("monolithic".into(), "nonlinear".into())];
    };
    (structure.layout.sections.iter())
        .map(|section| {
            let chosen = combination
                .iter()
                .find(|(s, _)| *s == section.name)
                .map(|(_, c)| c.label());
            let label = chosen.unwrap_or_else(|| section.choice.clone());
            (section.name.clone(), label)
        })
        .collect()
}
