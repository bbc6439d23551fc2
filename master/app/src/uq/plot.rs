//! A UQ study's figures: Sobol' indices per input as bars with their bootstrap
//! intervals (like seed 000's Fig. 11), each output against each input over
//! the runs (like Fig. 8), the moments against the design size and the outputs'
//! distribution (Fig. 9).

use super::{Run, UqReport};
use crate::figures::axes::linear_axis;
use crate::figures::labels::{Area, DrawResult, Entry, side_legend};
use crate::figures::ticks;
use crate::plot::PlotError;
use plotters::prelude::*;
use std::path::Path;

/// First-order (filled) and total (outlined) indices per input, one panel per
/// output, with the 95 % intervals as whiskers.
pub fn sobol_bars(path: &Path, report: &UqReport) -> Result<(), PlotError> {
    let fail = |e: &dyn std::fmt::Display| PlotError::new(path, e);
    let panels = report.outputs.len().max(1);
    let root = SVGBackend::new(path, (1200, 320 * panels as u32)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let d = report.inputs.len();
    let entries = [
        Entry {
            text: "first order".into(),
            colour: BLUE.to_rgba(),
            marker: true,
        },
        Entry {
            text: "total".into(),
            colour: RED.to_rgba(),
            marker: true,
        },
        Entry {
            text: "95 % bootstrap interval".into(),
            colour: BLACK.to_rgba(),
            marker: false,
        },
    ];
    for (area, o) in root.split_evenly((panels, 1)).iter().zip(&report.outputs) {
        let (area, legend) = area.split_horizontally(950);
        side_legend(&legend, "", &entries).map_err(|e| fail(&e))?;
        let mut chart = ChartBuilder::on(&area)
            .caption(format!("Sobol' indices of {}", o.name), ("sans-serif", 18))
            .margin(10)
            .x_label_area_size(45)
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
            .x_desc("input")
            .y_desc("Sobol' index (-)")
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

/// Each output against each input: the stable runs in blue, the unstable
/// ones in red at the phi the expansions count them at.
pub fn scatter(path: &Path, report: &UqReport, runs: &[Run]) -> Result<(), PlotError> {
    let fail = |e: &dyn std::fmt::Display| PlotError::new(path, e);
    let (d, m) = (report.inputs.len(), report.outputs.len());
    let cols = d.clamp(1, 4);
    let rows = m * d.div_ceil(cols);
    let root =
        SVGBackend::new(path, (260 * cols as u32, 200 * rows.max(1) as u32)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let cells = root.split_evenly((rows.max(1), cols));
    let floor = report.stability.as_ref().map_or(0.0, |s| s.counted_as);
    for (k, o) in report.outputs.iter().enumerate() {
        for i in 0..d {
            let area = &cells[k * d.div_ceil(cols) * cols + i];
            // Stable runs as circles, unstable ones as crosses: each once.
            let (unstable, stable): (Vec<&Run>, Vec<&Run>) =
                runs.iter().partition(|r| r.unstable());
            let at = |group: &[&Run]| -> Vec<(f64, f64)> {
                (group.iter())
                    .filter_map(|r| r.counted(k, floor).map(|y| (r.inputs[i], y)))
                    .collect()
            };
            let (points, unstable) = (at(&stable), at(&unstable));
            let range = |f: fn(&(f64, f64)) -> f64| {
                let (lo, hi) = (points.iter().chain(&unstable))
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
            chart
                .draw_series(unstable.iter().map(|&p| Cross::new(p, 3, RED)))
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
    let root = SVGBackend::new(path, (1050, 280 * panels as u32)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    for (area, o) in root.split_evenly((panels, 1)).iter().zip(&report.outputs) {
        let (area, legend) = area.split_horizontally(800);
        side_legend(&legend, "", &convergence_key(o.convergence.len())).map_err(|e| fail(&e))?;
        moments_chart(&area, o).map_err(|e| fail(&e))?;
    }
    root.present().map_err(|e| fail(&e))
}

/// The convergence figure's key, with a note where the design has one size.
fn convergence_key(sizes: usize) -> Vec<Entry> {
    let mut entries = vec![
        Entry {
            text: "mean".into(),
            colour: BLUE.to_rgba(),
            marker: false,
        },
        Entry {
            text: "mean +- standard deviation".into(),
            colour: RED.to_rgba(),
            marker: false,
        },
    ];
    if sizes < 2 {
        for note in [
            "one design size so far: uq again with",
            "--samples twice as large adds one",
        ] {
            entries.push(Entry {
                text: note.into(),
                colour: WHITE.to_rgba(),
                marker: false,
            });
        }
    }
    entries
}

/// One output's mean and mean +- sd at each design size (ticked at the sizes).
fn moments_chart(area: &Area<'_>, o: &super::OutputResult) -> DrawResult {
    let sizes: Vec<f64> = o.convergence.iter().map(|c| c.0 as f64).collect();
    let (lo, hi) = (o.convergence.iter()).fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), c| {
        (a.min(c.1 - c.2), b.max(c.1 + c.2))
    });
    let (x0, x1) = (
        sizes.first().copied().unwrap_or(1.0),
        sizes.last().copied().unwrap_or(2.0),
    );
    let pad = 0.1 * (hi - lo).max(1e-9);
    let (y, y_step) = y_axis(lo - pad, hi + pad);
    let mut chart = ChartBuilder::on(area)
        .caption(
            format!("{}: mean and mean +- sd against the design size", o.name),
            ("sans-serif", 16),
        )
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d((x0 / 2.0..x1 * 2.0).log_scale().with_key_points(sizes), y)?;
    chart
        .configure_mesh()
        .x_desc("runs in the design")
        .y_desc(o.name.as_str())
        .x_label_formatter(&|v| format!("{v:.0}"))
        .y_label_formatter(&|v| ticks::linear_label(*v, y_step))
        .draw()?;
    for (sign, colour) in [(0.0, BLUE), (1.0, RED), (-1.0, RED)] {
        let series: Vec<(f64, f64)> = (o.convergence.iter())
            .map(|c| (c.0 as f64, c.1 + sign * c.2))
            .collect();
        chart.draw_series(LineSeries::new(series.clone(), colour.stroke_width(2)))?;
        chart.draw_series(series.iter().map(|&p| Circle::new(p, 4, colour.filled())))?;
    }
    Ok(())
}

/// Each output's distribution: the runs' histogram (bars) and the expansion's
/// density (line), with the 5 %, 50 % and 95 % quantiles (Fig. 9's left half).
pub fn distribution(path: &Path, report: &UqReport, runs: &[Run]) -> Result<(), PlotError> {
    let fail = |e: &dyn std::fmt::Display| PlotError::new(path, e);
    let panels = report.outputs.len().max(1);
    let root = SVGBackend::new(path, (1050, 280 * panels as u32)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let entries = [
        Entry {
            text: "runs (histogram)".into(),
            colour: BLUE.mix(0.3),
            marker: true,
        },
        Entry {
            text: "the expansion's density".into(),
            colour: RED.to_rgba(),
            marker: false,
        },
        Entry {
            text: "5 %, 50 %, 95 % quantiles".into(),
            colour: BLACK.to_rgba(),
            marker: false,
        },
    ];
    let panels = root.split_evenly((panels, 1));
    for (k, (area, o)) in panels.iter().zip(&report.outputs).enumerate() {
        let (area, legend) = area.split_horizontally(800);
        side_legend(&legend, "", &entries).map_err(|e| fail(&e))?;
        let floor = report.stability.as_ref().map_or(0.0, |s| s.counted_as);
        let values: Vec<f64> = runs.iter().filter_map(|r| r.counted(k, floor)).collect();
        density_chart(&area, o, &values).map_err(|e| fail(&e))?;
    }
    root.present().map_err(|e| fail(&e))
}

/// The runs' histogram (20 bins over the runs and the expansion's range) as
/// a density: the bins' left edges, their width and the densities.
fn histogram(values: &[f64], (lo, hi): (f64, f64)) -> (f64, Vec<f64>) {
    let width = (hi - lo).max(1e-12) / 20.0;
    let mut counts = [0usize; 20];
    for v in values {
        counts[(((v - lo) / width) as usize).min(19)] += 1;
    }
    let density = counts
        .iter()
        .map(|&c| c as f64 / (values.len().max(1) as f64 * width))
        .collect();
    (width, density)
}

/// One output's histogram, expansion density and quantiles.
fn density_chart(area: &Area<'_>, o: &super::OutputResult, values: &[f64]) -> DrawResult {
    let d = &o.distribution;
    let width = (d.upper - d.edges[0]) / d.density.len() as f64;
    let (lo, hi) = values
        .iter()
        .fold((d.edges[0], d.upper), |(a, b), &v| (a.min(v), b.max(v)));
    let (run_width, run_density) = histogram(values, (lo, hi));
    let top = d
        .density
        .iter()
        .chain(&run_density)
        .copied()
        .fold(0.0, f64::max)
        .max(1e-12);
    let ((x, x_step), (y, y_step)) = (y_axis(lo, hi), y_axis(0.0, 1.1 * top));
    let mut chart = ChartBuilder::on(area)
        .caption(
            format!("{}: runs (bars) and the expansion's density (line)", o.name),
            ("sans-serif", 16),
        )
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(x, y)?;
    chart
        .configure_mesh()
        .x_desc(o.name.as_str())
        .y_desc("probability density (1 / the output's unit)")
        .x_label_formatter(&|v| ticks::linear_label(*v, x_step))
        .y_label_formatter(&|v| ticks::linear_label(*v, y_step))
        .draw()?;
    chart.draw_series(run_density.iter().enumerate().map(|(b, &p)| {
        let a = lo + b as f64 * run_width;
        Rectangle::new([(a, 0.0), (a + run_width, p)], BLUE.mix(0.3).filled())
    }))?;
    let line = d
        .edges
        .iter()
        .zip(&d.density)
        .map(|(&a, &p)| (a + 0.5 * width, p));
    chart.draw_series(LineSeries::new(line, RED.stroke_width(2)))?;
    for q in d.quantiles {
        chart.draw_series([PathElement::new(vec![(q, 0.0), (q, 1.1 * top)], BLACK)])?;
    }
    Ok(())
}

/// A linear axis of six 1-2-5 ticks and its step.
fn y_axis(lo: f64, hi: f64) -> (crate::figures::axes::Ticked, f64) {
    linear_axis(lo, hi, 6)
}
