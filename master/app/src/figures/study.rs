//! The study figure (`study.svg`): one row per group of runs, errors on the
//! left and cost on the right, drawn as the group's settings allow: a sweep of
//! numbers as log-log lines, a sweep of names (a scheme, an acceleration) as
//! grouped bars, a grid of two settings as heat maps.

use super::axes::{fitting, log_axis, positive_range};
use super::labels::{Area, DrawResult, Entry, side_legend};
use super::{bars, heat, ticks};
use crate::plot::PlotError;
use crate::study::StudyRow;
use plotters::prelude::*;
use std::path::Path;

/// Height of one group's row of panels (px).
const ROW: u32 = 340;
/// Width of the legend column beside the error panel (px).
const LEGEND: u32 = 230;

/// How a group is drawn.
pub(super) enum Shape {
    /// Each run's value a positive number: lines against it, log-log.
    Numbers,
    /// Values that are names (or not all positive): bars per value.
    Names,
    /// A grid of two settings: heat maps.
    Grid,
    /// A grid of more settings: left to the error-against-cost figure.
    Wide,
}

/// A group of rows and how to draw it.
pub(super) struct Group<'a> {
    pub name: String,
    pub rows: Vec<&'a StudyRow>,
    pub shape: Shape,
}

impl Group<'_> {
    /// Each row's cost per simulated second (s/s); NaN for a failed run.
    pub(super) fn costs(&self) -> Vec<f64> {
        let cost = |r: &&StudyRow| match r.error {
            None => r.cost_per_simulated_second,
            Some(_) => f64::NAN,
        };
        self.rows.iter().map(cost).collect()
    }
}

/// The study's groups in their order, each with its shape.
pub(super) fn groups(rows: &[StudyRow]) -> Vec<Group<'_>> {
    let mut groups: Vec<Group<'_>> = Vec::new();
    for r in rows {
        match groups.iter_mut().find(|g| g.name == r.group) {
            Some(g) => g.rows.push(r),
            None => groups.push(Group {
                name: r.group.clone(),
                rows: vec![r],
                shape: Shape::Names,
            }),
        }
    }
    for g in &mut groups {
        let keys = g.rows.first().map_or(0, |r| r.settings.len());
        g.shape = match keys {
            0 | 1 if g.rows.iter().all(|r| r.value.is_finite() && r.value > 0.0) => Shape::Numbers,
            0 | 1 => Shape::Names,
            2 => Shape::Grid,
            _ => Shape::Wide,
        };
    }
    groups
}

/// The indicator names of the rows.
pub(super) fn indicators(rows: &[&StudyRow]) -> Vec<String> {
    rows.first()
        .map(|r| r.errors.iter().map(|e| e.0.clone()).collect())
        .unwrap_or_default()
}

