//! Error against cost (log-log), the figure every study and fidelity study
//! writes: each run a numbered marker with a key beside the chart (never a
//! label over another or off the page), the Pareto front joined, and where
//! given the tolerance, the reference's cost and the chosen run.

use super::axes::{fitting, log_axis, positive_range};
use super::labels::{Area, CHAR_WIDTH, Entry, KEY_ROW, place_labels, side_legend};
use super::ticks;
use crate::plot::PlotError;
use crate::report::hover;
use plotters::prelude::*;
use std::path::Path;

/// One run in the figure.
pub struct Point {
    /// The run's settings or combination, for the key.
    pub label: String,
    /// Cost per simulated second (s/s).
    pub cost: f64,
    /// Its error (the worst over the quantities).
    pub error: f64,
}

/// What the figure shows besides the points.
pub struct Tradeoff<'a> {
    /// The figure's title.
    pub title: &'a str,
    /// The y axis: what the error is measured against.
    pub error_label: &'a str,
    /// The combinations or runs.
    pub points: Vec<Point>,
    /// The tolerance drawn as a line, when there is one.
    pub tolerance: Option<f64>,
    /// The reference's cost drawn as a line (s per simulated s).
    pub reference_cost: Option<f64>,
    /// The point to ring (the cheapest within the tolerance).
    pub chosen: Option<usize>,
}

/// Whether each point is on the Pareto front: no other point is at most as
/// costly and as wrong and better in one. Points that cannot be drawn
/// (non-positive or non-finite) are not.
pub fn pareto(points: &[Point]) -> Vec<bool> {
    let drawable =
        |p: &Point| p.cost.is_finite() && p.cost > 0.0 && p.error.is_finite() && p.error > 0.0;
    points
        .iter()
        .map(|p| {
            drawable(p)
                && !points.iter().any(|q| {
                    drawable(q)
                        && q.cost <= p.cost
                        && q.error <= p.error
                        && (q.cost < p.cost || q.error < p.error)
                })
        })
        .collect()
}

