//! SVG figures of recorded time series (plotters, SVG backend: no fonts needed).

use crate::figures::axes::{linear_axis, log_axis, positive_range};
use crate::figures::labels::{Area, DrawResult, Entry, inner_legend, side_legend};
use crate::figures::ticks;
use crate::record::Recorder;
use plotters::prelude::*;
use std::path::Path;

/// A figure that could not be drawn or written: its file and why.
#[derive(Debug, thiserror::Error)]
#[error("{path}: {reason}")]
pub struct PlotError {
    /// The figure's file.
    pub path: String,
    /// What went wrong.
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

/// Draws stacked panels; each panel overlays the named recorded signals
/// against time, its y axis titled with their units and the legend beside it.
pub fn time_series(
    path: &Path,
    title: &str,
    recorder: &Recorder,
    panels: &[Vec<String>],
) -> Result<(), PlotError> {
    let height = 60 + 220 * panels.len() as u32;
    let root = SVGBackend::new(path, (1200, height)).into_drawing_area();
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
        let (chart_area, legend) = area.split_horizontally(950);
        let y_title = units_title(panel.iter().map(|n| recorder.unit(n).unwrap_or("")));
        let axes = Axes {
            x: (t0, t1),
            x_title: "time (s)",
            y_title: &y_title,
        };
        let curves: Vec<(&String, &[f64], &[f64])> = (series.iter())
            .map(|(n, c)| (*n, recorder.time.as_slice(), *c))
            .collect();
        panel_chart(&chart_area, &axes, &curves).map_err(|e| fail(&e))?;
        let entries: Vec<Entry> = (series.iter().enumerate())
            .map(|(i, (name, _))| Entry {
                text: (*name).clone(),
                colour: Palette99::pick(i).to_rgba(),
                marker: false,
            })
            .collect();
        side_legend(&legend, "", &entries).map_err(|e| fail(&e))?;
    }
    root.present().map_err(|e| fail(&e))
}

/// A y axis title from its signals' units: `value (N)`, `value (N, m)` where
/// they differ, `value (-)` where they have none.
fn units_title<'a>(units: impl Iterator<Item = &'a str>) -> String {
    let mut distinct: Vec<&str> = Vec::new();
    for u in units.map(|u| if u.is_empty() { "-" } else { u }) {
        if !distinct.contains(&u) {
            distinct.push(u);
        }
    }
    format!("value ({})", distinct.join(", "))
}

/// A panel's x range and its axes' titles.
struct Axes<'a> {
    x: (f64, f64),
    x_title: &'a str,
    y_title: &'a str,
}

/// One curve of a panel: its legend, and its points' x and y.
pub struct Curve<'a> {
    /// Its legend.
    pub name: String,
    /// The points' x.
    pub x: &'a [f64],
    /// The points' y.
    pub y: &'a [f64],
}

/// One panel of a stacked figure: curves against x.
pub struct Profile<'a> {
    /// The x axis's range.
    pub x_range: (f64, f64),
    /// Title of the x axis, with its unit.
    pub x_title: &'a str,
    /// Title of the y axis, with its unit.
    pub y_title: String,
    /// The curves.
    pub series: Vec<Curve<'a>>,
}

