//! A sweep of names (`master.scheme`, `master.acceleration`) as grouped bars:
//! each value a band, each indicator's error a bar in it, on a log axis; the
//! cost as one bar per value.

use super::axes::{band_axis, band_of, log_axis, positive_range};
use super::labels::{Area, CHAR_WIDTH, DrawResult, Entry, side_legend};
use super::study::{Group, indicators};
use super::ticks;
use crate::study::StudyRow;
use plotters::prelude::*;

/// The band labels: the values where they fit under their bands, else their
/// numbers (the legend then says which is which).
fn band_labels(values: &[String], band_pixels: i32) -> (Vec<String>, bool) {
    let widest = values.iter().map(String::len).max().unwrap_or(0) as i32;
    if widest * CHAR_WIDTH + 8 <= band_pixels {
        (values.to_vec(), false)
    } else {
        ((1..=values.len()).map(|k| k.to_string()).collect(), true)
    }
}

/// One bar of a band: the `j`-th of `n`, from the axis's foot up to `value`.
fn bar(
    k: usize,
    j: usize,
    n: usize,
    foot: f64,
    value: f64,
    colour: RGBAColor,
) -> Rectangle<(f64, f64)> {
    let width = 0.8 / n.max(1) as f64;
    let left = k as f64 + 0.1 + j as f64 * width;
    Rectangle::new([(left, foot), (left + width * 0.9, value)], colour.filled())
}

/// Draws the errors' grouped bars, their legend and the cost bars.
pub(super) fn names(
    chart_area: &Area<'_>,
    legend: &Area<'_>,
    cost_area: &Area<'_>,
    group: &Group<'_>,
) -> DrawResult {
    let key = group.rows[0]
        .settings
        .first()
        .map_or(group.name.clone(), |s| s.0.clone());
    let values: Vec<String> = group
        .rows
        .iter()
        .map(|r| r.settings.first().map_or(String::new(), |s| s.1.clone()))
        .collect();
    let band_pixels = (chart_area.dim_in_pixel().0 as i32 - 100) / values.len().max(1) as i32;
    let (labels, numbered) = band_labels(&values, band_pixels);
    let names = indicators(&group.rows);
    let colours: Vec<RGBAColor> = (0..names.len())
        .map(|i| Palette99::pick(i).to_rgba())
        .collect();
    let errors = group
        .rows
        .iter()
        .filter(|r| r.error.is_none())
        .flat_map(|r| r.errors.iter().map(|e| e.1));
    let (lo, hi) = positive_range(errors);
    let mut chart = ChartBuilder::on(chart_area)
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(75)
        .build_cartesian_2d(band_axis(values.len()), log_axis(lo, hi, 8))?;
    let label_of = |v: &f64| labels.get(band_of(*v)).cloned().unwrap_or_default();
    chart
        .configure_mesh()
        .disable_x_mesh()
        .x_desc(key.as_str())
        .y_desc("epsilon against the reference (-)")
        .x_label_formatter(&label_of)
        .y_label_formatter(&|v| ticks::log_label(*v))
        .draw()?;
    for (k, r) in group.rows.iter().enumerate() {
        if let Some(note) = note(r) {
            let above_foot = lo * (hi / lo).powf(0.06);
            chart.draw_series([Text::new(
                note,
                (k as f64 + 0.15, above_foot),
                ("sans-serif", 12),
            )])?;
            continue;
        }
        let shown = r
            .errors
            .iter()
            .enumerate()
            .filter(|(_, e)| e.1 > 0.0 && e.1.is_finite());
        chart.draw_series(shown.map(|(j, e)| bar(k, j, names.len(), lo, e.1, colours[j])))?;
    }
    let mut entries = Entry::each(&names, &colours, true);
    if numbered {
        entries.extend(values.iter().enumerate().map(|(k, v)| Entry {
            text: format!("{} = {v}", k + 1),
            colour: WHITE.to_rgba(),
            marker: false,
        }));
    }
    side_legend(legend, &group.name, &entries)?;
    cost_bars(cost_area, &key, &labels, group)
}

/// What a band shows instead of bars: the reference, or a failed run.
fn note(r: &StudyRow) -> Option<&'static str> {
    if r.error.is_some() {
        Some("failed")
    } else if r.reference {
        Some("reference")
    } else {
        None
    }
}

/// One cost bar per value, log axis.
fn cost_bars(area: &Area<'_>, key: &str, labels: &[String], group: &Group<'_>) -> DrawResult {
    let costs = group.costs();
    let (lo, hi) = positive_range(costs.iter().copied());
    let mut chart = ChartBuilder::on(area)
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(75)
        .build_cartesian_2d(band_axis(labels.len()), log_axis(lo, hi, 8))?;
    let label_of = |v: &f64| labels.get(band_of(*v)).cloned().unwrap_or_default();
    chart
        .configure_mesh()
        .disable_x_mesh()
        .x_desc(key)
        .y_desc("cost (s per simulated s)")
        .x_label_formatter(&label_of)
        .y_label_formatter(&|v| ticks::log_label(*v))
        .draw()?;
    let shown = costs
        .iter()
        .enumerate()
        .filter(|(_, c)| c.is_finite() && **c > 0.0);
    chart.draw_series(shown.map(|(k, c)| bar(k, 0, 1, lo, *c, BLACK.mix(0.7))))?;
    Ok(())
}
