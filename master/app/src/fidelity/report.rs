//! A fidelity study as CSV, Markdown and a figure of worst error against cost
//! with the Pareto front and the cheapest combination within the tolerance.

use super::{FidelityReport, FidelityRow};
use crate::figures::tradeoff::{self, Point, Tradeoff};
use crate::plot::PlotError;
use std::path::Path;

/// A row's combination as `section=choice` pairs.
pub(super) fn label(r: &FidelityRow) -> String {
    r.combination
        .iter()
        .map(|(s, c)| format!("{s}={c}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// The rows as CSV: combination, epsilon per quantity, worst, cost, speed-up,
/// iterations per step, non-converged steps, the start check's change,
/// Pareto, within tolerance, error, warnings (`; ` between them).
pub fn to_csv(report: &FidelityReport) -> String {
    let eps: Vec<String> = report
        .quantities
        .iter()
        .map(|n| format!("epsilon_{n}"))
        .collect();
    let mut out = format!(
        "combination,reference,{},worst_epsilon,cost_per_simulated_second,cost_spread,speed_up,iterations_per_step,non_converged_steps,start_change,pareto,within_tolerance,error,warnings\n",
        eps.join(",")
    );
    for r in &report.rows {
        let eps: Vec<String> = r.errors.iter().map(|(_, e)| format!("{e:e}")).collect();
        out += &format!(
            "{},{},{},{:e},{:e},{},{},{},{},{},{},{},{},{}\n",
            label(r),
            r.reference,
            eps.join(","),
            r.worst_error,
            r.cost_per_simulated_second,
            crate::costs::csv(r.cost_spread),
            r.speed_up,
            r.iterations_per_step,
            r.non_converged_steps,
            r.start_change.map(|c| format!("{c:e}")).unwrap_or_default(),
            r.pareto,
            r.within_tolerance,
            r.error.as_deref().unwrap_or("").replace([',', '\n'], ";"),
            r.warnings.join("; ").replace([',', '\n'], ";")
        );
    }
    out
}

/// The rows as a Markdown table, then the cheapest combination within the
/// tolerance.
pub fn to_markdown(report: &FidelityReport) -> String {
    let mut out = format!(
        "Fidelity study of `{}`: epsilon of each quantity against the monolithic reference; worst: the largest over {}; Pareto: not beaten in both worst error and cost.\n\n| combination | {} | worst | s per sim. s | speed-up | it/step | non-conv. | start change | Pareto |\n|---|{}---|---|---|---|---|---|---|\n",
        report.scene,
        judged(report),
        report.quantities.join(" | "),
        "---|".repeat(report.quantities.len())
    );
    for r in &report.rows {
        let eps: Vec<String> = r.errors.iter().map(|(_, e)| format!("{e:.2e}")).collect();
        let name = if r.reference {
            "reference (monolithic)".to_owned()
        } else {
            label(r)
        };
        let tail = match &r.error {
            Some(e) => format!(" FAILED: {} |", e.replace('|', "/").replace('\n', " ")),
            None => format!(" {} |", if r.pareto { "yes" } else { "" }),
        };
        out += &format!(
            "| {name} | {} | {:.2e} | {} | {:.2} | {:.2} | {} | {} |{tail}\n",
            eps.join(" | "),
            r.worst_error,
            crate::costs::cell(r.cost_per_simulated_second, r.cost_spread),
            r.speed_up,
            r.iterations_per_step,
            r.non_converged_steps,
            crate::study::report::start_change(r.start_change),
        );
    }
    out += &format!("\n{}\n", conclusion(report));
    out += &super::reference_report::to_markdown(report);
    out += &warnings(report);
    out
}

/// Each distinct warning of the runs with the combinations that gave it, as
/// a list (empty when no run warned).
fn warnings(report: &FidelityReport) -> String {
    let mut distinct: Vec<(&str, Vec<String>)> = Vec::new();
    for r in &report.rows {
        for w in &r.warnings {
            match distinct.iter_mut().find(|(text, _)| text == w) {
                Some((_, rows)) => rows.push(label(r)),
                None => distinct.push((w, vec![label(r)])),
            }
        }
    }
    let mut out = String::new();
    if !distinct.is_empty() {
        out += "\nWarnings of the runs:\n\n";
    }
    for (text, rows) in distinct {
        let text = text.replace('\n', " ");
        out += &format!("- {text} ({})\n", rows.join("; "));
    }
    out
}

/// The sentence naming the cheapest combination within the tolerance, and
/// the cautions on what it is judged against.
pub fn conclusion(report: &FidelityReport) -> String {
    let notes = [
        Some(verdict(report)),
        super::reference_report::caution(report),
        super::floors::note(&report.floors),
    ];
    notes.into_iter().flatten().collect::<Vec<_>>().join("\n")
}

/// The cheapest combination within the tolerance, or that there is none.
fn verdict(report: &FidelityReport) -> String {
    match report.cheapest.map(|k| &report.rows[k]) {
        Some(r) => format!(
            "Cheapest within epsilon <= {} on {}: {} ({:.3e} s per simulated s, {:.2}x the reference's speed, worst epsilon {:.2e}).",
            report.tolerance,
            judged(report),
            label(r),
            r.cost_per_simulated_second,
            r.speed_up,
            r.worst_error
        ),
        None => format!(
            "No combination is within epsilon <= {} of the reference on {}.",
            report.tolerance,
            judged(report)
        ),
    }
}

/// The judged quantities in words: "every quantity" or their names.
pub(super) fn judged(report: &FidelityReport) -> String {
    if report.judged.len() == report.quantities.len() {
        "every quantity".into()
    } else {
        report.judged.join(", ")
    }
}

/// Worst epsilon against cost per simulated second (log-log): every
/// combination a numbered marker with its key beside the chart, the Pareto
/// front joined, the cheapest within the tolerance ringed, the tolerance and
/// the reference's cost as lines; the points' pixels and combinations.
pub fn plot(
    path: &Path,
    title: &str,
    report: &FidelityReport,
) -> Result<Vec<crate::report::hover::Point>, PlotError> {
    let usable: Vec<(usize, &FidelityRow)> = (report.rows.iter().enumerate())
        .filter(|(_, r)| !r.reference && r.error.is_none())
        .collect();
    let points = usable
        .iter()
        .map(|(_, r)| Point {
            label: label(r),
            cost: r.cost_per_simulated_second,
            error: r.worst_error,
        })
        .collect();
    let figure = Tradeoff {
        title,
        error_label: "worst epsilon against the monolithic reference (-)",
        points,
        tolerance: Some(report.tolerance),
        reference_cost: (report.rows.iter().find(|r| r.reference))
            .map(|r| r.cost_per_simulated_second),
        chosen: report
            .cheapest
            .and_then(|k| usable.iter().position(|(i, _)| *i == k)),
    };
    tradeoff::draw(path, &figure)
}
