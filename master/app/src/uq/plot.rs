//! A UQ study's figures: Sobol' indices per input as bars with their bootstrap
//! intervals (like seed 000's Fig. 11), each output against each input over
//! the runs (like Fig. 8), the moments against the design size and the outputs'
//! distribution (Fig. 9).

use super::{Run, UqReport};
use crate::plot::PlotError;
use plotters::prelude::*;
use std::path::Path;

/// First-order (filled) and total (outlined) indices per input, one panel per
/// output, with the 95 % intervals as whiskers.
pub fn sobol_bars(path: &Path, report: &UqReport) -> Result<(), PlotError> {
    let fail = |e: &dyn std::fmt::Display| PlotError::new(path, e);
    let panels = report.outputs.len().max(1);
    let root = SVGBackend::new(path, (1000, 320 * panels as u32)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let d = report.inputs.len();
    for (area, o) in root.split_evenly((panels, 1)).iter().zip(&report.outputs) {
        let mut chart = ChartBuilder::on(area)
            .caption(format!("Sobol' indices of {}", o.name), ("sans-serif", 18))
            .margin(10)
            .x_label_area_size(30)
            .y_label_area_size(50)
            .build_cartesian_2d(-0.5..d as f64 - 0.5, 0.0..1.0)
            .map_err(|e| fail(&e))?;
        let names = report.inputs.clone();
        chart
            .configure_mesh()
            .x_labels(d)
            .x_label_formatter(&|x| {
                let k = x.round();
                if (x - k).abs() < 1e-6 && k >= 0.0 {
                    names.get(k as usize).cloned().unwrap_or_default()
                } else {
                    String::new()
                }
            })
            .y_desc("index")
            .draw()
            .map_err(|e| fail(&e))?;
        for i in 0..d {
            let x = i as f64;
            let bars = [
                (
                    x - 0.35,
                    x,
                    o.first_order[i],
                    o.intervals.first_order[i],
                    true,
                ),
                (x, x + 0.35, o.total[i], o.intervals.total[i], false),
            ];
            for (a, b, value, (lo, hi), filled) in bars {
                let style = if filled {
                    BLUE.filled()
                } else {
                    RED.stroke_width(2)
                };
                let mid = 0.5 * (a + b);
                chart
                    .draw_series([
                        Rectangle::new([(a, 0.0), (b, value.max(0.0))], style).into_dyn(),
                        PathElement::new(vec![(mid, lo.max(0.0)), (mid, hi.max(0.0))], BLACK)
                            .into_dyn(),
                    ])
                    .map_err(|e| fail(&e))?;
            }
        }
    }
    root.present().map_err(|e| fail(&e))
}

/// Each output against each input over the runs that succeeded.
pub fn scatter(path: &Path, report: &UqReport, runs: &[Run]) -> Result<(), PlotError> {
    let fail = |e: &dyn std::fmt::Display| PlotError::new(path, e);
    let (d, m) = (report.inputs.len(), report.outputs.len());
    let cols = d.clamp(1, 4);
    let rows = m * d.div_ceil(cols);
    let root =
        SVGBackend::new(path, (260 * cols as u32, 200 * rows.max(1) as u32)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let cells = root.split_evenly((rows.max(1), cols));
    let ok: Vec<&Run> = runs
        .iter()
        .filter(|r| r.1.iter().all(|v| v.is_finite()))
        .collect();
    for (k, o) in report.outputs.iter().enumerate() {
        for i in 0..d {
            let area = &cells[k * d.div_ceil(cols) * cols + i];
            let points: Vec<(f64, f64)> = ok.iter().map(|r| (r.0[i], r.1[k])).collect();
            let range = |f: fn(&(f64, f64)) -> f64| {
                let (lo, hi) = points
                    .iter()
                    .map(f)
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                        (a.min(v), b.max(v))
                    });
                if lo < hi { lo..hi } else { lo - 1.0..lo + 1.0 }
            };
            let mut chart = ChartBuilder::on(area)
                .margin(6)
                .x_label_area_size(25)
                .y_label_area_size(40)
                .build_cartesian_2d(range(|p| p.0), range(|p| p.1))
                .map_err(|e| fail(&e))?;
            chart
                .configure_mesh()
                .x_labels(3)
                .y_labels(4)
                .x_desc(report.inputs[i].as_str())
                .y_desc(o.name.as_str())
                .draw()
                .map_err(|e| fail(&e))?;
            chart
                .draw_series(points.iter().map(|&p| Circle::new(p, 2, BLUE.filled())))
                .map_err(|e| fail(&e))?;
        }
    }
    root.present().map_err(|e| fail(&e))
}

