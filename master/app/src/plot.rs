//! SVG figures of recorded time series (plotters, SVG backend: no fonts needed).

use crate::record::Recorder;
use plotters::prelude::*;
use std::path::Path;

/// A figure that could not be drawn or written: its file and why.
#[derive(Debug, thiserror::Error)]
#[error("{path}: {reason}")]
pub struct PlotError {
    pub path: String,
    pub reason: String,
}

impl From<crate::whole::RenameError> for PlotError {
    fn from(e: crate::whole::RenameError) -> PlotError {
        PlotError::new(&e.path, &e.source)
    }
}

impl PlotError {
    pub(crate) fn new(path: &Path, reason: &dyn std::fmt::Display) -> PlotError {
        PlotError {
            path: path.display().to_string(),
            reason: reason.to_string(),
        }
    }
}

/// A tick label: plain for moderate magnitudes, engineering notation otherwise.
fn tick(v: f64) -> String {
    let a = v.abs();
    if a != 0.0 && !(1e-2..1e4).contains(&a) {
        format!("{v:.2e}")
    } else {
        format!("{v:.3}")
    }
}

/// Draws stacked panels; each panel overlays the named recorded signals against time.
pub fn time_series(
    path: &Path,
    title: &str,
    recorder: &Recorder,
    panels: &[Vec<String>],
) -> Result<(), PlotError> {
    let height = 60 + 220 * panels.len() as u32;
    let root = SVGBackend::new(path, (1000, height)).into_drawing_area();
    let fail = |e: &dyn std::fmt::Display| PlotError::new(path, e);
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let root = root
        .titled(title, ("sans-serif", 22))
        .map_err(|e| fail(&e))?;
    let areas = root.split_evenly((panels.len(), 1));
    let (t0, t1) = match (recorder.time.first(), recorder.time.last()) {
        (Some(&a), Some(&b)) if b > a => (a, b),
        _ => return Err(PlotError::new(path, &"nothing recorded to plot")),
    };
    for (area, panel) in areas.iter().zip(panels) {
        let series: Vec<(&String, &[f64])> = panel
            .iter()
            .map(|n| {
                recorder
                    .column(n)
                    .map(|c| (n, c))
                    .ok_or_else(|| PlotError::new(path, &format!("`{n}` is not a recorded signal")))
            })
            .collect::<Result<_, _>>()?;
        let (lo, hi) = series
            .iter()
            .flat_map(|(_, c)| c.iter().copied())
            .filter(|v| v.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(v), b.max(v))
            });
        let pad = if hi > lo {
            0.05 * (hi - lo)
        } else {
            1.0_f64.max(lo.abs() * 0.05)
        };
        let (lo, hi) = if lo.is_finite() {
            (lo - pad, hi + pad)
        } else {
            (-1.0, 1.0)
        };
        let mut chart = ChartBuilder::on(area)
            .margin(10)
            .x_label_area_size(30)
            .y_label_area_size(80)
            .build_cartesian_2d(t0..t1, lo..hi)
            .map_err(|e| fail(&e))?;
        chart
            .configure_mesh()
            .x_desc("time (s)")
            .y_label_formatter(&|v| tick(*v))
            .draw()
            .map_err(|e| fail(&e))?;
        for (i, (name, column)) in series.iter().enumerate() {
            let color = Palette99::pick(i).to_rgba();
            chart
                .draw_series(LineSeries::new(
                    recorder.time.iter().copied().zip(column.iter().copied()),
                    color.stroke_width(2),
                ))
                .map_err(|e| fail(&e))?
                .label(name.as_str())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color));
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(|e| fail(&e))?;
    }
    root.present().map_err(|e| fail(&e))
}