/// Stacked panels, top to bottom, each its curves with a legend beside it.
pub fn profiles(path: &Path, title: &str, panels: &[Profile<'_>]) -> Result<(), PlotError> {
    let fail = |e: &dyn std::fmt::Display| PlotError::new(path, e);
    let root = SVGBackend::new(path, (1200, 60 + 220 * panels.len() as u32)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let root = root
        .titled(title, ("sans-serif", 22))
        .map_err(|e| fail(&e))?;
    for (area, p) in root.split_evenly((panels.len(), 1)).iter().zip(panels) {
        let (chart_area, legend) = area.split_horizontally(950);
        let axes = Axes {
            x: p.x_range,
            x_title: p.x_title,
            y_title: &p.y_title,
        };
        let series: Vec<(&String, &[f64], &[f64])> =
            p.series.iter().map(|c| (&c.name, c.x, c.y)).collect();
        panel_chart(&chart_area, &axes, &series).map_err(|e| fail(&e))?;
        let entries: Vec<Entry> = (p.series.iter().enumerate())
            .map(|(i, c)| Entry {
                text: c.name.clone(),
                colour: Palette99::pick(i).to_rgba(),
                marker: false,
            })
            .collect();
        side_legend(&legend, "", &entries).map_err(|e| fail(&e))?;
    }
    root.present().map_err(|e| fail(&e))
}

/// Stacked panels of power spectral densities, one per `(signal, density
/// unit, spectrum)`, up to the frequency past which every density stays
/// under a thousandth of its peak.
pub fn spectra(
    path: &Path,
    title: &str,
    panels: &[(&str, &str, &crate::spectrum::Spectrum)],
) -> Result<(), PlotError> {
    let top = (panels.iter())
        .map(|(_, _, s)| {
            let peak = s.density.iter().copied().fold(0.0, f64::max);
            let last = (s.density.iter())
                .rposition(|d| *d > 1e-3 * peak)
                .unwrap_or(0);
            s.frequency_hz[(last + 1).min(s.frequency_hz.len() - 1)]
        })
        .fold(0.0, f64::max);
    let profiles: Vec<Profile> = (panels.iter())
        .map(|(name, unit, s)| Profile {
            x_range: (0.0, if top > 0.0 { top } else { 1.0 }),
            x_title: "frequency (Hz)",
            y_title: format!("density ({unit})"),
            series: vec![Curve {
                name: (*name).to_owned(),
                x: &s.frequency_hz,
                y: &s.density,
            }],
        })
        .collect();
    self::profiles(path, title, &profiles)
}

/// One panel: the curves (name, x, y) against x (time, frequency, arc) on
/// 1-2-5 ticks.
fn panel_chart(
    area: &Area<'_>,
    axes: &Axes<'_>,
    series: &[(&String, &[f64], &[f64])],
) -> DrawResult {
    let (t0, t1) = axes.x;
    let y_title = axes.y_title;
    let (lo, hi) = series
        .iter()
        .flat_map(|(_, _, c)| c.iter().copied())
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
    let (x_axis, x_step) = linear_axis(t0, t1, 10);
    let (y_axis, y_step) = linear_axis(lo, hi, 6);
    let mut chart = ChartBuilder::on(area)
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(85)
        .build_cartesian_2d(x_axis, y_axis)?;
    chart
        .configure_mesh()
        .x_desc(axes.x_title)
        .y_desc(y_title)
        .x_label_formatter(&|v| ticks::linear_label(*v, x_step))
        .y_label_formatter(&|v| ticks::linear_label(*v, y_step))
        .draw()?;
    for (i, (_, x, column)) in series.iter().enumerate() {
        let color = Palette99::pick(i).to_rgba();
        let points = crate::figures::thin::thinned(x, column, crate::figures::thin::COLUMNS);
        chart.draw_series(LineSeries::new(points, color.stroke_width(2)))?;
    }
    Ok(())
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
    inner_legend(&mut chart).map_err(|e| fail(&e))?;
    root.present().map_err(|e| fail(&e))
}

/// One log-log panel with a line and markers per named series (a legend when
/// the series have names), ticked at decades or 1-2-5.
fn log_log_panel(
    area: &DrawingArea<SVGBackend<'_>, plotters::coord::Shift>,
    x_desc: &str,
    y_desc: &str,
    series: &[(String, Vec<(f64, f64)>)],
) -> Result<(), Box<dyn std::error::Error>> {
    let (xlo, xhi) = positive_range(series.iter().flat_map(|s| s.1.iter().map(|p| p.0)));
    let (ylo, yhi) = positive_range(series.iter().flat_map(|s| s.1.iter().map(|p| p.1)));
    let mut chart = ChartBuilder::on(area)
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(70)
        .build_cartesian_2d(log_axis(xlo, xhi, 7), log_axis(ylo, yhi, 8))?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_label_formatter(&|v| ticks::log_label(*v))
        .y_label_formatter(&|v| ticks::log_label(*v))
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
        inner_legend(&mut chart)?;
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
        .build_cartesian_2d(log_axis(w0, w1, 10), log_axis(lo.max(hi * 1e-8), hi, 10))
        .map_err(|e| fail(&e))?;
    mag.configure_mesh()
        .x_desc("omega (rad/s)")
        .y_desc("|H| (m/rad)")
        .x_label_formatter(&|v| ticks::log_label(*v))
        .y_label_formatter(&|v| ticks::log_label(*v))
        .draw()
        .map_err(|e| fail(&e))?;
    let mut phase = ChartBuilder::on(&bottom)
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(70)
        .build_cartesian_2d(log_axis(w0, w1, 10), -180.0f64..180.0)
        .map_err(|e| fail(&e))?;
    phase
        .configure_mesh()
        .x_desc("omega (rad/s)")
        .y_desc("phase (deg)")
        .x_label_formatter(&|v| ticks::log_label(*v))
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
    inner_legend(&mut mag).map_err(|e| fail(&e))?;
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
    log_log_panel(&root, "cost (s per simulated s)", error_label, &series).map_err(|e| fail(&e))?;
    root.present().map_err(|e| fail(&e))
}
