//! Curves against one abscissa in stacked panels (`statics.svg`: a moored
//! body's restoring force and its lines' tensions against its offset).

use crate::figures::labels::inner_legend;
use crate::plot::PlotError;
use plotters::prelude::*;
use std::path::Path;

/// One panel: its axes' titles (with units) and its named curves.
pub struct CurvePanel {
    /// Title of the x axis, with its unit.
    pub x_label: String,
    /// Title of the y axis, with its unit.
    pub y_label: String,
    /// Each curve's name and points (x, y).
    pub series: Vec<(String, Vec<(f64, f64)>)>,
}

/// The range of `values` widened by 5 % (a unit either side of a constant).
fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
        (a.min(v), b.max(v))
    });
    if !(lo.is_finite() && hi.is_finite()) {
        return (0.0, 1.0);
    }
    let pad = if hi > lo {
        0.05 * (hi - lo)
    } else {
        lo.abs().max(1.0)
    };
    (lo - pad, hi + pad)
}

/// Draws `panels` stacked under `title` into the SVG file `path`.
pub fn curves(path: &Path, title: &str, panels: &[CurvePanel]) -> Result<(), PlotError> {
    let fail = |e: &dyn std::fmt::Display| PlotError::new(path, e);
    let height = 60 + 300 * panels.len() as u32;
    let root = SVGBackend::new(path, (900, height)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let root = root
        .titled(title, ("sans-serif", 20))
        .map_err(|e| fail(&e))?;
    for (area, panel) in root.split_evenly((panels.len(), 1)).iter().zip(panels) {
        let points = || panel.series.iter().flat_map(|(_, p)| p.iter());
        let (x0, x1) = range(points().map(|p| p.0));
        let (y0, y1) = range(points().map(|p| p.1));
        let mut chart = ChartBuilder::on(area)
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(80)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| fail(&e))?;
        chart
            .configure_mesh()
            .x_desc(panel.x_label.as_str())
            .y_desc(panel.y_label.as_str())
            .draw()
            .map_err(|e| fail(&e))?;
        for (i, (name, pts)) in panel.series.iter().enumerate() {
            let color = Palette99::pick(i).to_rgba();
            chart
                .draw_series(LineSeries::new(pts.iter().copied(), color.stroke_width(2)))
                .map_err(|e| fail(&e))?
                .label(name.as_str())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color));
        }
        inner_legend(&mut chart).map_err(|e| fail(&e))?;
    }
    root.present().map_err(|e| fail(&e))
}
