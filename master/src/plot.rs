//! SVG figures of recorded time series (plotters, SVG backend: no fonts needed).

use crate::record::Recorder;
use plotters::prelude::*;
use std::path::Path;

/// Draws stacked panels; each panel overlays the named recorded signals against time.
pub fn time_series(
    path: &Path,
    title: &str,
    recorder: &Recorder,
    panels: &[Vec<String>],
) -> Result<(), String> {
    let height = 60 + 220 * panels.len() as u32;
    let root = SVGBackend::new(path, (1000, height)).into_drawing_area();
    let fail = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let root = root
        .titled(title, ("sans-serif", 22))
        .map_err(|e| fail(&e))?;
    let areas = root.split_evenly((panels.len(), 1));
    let (t0, t1) = match (recorder.time.first(), recorder.time.last()) {
        (Some(&a), Some(&b)) if b > a => (a, b),
        _ => return Err(format!("{}: nothing recorded to plot", path.display())),
    };
    for (area, panel) in areas.iter().zip(panels) {
        let series: Vec<(&String, &[f64])> = panel
            .iter()
            .map(|n| {
                recorder
                    .column(n)
                    .map(|c| (n, c))
                    .ok_or_else(|| format!("{}: `{n}` is not a recorded signal", path.display()))
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
