//! A fidelity study as CSV, Markdown and a figure of worst error against cost
//! with the Pareto front and the cheapest combination within the tolerance.

use super::{FidelityReport, FidelityRow};
use crate::plot::PlotError;
use plotters::prelude::*;
use std::path::Path;

/// A row's combination as `section=choice` pairs.
fn label(r: &FidelityRow) -> String {
    r.combination
        .iter()
        .map(|(s, c)| format!("{s}={c}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// The rows as CSV: combination, epsilon per quantity, worst, cost, speed-up,
/// iterations per step, non-converged steps, the start check's change,
/// Pareto, within tolerance, error.
pub fn to_csv(report: &FidelityReport) -> String {
    let eps: Vec<String> = report
        .quantities
        .iter()
        .map(|n| format!("epsilon_{n}"))
        .collect();
    let mut out = format!(
        "combination,reference,{},worst_epsilon,cost_per_simulated_second,cost_spread,speed_up,iterations_per_step,non_converged_steps,start_change,pareto,within_tolerance,error\n",
        eps.join(",")
    );
    for r in &report.rows {
        let eps: Vec<String> = r.errors.iter().map(|(_, e)| format!("{e:e}")).collect();
        out += &format!(
            "{},{},{},{:e},{:e},{},{},{},{},{},{},{},{}\n",
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
            r.error.as_deref().unwrap_or("").replace([',', '\n'], ";")
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
    out
}

/// The sentence naming the cheapest combination within the tolerance.
pub fn conclusion(report: &FidelityReport) -> String {
    let verdict = verdict(report);
    match super::floors::note(&report.floors) {
        Some(note) => format!("{verdict}\n{note}"),
        None => verdict,
    }
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
fn judged(report: &FidelityReport) -> String {
    if report.judged.len() == report.quantities.len() {
        "every quantity".into()
    } else {
        report.judged.join(", ")
    }
}

/// Worst epsilon against cost per simulated second (log-log): every
/// combination labelled, the Pareto front joined, the cheapest within the
/// tolerance ringed, the tolerance and the reference's cost as lines.
pub fn plot(path: &Path, title: &str, report: &FidelityReport) -> Result<(), PlotError> {
    let fail = |e: &dyn std::fmt::Display| PlotError::new(path, e);
    let usable: Vec<&FidelityRow> = report
        .rows
        .iter()
        .filter(|r| {
            !r.reference && r.error.is_none() && r.worst_error.is_finite() && r.worst_error > 0.0
        })
        .collect();
    let costs = report
        .rows
        .iter()
        .map(|r| r.cost_per_simulated_second)
        .filter(|c| c.is_finite() && *c > 0.0);
    let (xlo, xhi) = costs.fold((f64::INFINITY, 0.0f64), |(a, b), c| (a.min(c), b.max(c)));
    let (ylo, yhi) = usable
        .iter()
        .map(|r| r.worst_error)
        .chain([report.tolerance])
        .fold((f64::INFINITY, 0.0f64), |(a, b), e| (a.min(e), b.max(e)));
    let (xlo, xhi) = if xlo.is_finite() {
        (xlo / 2.0, xhi * 2.0)
    } else {
        (1e-3, 1.0)
    };
    let root = SVGBackend::new(path, (1000, 650)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 18))
        .margin(15)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d((xlo..xhi).log_scale(), (ylo / 3.0..yhi * 3.0).log_scale())
        .map_err(|e| fail(&e))?;
    chart
        .configure_mesh()
        .x_desc("cost (s per simulated s)")
        .y_desc("worst epsilon against the monolithic reference")
        .x_label_formatter(&|v| format!("{v:.1e}"))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .draw()
        .map_err(|e| fail(&e))?;
    let mut front: Vec<(f64, f64)> = usable
        .iter()
        .filter(|r| r.pareto)
        .map(|r| point(r))
        .collect();
    front.sort_by(|a, b| a.0.total_cmp(&b.0));
    chart
        .draw_series(LineSeries::new(front, RED.stroke_width(2)))
        .map_err(|e| fail(&e))?
        .label("Pareto front")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED));
    chart
        .draw_series(LineSeries::new(
            [(xlo, report.tolerance), (xhi, report.tolerance)],
            BLUE.mix(0.5).stroke_width(1),
        ))
        .map_err(|e| fail(&e))?
        .label(format!("tolerance {}", report.tolerance))
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE.mix(0.5)));
    draw_reference_cost(&mut chart, report, (ylo / 3.0, yhi * 3.0)).map_err(|e| fail(&e))?;
    draw_points(&mut chart, report, &usable).map_err(|e| fail(&e))?;
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
        .map_err(|e| fail(&e))?;
    root.present().map_err(|e| fail(&e))
}

/// A row's place in the figure: (cost, worst epsilon).
fn point(r: &FidelityRow) -> (f64, f64) {
    (r.cost_per_simulated_second, r.worst_error)
}

type LogLog<'a> = ChartContext<
    'a,
    SVGBackend<'a>,
    Cartesian2d<
        plotters::coord::combinators::LogCoord<f64>,
        plotters::coord::combinators::LogCoord<f64>,
    >,
>;

/// Every usable combination as a labelled point (red on the Pareto front), the
/// cheapest within the tolerance ringed.
fn draw_points(
    chart: &mut LogLog<'_>,
    report: &FidelityReport,
    usable: &[&FidelityRow],
) -> Result<(), Box<dyn std::error::Error>> {
    for r in usable {
        let colour = if r.pareto { RED } else { BLACK };
        chart.draw_series([
            Circle::new(point(r), 4, colour.filled()).into_dyn(),
            Text::new(label(r), point(r), ("sans-serif", 11)).into_dyn(),
        ])?;
    }
    if let Some(r) = report.cheapest.map(|k| &report.rows[k]) {
        chart
            .draw_series([Circle::new(point(r), 9, GREEN.stroke_width(2))])?
            .label("cheapest within tolerance")
            .legend(|(x, y)| Circle::new((x + 10, y), 5, GREEN.stroke_width(2)));
    }
    Ok(())
}

/// The reference's cost as a vertical line over `(ylo, yhi)`.
fn draw_reference_cost(
    chart: &mut LogLog<'_>,
    report: &FidelityReport,
    (ylo, yhi): (f64, f64),
) -> Result<(), Box<dyn std::error::Error>> {
    if let Some(r) = report.rows.iter().find(|r| r.reference) {
        let c = r.cost_per_simulated_second;
        if c.is_finite() && c > 0.0 {
            chart
                .draw_series(LineSeries::new(
                    [(c, ylo), (c, yhi)],
                    BLACK.mix(0.5).stroke_width(1),
                ))?
                .label("reference's cost")
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.mix(0.5)));
        }
    }
    Ok(())
}