/// Each output's mean and mean +- sd against the design size (log2), one panel
/// per output: the moments' convergence as the nested design grows (Fig. 9).
pub fn convergence(path: &Path, report: &UqReport) -> Result<(), PlotError> {
    let fail = |e: &dyn std::fmt::Display| PlotError::new(path, e);
    let panels = report.outputs.len().max(1);
    let root = SVGBackend::new(path, (800, 280 * panels as u32)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    for (area, o) in root.split_evenly((panels, 1)).iter().zip(&report.outputs) {
        let sizes: Vec<f64> = o.convergence.iter().map(|c| c.0 as f64).collect();
        let (lo, hi) = o
            .convergence
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), c| {
                (a.min(c.1 - c.2), b.max(c.1 + c.2))
            });
        let (x0, x1) = (
            sizes.first().copied().unwrap_or(1.0),
            sizes.last().copied().unwrap_or(2.0),
        );
        let pad = 0.1 * (hi - lo).max(1e-9);
        let mut chart = ChartBuilder::on(area)
            .caption(
                format!("{}: mean and mean +- sd against the design size", o.name),
                ("sans-serif", 16),
            )
            .margin(10)
            .x_label_area_size(30)
            .y_label_area_size(50)
            .build_cartesian_2d((x0 / 1.2..x1 * 1.2).log_scale(), lo - pad..hi + pad)
            .map_err(|e| fail(&e))?;
        chart
            .configure_mesh()
            .x_desc("runs")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .draw()
            .map_err(|e| fail(&e))?;
        for (series, colour) in [
            (
                o.convergence
                    .iter()
                    .map(|c| (c.0 as f64, c.1))
                    .collect::<Vec<_>>(),
                BLUE,
            ),
            (
                o.convergence
                    .iter()
                    .map(|c| (c.0 as f64, c.1 + c.2))
                    .collect(),
                RED,
            ),
            (
                o.convergence
                    .iter()
                    .map(|c| (c.0 as f64, c.1 - c.2))
                    .collect(),
                RED,
            ),
        ] {
            chart
                .draw_series(LineSeries::new(series.clone(), colour.stroke_width(2)))
                .map_err(|e| fail(&e))?;
            chart
                .draw_series(series.iter().map(|&p| Circle::new(p, 4, colour.filled())))
                .map_err(|e| fail(&e))?;
        }
    }
    root.present().map_err(|e| fail(&e))
}

/// Each output's distribution: the runs' histogram (bars) and the expansion's
/// density (line), with the 5 %, 50 % and 95 % quantiles (Fig. 9's left half).
pub fn distribution(path: &Path, report: &UqReport, runs: &[Run]) -> Result<(), PlotError> {
    let fail = |e: &dyn std::fmt::Display| PlotError::new(path, e);
    let panels = report.outputs.len().max(1);
    let root = SVGBackend::new(path, (800, 280 * panels as u32)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    for (k, (area, o)) in root
        .split_evenly((panels, 1))
        .iter()
        .zip(&report.outputs)
        .enumerate()
    {
        let d = &o.distribution;
        let bins = d.density.len();
        let width = (d.upper - d.edges[0]) / bins as f64;
        let values: Vec<f64> = runs
            .iter()
            .map(|r| r.1[k])
            .filter(|v| v.is_finite())
            .collect();
        let (lo, hi) = values
            .iter()
            .fold((d.edges[0], d.upper), |(a, b), &v| (a.min(v), b.max(v)));
        let run_width = (hi - lo).max(1e-12) / 20.0;
        let mut counts = [0usize; 20];
        for v in &values {
            counts[(((v - lo) / run_width) as usize).min(19)] += 1;
        }
        let run_density: Vec<f64> = counts
            .iter()
            .map(|&c| c as f64 / (values.len().max(1) as f64 * run_width))
            .collect();
        let top = d
            .density
            .iter()
            .chain(&run_density)
            .copied()
            .fold(0.0, f64::max)
            .max(1e-12);
        let mut chart = ChartBuilder::on(area)
            .caption(
                format!("{}: runs (bars) and the expansion's density (line)", o.name),
                ("sans-serif", 16),
            )
            .margin(10)
            .x_label_area_size(30)
            .y_label_area_size(50)
            .build_cartesian_2d(lo..hi, 0.0..1.1 * top)
            .map_err(|e| fail(&e))?;
        chart
            .configure_mesh()
            .x_desc(o.name.as_str())
            .y_desc("density")
            .draw()
            .map_err(|e| fail(&e))?;
        chart
            .draw_series(run_density.iter().enumerate().map(|(b, &p)| {
                let a = lo + b as f64 * run_width;
                Rectangle::new([(a, 0.0), (a + run_width, p)], BLUE.mix(0.3).filled())
            }))
            .map_err(|e| fail(&e))?;
        let line = d
            .edges
            .iter()
            .zip(&d.density)
            .map(|(&a, &p)| (a + 0.5 * width, p));
        chart
            .draw_series(LineSeries::new(line, RED.stroke_width(2)))
            .map_err(|e| fail(&e))?;
        for q in d.quantiles {
            chart
                .draw_series([PathElement::new(vec![(q, 0.0), (q, 1.1 * top)], BLACK)])
                .map_err(|e| fail(&e))?;
        }
    }
    root.present().map_err(|e| fail(&e))
}
