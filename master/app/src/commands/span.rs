//! `slender span bode|study|coupling`: the suspended span of seed 004 ch. 5.

use super::{CliError, count_in, positive, report_written, results_folder};
use crate::cli::SpanAction;
use slender_app::span_study::StudyPlan;
use slender_app::{coupling_study, span_study};
use slender_units::span::transfer::Span;
use std::path::{Path, PathBuf};

/// Runs one span action and writes its report and figure into `out`.
pub(super) fn span(span: &Span, action: SpanAction, out: &Path) -> Result<(), CliError> {
    span.validate()
        .map_err(|e| CliError::input(e.to_string()))?;
    let coupled = matches!(action, SpanAction::Coupling { .. });
    let files = match action {
        SpanAction::Bode { order, elements } => bode(span, order, elements, out)?,
        SpanAction::Study {
            duration,
            step,
            reference_elements,
            reference_substeps,
            fe_substeps,
        }
        | SpanAction::Coupling {
            duration,
            step,
            reference_elements,
            reference_substeps,
            fe_substeps,
        } => {
            let (orders, elements) = if coupled {
                (
                    coupling_study::ORDERS.to_vec(),
                    coupling_study::ELEMENTS.to_vec(),
                )
            } else {
                (span_study::ORDERS.to_vec(), span_study::ELEMENTS.to_vec())
            };
            let plan = StudyPlan {
                orders,
                elements,
                ..plan(
                    duration,
                    step,
                    reference_elements,
                    reference_substeps,
                    fe_substeps,
                )?
            };
            let _lock = results_folder(out)?;
            let study = if coupled { coupling } else { siso_study };
            study(span, &plan, out).map_err(CliError::failure)?
        }
    };
    report_written(&files);
    Ok(())
}

/// A study plan's common settings from the command line, checked; no orders or
/// element counts yet.
fn plan(
    duration: f64,
    step: f64,
    reference_elements: usize,
    reference_substeps: usize,
    fe_substeps: Vec<usize>,
) -> Result<StudyPlan, CliError> {
    let (duration, step) = (positive("--duration", duration)?, positive("--step", step)?);
    let reference_elements = count_in("--reference-elements", reference_elements, 1, 1024)?;
    let reference_substeps = count_in("--reference-substeps", reference_substeps, 1, 1024)?;
    for n in &fe_substeps {
        count_in("--fe-substeps", *n, 1, 1024)?;
    }
    Ok(StudyPlan {
        orders: Vec::new(),
        elements: Vec::new(),
        fe_substeps,
        reference_elements,
        reference_substeps,
        duration,
        step,
    })
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
    let _lock = results_folder(out)?;
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
    slender_app::whole::through(&path, |f| {
        slender_app::plot::bode(f, &title, &omegas, &series)
    })
    .map_err(CliError::failure)?;
    Ok(vec![path])
}

fn siso_study(span: &Span, plan: &StudyPlan, out: &Path) -> Result<Vec<PathBuf>, String> {
    let report = span_study::study(span, plan, &out.join("scenes")).map_err(|e| e.to_string())?;
    let points: Vec<(String, f64, f64)> = report
        .rows
        .iter()
        .map(|r| (r.label(), r.cost_per_simulated_second, r.error_sines))
        .collect();
    let figure = Figure {
        stem: "accuracy_cost",
        title: "Span: error against cost per simulated second",
        error_label: "error vs the continuum (sum of sines)",
    };
    let markdown = span_study::to_markdown(&report);
    write_study_report(out, "span_study", &markdown, &report, &figure, &points)
}

fn coupling(span: &Span, plan: &StudyPlan, out: &Path) -> Result<Vec<PathBuf>, String> {
    let report = coupling_study::coupling_study(span, plan, &out.join("scenes"))
        .map_err(|e| e.to_string())?;
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
    let figure = Figure {
        stem: "coupling_accuracy_cost",
        title: "Span between two sections: error against cost per simulated second",
        error_label: "largest error of the four outputs vs the continuum",
    };
    let markdown = coupling_study::to_markdown(&report);
    write_study_report(out, "coupling_study", &markdown, &report, &figure, &points)
}

/// The error-against-cost figure of a study: its file stem and labels.
struct Figure {
    stem: &'static str,
    title: &'static str,
    error_label: &'static str,
}

/// Prints a study's Markdown and writes it as `<stem>.md`, the report as
/// `<stem>.json` and the error-against-cost figure of `points` into `out`;
/// returns the three paths.
fn write_study_report(
    out: &Path,
    stem: &str,
    markdown: &str,
    report: &impl serde::Serialize,
    figure: &Figure,
    points: &[(String, f64, f64)],
) -> Result<Vec<PathBuf>, String> {
    print!("{markdown}");
    let (md, json, svg) = (
        out.join(format!("{stem}.md")),
        out.join(format!("{stem}.json")),
        out.join(format!("{}.svg", figure.stem)),
    );
    slender_app::whole::write(&md, markdown).map_err(|e| format!("{}: {e}", md.display()))?;
    let text = serde_json::to_string_pretty(report).map_err(|e| e.to_string())?;
    slender_app::whole::write(&json, text).map_err(|e| format!("{}: {e}", json.display()))?;
    slender_app::whole::through(&svg, |f| {
        slender_app::plot::accuracy_cost(f, figure.title, figure.error_label, points)
    })
    .map_err(|e| e.to_string())?;
    Ok(vec![md, json, svg])
}