/// Draws the study figure; `unit_of` gives a setting key's unit for its axis
/// (`""` for a count or a name).
pub fn study(
    path: &Path,
    title: &str,
    rows: &[StudyRow],
    unit_of: &dyn Fn(&str) -> String,
) -> Result<(), PlotError> {
    let fail = |e: &dyn std::fmt::Display| PlotError::new(path, e);
    let groups = groups(rows);
    let drawn: Vec<&Group<'_>> = groups
        .iter()
        .filter(|g| !matches!(g.shape, Shape::Wide))
        .collect();
    let height = 60 + ROW * drawn.len().max(1) as u32;
    let root = SVGBackend::new(path, (1300, height)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let root = root
        .titled(title, ("sans-serif", 22))
        .map_err(|e| fail(&e))?;
    if drawn.is_empty() {
        let note = "every run varies more than two settings: see error_cost.svg";
        root.draw(&Text::new(note, (40, 40), ("sans-serif", 16)))
            .map_err(|e| fail(&e))?;
    }
    let rows_of_panels = root.split_evenly((drawn.len().max(1), 1));
    for (area, group) in rows_of_panels.iter().zip(&drawn) {
        let (errors, cost) = area.split_horizontally(650);
        let (chart, legend) = errors.split_horizontally(650 - LEGEND);
        let drawn = match group.shape {
            Shape::Numbers => numbers(&chart, &legend, &cost, group, unit_of),
            Shape::Names => bars::names(&chart, &legend, &cost, group),
            _ => heat::grid(&chart, &legend, &cost, group, unit_of),
        };
        drawn.map_err(|e| fail(&e))?;
    }
    root.present().map_err(|e| fail(&e))
}

/// An axis title: the key and its unit in brackets, or the key alone.
pub(super) fn titled(key: &str, unit: &str) -> String {
    if unit.is_empty() {
        key.to_owned()
    } else {
        format!("{key} ({unit})")
    }
}

/// A sweep of numbers: each indicator's error and the cost against the value, log-log.
fn numbers(
    chart_area: &Area<'_>,
    legend: &Area<'_>,
    cost_area: &Area<'_>,
    group: &Group<'_>,
    unit_of: &dyn Fn(&str) -> String,
) -> DrawResult {
    let key = group.rows[0]
        .settings
        .first()
        .map_or(group.name.as_str(), |s| s.0.as_str());
    let x_title = titled(key, &unit_of(key));
    let ok: Vec<&&StudyRow> = group.rows.iter().filter(|r| r.error.is_none()).collect();
    let names = indicators(&group.rows);
    let colours: Vec<RGBAColor> = (0..names.len())
        .map(|i| Palette99::pick(i).to_rgba())
        .collect();
    let series: Vec<Vec<(f64, f64)>> = (0..names.len())
        .map(|i| {
            ok.iter()
                .map(|r| (r.value, r.errors[i].1))
                .filter(|p| p.1 > 0.0)
                .collect()
        })
        .collect();
    log_log(
        chart_area,
        &x_title,
        "epsilon against the reference (-)",
        &series,
        &colours,
    )?;
    let mut entries = Entry::each(&names, &colours, false);
    if let Some(r) = group.rows.iter().find(|r| r.reference) {
        entries.push(Entry {
            text: format!(
                "reference: {}",
                r.settings.first().map_or("", |s| s.1.as_str())
            ),
            colour: BLACK.to_rgba(),
            marker: true,
        });
    }
    side_legend(legend, &group.name, &entries)?;
    let cost: Vec<(f64, f64)> = ok
        .iter()
        .map(|r| (r.value, r.cost_per_simulated_second))
        .collect();
    log_log(
        cost_area,
        &x_title,
        "cost (s per simulated s)",
        &[cost],
        &[BLACK.to_rgba()],
    )
}

/// Lines with markers on log-log axes ticked by [`ticks`].
pub(super) fn log_log(
    area: &Area<'_>,
    x_title: &str,
    y_title: &str,
    series: &[Vec<(f64, f64)>],
    colours: &[RGBAColor],
) -> DrawResult {
    let (xlo, xhi) = positive_range(series.iter().flatten().map(|p| p.0));
    let (ylo, yhi) = positive_range(series.iter().flatten().map(|p| p.1));
    let width = area.dim_in_pixel().0 as i32 - 90;
    let mut chart = ChartBuilder::on(area)
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(75)
        .build_cartesian_2d(log_axis(xlo, xhi, fitting(width, 6)), log_axis(ylo, yhi, 8))?;
    chart
        .configure_mesh()
        .x_desc(x_title)
        .y_desc(y_title)
        .x_label_formatter(&|v| ticks::log_label(*v))
        .y_label_formatter(&|v| ticks::log_label(*v))
        .draw()?;
    for (points, colour) in series.iter().zip(colours) {
        chart.draw_series(LineSeries::new(points.clone(), colour.stroke_width(2)))?;
        chart.draw_series(points.iter().map(|&p| Circle::new(p, 4, colour.filled())))?;
    }
    Ok(())
}
