//! A grid of two settings as heat maps: the worst error and the cost of each
//! combination as a coloured cell with its value written in it.

use super::axes::{band_axis, band_of};
use super::labels::{Area, CHAR_WIDTH, DrawResult, KEY_FONT, KEY_ROW, side_legend};
use super::study::{Group, titled};
use crate::study::StudyRow;
use plotters::prelude::*;
use plotters::style::colors::colormaps::ViridisRGB;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// The distinct values of setting `i` over the rows, in their order.
fn levels(rows: &[&StudyRow], i: usize) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for r in rows {
        if let Some((_, v)) = r.settings.get(i) {
            if !out.contains(v) {
                out.push(v.clone());
            }
        }
    }
    out
}

/// The worst error over a row's indicators (NaN for a failed run).
fn worst(r: &StudyRow) -> f64 {
    if r.error.is_some() {
        return f64::NAN;
    }
    r.errors.iter().map(|e| e.1).fold(0.0, f64::max)
}

/// Colour of a value on a log scale between `lo` and `hi` (both > 0).
fn colour(v: f64, (lo, hi): (f64, f64)) -> RGBColor {
    let t = if hi > lo {
        (v.log10() - lo.log10()) / (hi.log10() - lo.log10())
    } else {
        0.5
    };
    ViridisRGB::get_color(if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    })
}

/// The bounds of the positive finite values.
fn bounds(values: &[f64]) -> (f64, f64) {
    values
        .iter()
        .filter(|v| v.is_finite() && **v > 0.0)
        .fold((f64::INFINITY, 0.0), |(a, b), v| (a.min(*v), b.max(*v)))
}

/// Draws the error and cost heat maps of a two-setting grid, and a colour key.
pub(super) fn grid(
    chart_area: &Area<'_>,
    legend: &Area<'_>,
    cost_area: &Area<'_>,
    group: &Group<'_>,
    unit_of: &dyn Fn(&str) -> String,
) -> DrawResult {
    let first = &group.rows[0].settings;
    let axes = [
        titled(&first[0].0, &unit_of(&first[0].0)),
        titled(&first[1].0, &unit_of(&first[1].0)),
    ];
    let errors: Vec<f64> = group.rows.iter().map(|r| worst(r)).collect();
    let costs = group.costs();
    let scale = bounds(&errors);
    heat_map(
        chart_area,
        &axes,
        group,
        &errors,
        scale,
        "worst epsilon (-)",
    )?;
    heat_map(
        cost_area,
        &axes,
        group,
        &costs,
        bounds(&costs),
        "cost (s per simulated s)",
    )?;
    colour_key(legend, &group.name, scale)
}

/// One heat map of `values` (one per row) over the grid's two settings.
fn heat_map(
    area: &Area<'_>,
    axes: &[String; 2],
    group: &Group<'_>,
    values: &[f64],
    scale: (f64, f64),
    what: &str,
) -> DrawResult {
    let (xs, ys) = (levels(&group.rows, 0), levels(&group.rows, 1));
    let mut grid = Cells {
        caption: what,
        axes: [axes[0].as_str(), axes[1].as_str()],
        xs: &xs,
        ys: &ys,
        cells: Vec::with_capacity(values.len()),
    };
    for (r, value) in group.rows.iter().zip(values) {
        let at = |i: usize, levels: &[String]| {
            levels
                .iter()
                .position(|l| Some(l) == r.settings.get(i).map(|s| &s.1))
        };
        let (Some(x), Some(y)) = (at(0, &xs), at(1, &ys)) else {
            continue;
        };
        let (fill, text) = match (r.error.is_some(), value.is_finite() && *value > 0.0) {
            (true, _) => (RGBColor(200, 200, 200), "failed".to_owned()),
            (false, true) => (colour(*value, scale), format!("{value:.1e}")),
            (false, false) => (
                WHITE,
                if r.reference {
                    "reference".to_owned()
                } else {
                    "0".to_owned()
                },
            ),
        };
        grid.cells.push(Cell {
            at: (x, y),
            fill,
            text,
            outlined: false,
        });
    }
    draw_cells(area, &grid)
}

/// One cell of a map: its column and row, colour, text and whether it is
/// outlined (the one a caption points at).
pub(super) struct Cell {
    pub at: (usize, usize),
    pub fill: RGBColor,
    pub text: String,
    pub outlined: bool,
}

/// A map of coloured cells over two sets of levels, each with its text.
pub(super) struct Cells<'a> {
    pub caption: &'a str,
    /// The x and y axes' titles.
    pub axes: [&'a str; 2],
    pub xs: &'a [String],
    pub ys: &'a [String],
    pub cells: Vec<Cell>,
}

/// Draws `grid` on `area`: each cell a filled rectangle with its text in
/// black or white, whichever reads on its colour.
pub(super) fn draw_cells(area: &Area<'_>, grid: &Cells<'_>) -> DrawResult {
    let (xs, ys) = (grid.xs, grid.ys);
    let widest = ys.iter().map(String::len).max().unwrap_or(0) as i32;
    let mut chart = ChartBuilder::on(area)
        .caption(grid.caption, ("sans-serif", 14))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size((CHAR_WIDTH * widest + 40).clamp(75, 220))
        .build_cartesian_2d(band_axis(xs.len()), band_axis(ys.len()))?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(grid.axes[0])
        .y_desc(grid.axes[1])
        .x_label_formatter(&|v| xs.get(band_of(*v)).cloned().unwrap_or_default())
        .y_label_formatter(&|v| ys.get(band_of(*v)).cloned().unwrap_or_default())
        .draw()?;
    for cell in &grid.cells {
        let (x, y) = (cell.at.0 as f64, cell.at.1 as f64);
        let ink = if cell.fill == WHITE || cell.fill.1 > 150 {
            BLACK
        } else {
            WHITE
        };
        chart.draw_series([Rectangle::new(
            [(x, y), (x + 1.0, y + 1.0)],
            cell.fill.filled(),
        )])?;
        if cell.outlined {
            chart.draw_series([Rectangle::new(
                [(x + 0.02, y + 0.02), (x + 0.98, y + 0.98)],
                RED.stroke_width(3),
            )])?;
        }
        chart.draw_series([Text::new(
            cell.text.clone(),
            (x + 0.5, y + 0.5),
            ("sans-serif", 11)
                .into_font()
                .color(&ink)
                .pos(Pos::new(HPos::Center, VPos::Center)),
        )])?;
    }
    Ok(())
}

/// The error colour scale as swatches from the smallest to the largest value.
fn colour_key(area: &Area<'_>, heading: &str, (lo, hi): (f64, f64)) -> DrawResult {
    side_legend(area, heading, &[])?;
    if !(lo.is_finite() && hi >= lo) {
        return Ok(());
    }
    let steps = 6;
    for k in 0..=steps {
        let v = lo * (hi / lo).powf(k as f64 / steps as f64);
        let y = 30 + KEY_ROW * (k + 2);
        area.draw(&Rectangle::new(
            [(8, y), (30, y + KEY_ROW - 3)],
            colour(v, (lo, hi)).filled(),
        ))?;
        area.draw(&Text::new(
            format!("{v:.1e}"),
            (36, y),
            ("sans-serif", KEY_FONT),
        ))?;
    }
    let note = "worst epsilon; cost cells dark = cheap";
    area.draw(&Text::new(
        note,
        (8, 30 + KEY_ROW * (steps + 3)),
        ("sans-serif", 11),
    ))?;
    Ok(())
}