/// Draws the figure to `path` (SVG); returns each drawn point's pixel and
/// text, for a report's tooltips.
pub fn draw(path: &Path, figure: &Tradeoff<'_>) -> Result<Vec<hover::Point>, PlotError> {
    let fail = |e: &dyn std::fmt::Display| PlotError::new(path, e);
    let entries = key_entries(figure);
    let widest = entries.iter().map(|e| e.text.len()).max().unwrap_or(0) as i32;
    let key_width = (CHAR_WIDTH * (widest + 8)).clamp(220, 900) as u32;
    let rows = figure.points.len() as u32 + 6;
    let height = (80 + KEY_ROW as u32 * rows).max(650);
    let root = SVGBackend::new(path, (800 + key_width, height)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let root = root
        .titled(figure.title, ("sans-serif", 20))
        .map_err(|e| fail(&e))?;
    let (chart_area, key_area) = root.split_horizontally(800);
    let chart_area = chart_area.shrink((0, 0), (800, 600.min(height - 40)));
    let hover = chart(&chart_area, figure).map_err(|e| fail(&e))?;
    side_legend(&key_area, "runs", &entries).map_err(|e| fail(&e))?;
    root.present().map_err(|e| fail(&e))?;
    Ok(hover)
}

/// The chart: axes, front, tolerance, reference cost, numbered points; the
/// points' pixels and texts.
fn chart(
    area: &Area<'_>,
    figure: &Tradeoff<'_>,
) -> Result<Vec<hover::Point>, Box<dyn std::error::Error>> {
    let shown: Vec<(usize, (f64, f64))> = figure
        .points
        .iter()
        .enumerate()
        .filter(|(_, p)| p.cost.is_finite() && p.cost > 0.0 && p.error.is_finite() && p.error > 0.0)
        .map(|(k, p)| (k, (p.cost, p.error)))
        .collect();
    let (xlo, xhi) = positive_range(shown.iter().map(|s| s.1.0).chain(figure.reference_cost));
    let (ylo, yhi) = positive_range(shown.iter().map(|s| s.1.1).chain(figure.tolerance));
    let mut chart = ChartBuilder::on(area)
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(75)
        .build_cartesian_2d(log_axis(xlo, xhi, fitting(700, 6)), log_axis(ylo, yhi, 10))?;
    chart
        .configure_mesh()
        .x_desc("cost (s per simulated s)")
        .y_desc(figure.error_label)
        .x_label_formatter(&|v| ticks::log_label(*v))
        .y_label_formatter(&|v| ticks::log_label(*v))
        .draw()?;
    let front_flags = pareto(&figure.points);
    let mut front: Vec<(f64, f64)> = shown
        .iter()
        .filter(|s| front_flags[s.0])
        .map(|s| s.1)
        .collect();
    front.sort_by(|a, b| a.0.total_cmp(&b.0));
    chart.draw_series(LineSeries::new(front, RED.stroke_width(2)))?;
    if let Some(t) = figure.tolerance {
        chart.draw_series(LineSeries::new(
            [(xlo, t), (xhi, t)],
            BLUE.mix(0.5).stroke_width(1),
        ))?;
    }
    if let Some(c) = figure.reference_cost.filter(|c| c.is_finite() && *c > 0.0) {
        chart.draw_series(LineSeries::new(
            [(c, ylo), (c, yhi)],
            BLACK.mix(0.5).stroke_width(1),
        ))?;
    }
    for (k, p) in &shown {
        let colour = if front_flags[*k] { RED } else { BLACK };
        chart.draw_series([Circle::new(*p, 4, colour.filled())])?;
    }
    if let Some(p) = figure.chosen.and_then(|k| shown.iter().find(|s| s.0 == k)) {
        chart.draw_series([Circle::new(p.1, 9, GREEN.stroke_width(2))])?;
    }
    let pixels: Vec<(i32, i32)> = shown.iter().map(|s| chart.backend_coord(&s.1)).collect();
    let numbers: Vec<String> = shown.iter().map(|s| (s.0 + 1).to_string()).collect();
    let lengths: Vec<usize> = numbers.iter().map(String::len).collect();
    let (xr, yr) = chart.plotting_area().get_pixel_range();
    let corners = place_labels(&pixels, &lengths, (xr.start, yr.start, xr.end, yr.end));
    let offset = area.get_base_pixel();
    for (number, (x, y)) in numbers.into_iter().zip(corners) {
        area.draw(&Text::new(
            number,
            (x - offset.0, y - offset.1),
            ("sans-serif", 12),
        ))?;
    }
    let hover = (shown.iter().zip(&pixels))
        .map(|((k, (cost, error)), &(x, y))| hover::Point {
            x,
            y,
            text: format!(
                "{}: {} (error {error:.3e}, cost {cost:.3e} s/s)",
                k + 1,
                figure.points[*k].label
            ),
        })
        .collect();
    Ok(hover)
}

/// The key: what the lines and markers are, then each run by its number.
fn key_entries(figure: &Tradeoff<'_>) -> Vec<Entry> {
    let mut entries = vec![Entry {
        text: "Pareto front".into(),
        colour: RED.to_rgba(),
        marker: false,
    }];
    if let Some(t) = figure.tolerance {
        entries.push(Entry {
            text: format!("tolerance {t}"),
            colour: BLUE.mix(0.5),
            marker: false,
        });
    }
    if figure.reference_cost.is_some() {
        entries.push(Entry {
            text: "reference's cost".into(),
            colour: BLACK.mix(0.5),
            marker: false,
        });
    }
    if let Some(k) = figure.chosen {
        entries.push(Entry {
            text: format!("{}: cheapest within tolerance", k + 1),
            colour: GREEN.to_rgba(),
            marker: true,
        });
    }
    for (k, p) in figure.points.iter().enumerate() {
        let note = match (
            p.cost.is_finite() && p.cost > 0.0,
            p.error.is_finite() && p.error > 0.0,
        ) {
            (true, true) => String::new(),
            (_, false) if p.error == 0.0 => " (error 0: a reference, off the log axis)".into(),
            _ => format!(" (error {:.1e}, cost {:.1e}: not drawn)", p.error, p.cost),
        };
        entries.push(Entry {
            text: format!("{:>3}  {}{note}", k + 1, p.label),
            colour: WHITE.to_rgba(),
            marker: false,
        });
    }
    entries
}
