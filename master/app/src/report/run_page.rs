//! A run's report page: its outcome, the coupling's counters, the indicators,
//! the warnings, each signal's unit (and statistics, when the scene asks for
//! them) and every figure.

use super::Part;
use crate::run::Summary;
use std::path::PathBuf;

/// The parts of a run's page: the summary as tables, then the figures.
pub fn parts(summary: &Summary, figures: &[PathBuf]) -> Vec<Part> {
    let c = &summary.counters;
    let iterations = if c.steps > 0 {
        c.iterations as f64 / c.steps as f64
    } else {
        f64::NAN
    };
    let mut md = format!(
        "| status | simulated (s) | step (s) | cost (s per simulated s) | steps | iterations per step | non-converged steps | rollbacks |\n|---|---|---|---|---|---|---|---|\n| {} | {} | {} | {:.3e} | {} | {iterations:.2} | {} | {} |\n\n",
        summary.status,
        summary.simulated_s,
        summary.step_s,
        summary.cost_per_simulated_second,
        c.steps,
        c.non_converged_steps,
        c.rollbacks
    );
    if let Some(error) = &summary.error {
        md += &format!("Error: {}\n\n", error.replace('\n', " "));
    }
    for warning in &summary.warnings {
        md += &format!("Warning: {}\n\n", warning.replace('\n', " "));
    }
    if !summary.indicators.is_empty() {
        md += "| indicator | relative error epsilon | fidelity phi |\n|---|---|---|\n";
        for i in &summary.indicators {
            md += &format!(
                "| {} | {:.3e} | {:.3} |\n",
                i.name, i.relative_error, i.fidelity
            );
        }
        md += "\n";
    }
    md += &units_and_statistics(summary);
    let mut parts = vec![Part::Heading(summary.title.clone()), Part::Markdown(md)];
    parts.extend(figures.iter().map(|f| Part::figure(f, Vec::new())));
    parts
}

/// A row per recorded signal: its unit, and with `[output] statistics` its
/// statistics over the window asked for.
fn units_and_statistics(summary: &Summary) -> String {
    if summary.statistics.is_empty() {
        let mut md = "| signal | unit |\n|---|---|\n".to_owned();
        for (signal, unit) in &summary.units {
            md += &format!(
                "| {signal} | {} |\n",
                if unit.is_empty() { "-" } else { unit }
            );
        }
        return md;
    }
    let mut md = "| signal | unit | mean | standard deviation | skewness | kurtosis | min | max | zero-up-crossing period (s) |\n|---|---|---|---|---|---|---|---|---|\n".to_owned();
    for (signal, unit) in &summary.units {
        let unit = if unit.is_empty() { "-" } else { unit };
        let Some(s) = summary.statistics.get(signal) else {
            md += &format!("| {signal} | {unit} | | | | | | | |\n");
            continue;
        };
        let period = s
            .zero_up_crossing_period
            .map_or("-".to_owned(), |t| format!("{t:.3}"));
        md += &format!(
            "| {signal} | {unit} | {:.4e} | {:.4e} | {:.3} | {:.3} | {:.4e} | {:.4e} | {period} |\n",
            s.mean, s.std_dev, s.skewness, s.kurtosis, s.min, s.max
        );
    }
    md
}