/// Mode shapes like seed 000 Fig. 12: each mode's displacement normal to the chord
/// (bottom node to top node) against height z.
pub fn mode_shapes(
    path: &Path,
    title: &str,
    analysis: &slender_units::ModalAnalysis,
) -> Result<(), PlotError> {
    let fail = |e: &dyn std::fmt::Display| PlotError::new(path, e);
    let x = &analysis.positions;
    let (first, last) = match (x.first(), x.last()) {
        (Some(a), Some(b)) if x.len() > 1 => (*a, *b),
        _ => return Err(PlotError::new(path, &"no node positions to plot")),
    };
    let chord = [last[0] - first[0], last[1] - first[1]];
    let len = (chord[0] * chord[0] + chord[1] * chord[1]).sqrt();
    let normal = [-chord[1] / len, chord[0] / len];
    let root = SVGBackend::new(path, (700, 900)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let (zlo, zhi) = x
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p[1]), b.max(p[1]))
        });
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(60)
        .build_cartesian_2d(-1.1f64..1.1f64, zlo..zhi)
        .map_err(|e| fail(&e))?;
    chart
        .configure_mesh()
        .x_desc("displacement normal to the chord (scaled)")
        .y_desc("z (m)")
        .draw()
        .map_err(|e| fail(&e))?;
    for (i, m) in analysis.modes.iter().enumerate() {
        let color = Palette99::pick(i).to_rgba();
        let peak = m
            .shape
            .iter()
            .map(|d| (d[0] * normal[0] + d[1] * normal[1]).abs())
            .fold(0.0, f64::max)
            .max(1e-300);
        chart
            .draw_series(LineSeries::new(
                m.shape
                    .iter()
                    .zip(x)
                    .map(|(d, p)| ((d[0] * normal[0] + d[1] * normal[1]) / peak, p[1])),
                color.stroke_width(2),
            ))
            .map_err(|e| fail(&e))?
            .label(format!("mode {} ({:.2} s)", i + 1, m.period))
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color));
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
        .map_err(|e| fail(&e))?;
    root.present().map_err(|e| fail(&e))
}

/// Study figure: for each varied setting, the relative errors (left) and the cost
/// per simulated second (right) against the setting's value, log-log.
pub fn study(path: &Path, title: &str, rows: &[crate::study::StudyRow]) -> Result<(), PlotError> {
    let fail = |e: &dyn std::fmt::Display| PlotError::new(path, e);
    // One row of panels per group whose values are numbers.
    let mut knobs: Vec<String> = Vec::new();
    for r in rows
        .iter()
        .filter(|r| r.value.is_finite() && r.settings.len() == 1)
    {
        if !knobs.contains(&r.group) {
            knobs.push(r.group.clone());
        }
    }
    let root =
        SVGBackend::new(path, (1100, 60 + 300 * knobs.len().max(1) as u32)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let root = root
        .titled(title, ("sans-serif", 22))
        .map_err(|e| fail(&e))?;
    let cells = root.split_evenly((knobs.len().max(1), 2));
    for (k, knob) in knobs.iter().enumerate() {
        let mine: Vec<&crate::study::StudyRow> = rows
            .iter()
            .filter(|r| r.group == *knob && r.value.is_finite())
            .collect();
        let names: Vec<String> = mine
            .first()
            .map(|r| r.errors.iter().map(|e| e.0.clone()).collect())
            .unwrap_or_default();
        let errors: Vec<(String, Vec<(f64, f64)>)> = names
            .iter()
            .enumerate()
            .map(|(i, n)| {
                (
                    n.clone(),
                    mine.iter()
                        .map(|r| (r.value, r.errors[i].1))
                        .filter(|p| p.1 > 0.0)
                        .collect(),
                )
            })
            .collect();
        let cost = vec![(
            String::new(),
            mine.iter()
                .map(|r| (r.value, r.cost_per_simulated_second))
                .collect(),
        )];
        log_log_panel(&cells[2 * k], knob, "epsilon vs reference", 0, &errors)
            .map_err(|e| fail(&e))?;
        log_log_panel(&cells[2 * k + 1], knob, "s per simulated s", 1, &cost)
            .map_err(|e| fail(&e))?;
    }
    root.present().map_err(|e| fail(&e))
}

/// Bounds of the positive finite values, widened for a log axis.
fn positive_range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|x| x.is_finite() && *x > 0.0)
        .fold((f64::INFINITY, 0.0f64), |(a, b), x| (a.min(x), b.max(x)));
    if lo.is_finite() {
        (lo / 1.5, hi * 1.5)
    } else {
        (1e-12, 1.0)
    }
}

