//! `slender span bode|study|coupling`: the suspended span of seed 004 ch. 5.

use super::{CliError, count_in, positive, report_written, results_folder};
use crate::cli::SpanAction;
use slender_app::{coupling_study, span_study};
use slender_units::span::transfer::Span;
use std::path::{Path, PathBuf};

/// Runs one span action and writes its report and figure into `out`.
pub fn span(span: &Span, action: SpanAction, out: &Path) -> Result<(), CliError> {
    span.validate()
        .map_err(|e| CliError::input(e.to_string()))?;
    let files = match action {
        SpanAction::Bode { order, elements } => bode(span, order, elements, out)?,
        SpanAction::Study {
            duration,
            step,
            reference_elements,
            reference_substeps,
            fe_substeps,
        } => {
            let plan = span_study::StudyPlan::standard(
                positive("--duration", duration)?,
                positive("--step", step)?,
                count_in("--reference-elements", reference_elements, 1, 1024)?,
                count_in("--reference-substeps", reference_substeps, 1, 1024)?,
                substeps(fe_substeps)?,
            );
            results_folder(out)?;
            siso_study(span, &plan, out).map_err(CliError::failure)?
        }
        SpanAction::Coupling {
            duration,
            step,
            reference_elements,
            reference_substeps,
            fe_substeps,
        } => {
            let plan = coupling_study::CouplingPlan::standard(
                positive("--duration", duration)?,
                positive("--step", step)?,
                count_in("--reference-elements", reference_elements, 1, 1024)?,
                count_in("--reference-substeps", reference_substeps, 1, 1024)?,
                substeps(fe_substeps)?,
            );
            results_folder(out)?;
            coupling(span, &plan, out).map_err(CliError::failure)?
        }
    };
    report_written(&files);
    Ok(())
}

fn substeps(list: Vec<usize>) -> Result<Vec<usize>, CliError> {
    for n in &list {
        count_in("--fe-substeps", *n, 1, 1024)?;
    }
    Ok(list)
}

/// The Bode plot of H_{U2 -> U5} at one order (even, 2 to 24, as span units
/// offer) with an FE span of 1 to 1024 elements.
fn bode(span: &Span, order: usize, elements: usize, out: &Path) -> Result<Vec<PathBuf>, CliError> {
    if !(2..=24).contains(&order) || order % 2 != 0 {
        return Err(CliError::input(format!(
            "--order {order}: expected an even order from 2 to 24"
        )));
    }
    let elements = count_in("--elements", elements, 1, 1024)?;
    results_folder(out)?;
    let omegas: Vec<f64> = (0..600)
        .map(|k| 10f64.powf(-2.0 + 4.398 * k as f64 / 599.0))
        .collect();
    let series =
        span_study::bode_series(span, order, elements, &omegas).map_err(CliError::failure)?;
    let path = out.join("bode.svg");
    let title = format!(
        "H_U2->U5: EI = {}, mu = {}, c_d = {}, L = {}",
        span.flexural_rigidity, span.mass_per_length, span.damping_per_length, span.length
    );
    slender_app::plot::bode(&path, &title, &omegas, &series).map_err(CliError::failure)?;
    Ok(vec![path])
}

fn siso_study(
    span: &Span,
    plan: &span_study::StudyPlan,
    out: &Path,
) -> Result<Vec<PathBuf>, String> {
    let report = span_study::study(span, plan).map_err(|e| e.to_string())?;
    let (md, json, svg) = write_study_report(
        out,
        "span_study",
        "accuracy_cost",
        &span_study::to_markdown(&report),
        &report,
    )?;
    let points: Vec<(String, f64, f64)> = report
        .rows
        .iter()
        .map(|r| (r.label(), r.cost_per_simulated_second, r.error_sines))
        .collect();
    slender_app::plot::accuracy_cost(
        &svg,
        "Span: error against cost per simulated second",
        "error vs the continuum (sum of sines)",
        &points,
    )
    .map_err(|e| e.to_string())?;
    Ok(vec![md, json, svg])
}

fn coupling(
    span: &Span,
    plan: &coupling_study::CouplingPlan,
    out: &Path,
) -> Result<Vec<PathBuf>, String> {
    let report = coupling_study::coupling_study(span, plan).map_err(|e| e.to_string())?;
    let (md, json, svg) = write_study_report(
        out,
        "coupling_study",
        "coupling_accuracy_cost",
        &coupling_study::to_markdown(&report),
        &report,
    )?;
    let points: Vec<(String, f64, f64)> = report
        .rows
        .iter()
        .map(|r| {
            let label = match (r.model.as_str(), r.substeps) {
                ("fe", 1) => "fe".to_string(),
                ("fe", n) => format!("fe ({n} substeps)"),
                (m, _) => format!("span_coupling {m}"),
            };
            let worst = r.errors.iter().fold(0.0f64, |a, &e| a.max(e));
            (label, r.cost_per_simulated_second, worst)
        })
        .collect();
    slender_app::plot::accuracy_cost(
        &svg,
        "Span between two sections: error against cost per simulated second",
        "largest error of the four outputs vs the continuum",
        &points,
    )
    .map_err(|e| e.to_string())?;
    Ok(vec![md, json, svg])
}

/// Prints a study's Markdown and writes it as `<stem>.md` with the report as
/// `<stem>.json` into `out`; returns those paths and the path for its plot,
/// `<plot>.svg`.
fn write_study_report(
    out: &Path,
    stem: &str,
    plot: &str,
    markdown: &str,
    report: &impl serde::Serialize,
) -> Result<(PathBuf, PathBuf, PathBuf), String> {
    print!("{markdown}");
    let (md, json, svg) = (
        out.join(format!("{stem}.md")),
        out.join(format!("{stem}.json")),
        out.join(format!("{plot}.svg")),
    );
    std::fs::write(&md, markdown).map_err(|e| format!("{}: {e}", md.display()))?;
    let text = serde_json::to_string_pretty(report).map_err(|e| e.to_string())?;
    std::fs::write(&json, text).map_err(|e| format!("{}: {e}", json.display()))?;
    Ok((md, json, svg))
}
