//! The reference's own error in a fidelity study's report: its estimate per
//! quantity, the levels a converged reference ran, and the caution when the
//! tolerance is below what the reference itself can tell (issue 48).

use super::FidelityReport;
use super::reference::{ReferenceLevel, ReferenceMode};
use super::report::judged;

/// The caution when a judged quantity's reference is itself off by more than
/// a fifth of the tolerance; None when none is (or nothing was estimated).
pub(super) fn caution(report: &FidelityReport) -> Option<String> {
    let check = &report.reference;
    if check.flagged.is_empty() {
        return None;
    }
    let items: Vec<String> = (check.flagged.iter())
        .map(|(n, e)| format!("{n} ({e:.2e})"))
        .collect();
    let worst = (check.flagged.iter()).fold(0.0f64, |w, (_, e)| w.max(*e));
    let against = match check.mode {
        ReferenceMode::Converged => format!(
            "the finest reference run ({}x the elements, 1/{} the step; the most --refinements allowed)",
            1u64 << check.judging,
            1u64 << check.judging
        ),
        _ => "the reference at the model's mesh".to_owned(),
    };
    let severity = if worst >= report.tolerance {
        format!(
            "within {} of a reference that is itself about {worst:.2e} off",
            report.tolerance
        )
    } else {
        format!(
            "the reference's own error is more than a fifth of the tolerance {}",
            report.tolerance
        )
    };
    let remedy = match check.mode {
        ReferenceMode::Converged => "a larger `--refinements` refines it further",
        _ => {
            "`--reference converged` judges against a reference refined until its error is below a fifth of the tolerance"
        }
    };
    Some(format!(
        "Caution: {against} has an estimated error above a fifth of the tolerance on {}: {severity}; {remedy}.",
        items.join(", ")
    ))
}

/// The reference's section of the Markdown report: its estimated error per
/// quantity and, refined, its levels (empty for `--reference model`).
pub(super) fn to_markdown(report: &FidelityReport) -> String {
    let check = &report.reference;
    if check.mode == ReferenceMode::Model {
        return String::new();
    }
    let header = format!(
        "| | {} |\n|---|{}\n",
        report.quantities.join(" | "),
        "---|".repeat(report.quantities.len())
    );
    let cells = |values: &[(String, f64)]| -> String {
        let v: Vec<String> = values.iter().map(|(_, e)| format!("{e:.2e}")).collect();
        v.join(" | ")
    };
    let mut out = format!(
        "\nThe reference's own error, estimated by epsilon between successive levels (level k: 2^k times the model's elements at 1/2^k its step); for a method of order p >= 1 in its asymptotic range the true error is between this and twice it.\n\n{header}| estimated error of the reference judged against | {} |\n",
        cells(&check.estimate)
    );
    if check.mode == ReferenceMode::Converged {
        out += &levels_table(report);
    }
    out
}

/// A converged reference's levels: mesh, step, cost, change to the next
/// level and worst error against the finest; whether it converged and the
/// cheapest level good enough.
fn levels_table(report: &FidelityReport) -> String {
    let check = &report.reference;
    let mut out = format!(
        "\n| level | elements | step (s) | s per sim. s | change to the next level ({}) | worst epsilon against the finest |\n|---|---|---|---|---|---|\n",
        report.quantities.join(", ")
    );
    for l in &check.levels {
        out += &level_row(l, &report.judged);
    }
    let converged = match check.converged {
        Some(true) => format!(
            "Converged: the two finest levels differ by less than a fifth of the tolerance ({}) on {}; the rows are judged against level {}.",
            report.tolerance / 5.0,
            judged(report),
            check.judging
        ),
        _ => format!(
            "Not converged within the refinements allowed: the rows are judged against level {}, whose estimated error is above a fifth of the tolerance.",
            check.judging
        ),
    };
    out += &format!("\n{converged}\n");
    out += &cheapest_monolithic(report);
    out
}

/// One level's row in the levels table.
fn level_row(l: &ReferenceLevel, judged: &[String]) -> String {
    let change: Vec<String> = (l.change.iter())
        .map(|(_, e)| match e.is_finite() {
            true => format!("{e:.2e}"),
            false => "-".to_owned(),
        })
        .collect();
    let outcome = match &l.error {
        Some(e) => format!("FAILED: {}", e.replace('|', "/").replace('\n', " ")),
        None => format!("{:.2e}", l.worst(judged)),
    };
    format!(
        "| {} | {}x | {} | {} | {} | {outcome} |\n",
        l.refinement,
        1u64 << l.refinement,
        l.step,
        crate::costs::cell(l.cost_per_simulated_second, l.cost_spread),
        change.join(", "),
    )
}

/// The cheapest monolithic level within the tolerance of the finest, and
/// the cheapest combination's speed against it.
fn cheapest_monolithic(report: &FidelityReport) -> String {
    let check = &report.reference;
    let Some(level) = (check.cheapest_within).and_then(|k| check.levels.get(k as usize)) else {
        return format!(
            "No coarser level of the monolithic reference is within {} of the finest.\n",
            report.tolerance
        );
    };
    let against = match report.cheapest.map(|k| &report.rows[k]) {
        Some(r) => format!(
            "; the cheapest combination within it ({}) runs {:.2}x its speed",
            super::report::label(r),
            level.cost_per_simulated_second / r.cost_per_simulated_second
        ),
        None => String::new(),
    };
    format!(
        "The cheapest monolithic level within {} of the finest: level {} ({:.3e} s per simulated s){against}. {BETWEEN_LEVELS}\n",
        report.tolerance, level.refinement, level.cost_per_simulated_second
    )
}

/// Why the cheapest level is not the cheapest monolithic mesh: levels double.
const BETWEEN_LEVELS: &str = "Levels double the elements: a monolithic mesh between this level and the one before may be within the tolerance at less cost (run the structure as one section, `--section NAME=nonlinear:N,...`, against the same reference before quoting a speed-up against it).";