/// One log-log panel with a line and markers per named series (a legend when
/// the series have names); y labels in engineering notation with `y_digits` decimals.
fn log_log_panel(
    area: &DrawingArea<SVGBackend<'_>, plotters::coord::Shift>,
    x_desc: &str,
    y_desc: &str,
    y_digits: usize,
    series: &[(String, Vec<(f64, f64)>)],
) -> Result<(), Box<dyn std::error::Error>> {
    let (xlo, xhi) = positive_range(series.iter().flat_map(|s| s.1.iter().map(|p| p.0)));
    let (ylo, yhi) = positive_range(series.iter().flat_map(|s| s.1.iter().map(|p| p.1)));
    let mut chart = ChartBuilder::on(area)
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(70)
        .build_cartesian_2d((xlo..xhi).log_scale(), (ylo..yhi).log_scale())?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_label_formatter(&|v| format!("{v:.3}"))
        .y_label_formatter(&|v| format!("{v:.y_digits$e}"))
        .draw()?;
    for (i, (name, points)) in series.iter().enumerate() {
        let color = if name.is_empty() {
            BLACK.to_rgba()
        } else {
            Palette99::pick(i).to_rgba()
        };
        let line = chart.draw_series(LineSeries::new(points.clone(), color.stroke_width(2)))?;
        if !name.is_empty() {
            line.label(name.as_str())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color));
        }
        chart.draw_series(points.iter().map(|&p| Circle::new(p, 4, color.filled())))?;
    }
    if series.iter().any(|s| !s.0.is_empty()) {
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()?;
    }
    Ok(())
}

/// Bode plot: |H| (log-log) and phase (deg) of each named frequency response.
pub fn bode(
    path: &Path,
    title: &str,
    omegas: &[f64],
    series: &[(String, Vec<slender_units::span::transfer::C64>)],
) -> Result<(), PlotError> {
    let fail = |e: &dyn std::fmt::Display| PlotError::new(path, e);
    let root = SVGBackend::new(path, (1000, 800)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let root = root
        .titled(title, ("sans-serif", 22))
        .map_err(|e| fail(&e))?;
    let (top, bottom) = root.split_vertically(480);
    let (w0, w1) = (omegas[0], omegas[omegas.len() - 1]);
    let (lo, hi) = positive_range(series.iter().flat_map(|s| s.1.iter().map(|h| h.norm())));
    let mut mag = ChartBuilder::on(&top)
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(70)
        .build_cartesian_2d((w0..w1).log_scale(), (lo.max(hi * 1e-8)..hi).log_scale())
        .map_err(|e| fail(&e))?;
    mag.configure_mesh()
        .x_desc("omega (rad/s)")
        .y_desc("|H| (m/rad)")
        .x_label_formatter(&|v| format!("{v:.0e}"))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .draw()
        .map_err(|e| fail(&e))?;
    let mut phase = ChartBuilder::on(&bottom)
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(70)
        .build_cartesian_2d((w0..w1).log_scale(), -180.0f64..180.0)
        .map_err(|e| fail(&e))?;
    phase
        .configure_mesh()
        .x_desc("omega (rad/s)")
        .y_desc("phase (deg)")
        .x_label_formatter(&|v| format!("{v:.0e}"))
        .draw()
        .map_err(|e| fail(&e))?;
    for (i, (name, h)) in series.iter().enumerate() {
        let color = Palette99::pick(i).to_rgba();
        mag.draw_series(LineSeries::new(
            omegas.iter().zip(h).map(|(&w, h)| (w, h.norm().max(lo))),
            color.stroke_width(2),
        ))
        .map_err(|e| fail(&e))?
        .label(name.as_str())
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color));
        phase
            .draw_series(LineSeries::new(
                omegas
                    .iter()
                    .zip(h)
                    .map(|(&w, h)| (w, h.arg().to_degrees())),
                color.stroke_width(1),
            ))
            .map_err(|e| fail(&e))?;
    }
    mag.configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
        .map_err(|e| fail(&e))?;
    root.present().map_err(|e| fail(&e))
}

/// Error against cost per simulated second, log-log, one series per label: each
/// point is (label, cost in s per simulated s, relative error).
pub fn accuracy_cost(
    path: &Path,
    title: &str,
    error_label: &str,
    points: &[(String, f64, f64)],
) -> Result<(), PlotError> {
    let fail = |e: &dyn std::fmt::Display| PlotError::new(path, e);
    let root = SVGBackend::new(path, (900, 600)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let root = root
        .titled(title, ("sans-serif", 20))
        .map_err(|e| fail(&e))?;
    let mut series: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    for (label, cost, error) in points {
        let point = (*cost, error.max(1e-12));
        match series.iter_mut().find(|(l, _)| l == label) {
            Some((_, pts)) => pts.push(point),
            None => series.push((label.clone(), vec![point])),
        }
    }
    log_log_panel(&root, "cost (s per simulated s)", error_label, 0, &series)
        .map_err(|e| fail(&e))?;
    root.present().map_err(|e| fail(&e))
}
