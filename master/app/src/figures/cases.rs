//! A load-case matrix's figure (`cases.svg`): per signal, its extreme in
//! each sea state as a cell of the Hs-Tp scatter (the largest over the
//! headings; the design value's cell outlined); per fatigue entry, each sea
//! state's share of the damage per year (its headings' probability times
//! damage, summed, over the scatter's total, in per cent).

use super::heat::{Cell, Cells, draw_cells};
use crate::cases::aggregate::{CasesReport, Group};
use crate::plot::PlotError;
use plotters::prelude::*;
use plotters::style::colors::colormaps::ViridisRGB;
use std::path::Path;

/// One map of the scatter: its caption, each group's cell and value, and
/// the cell outlined.
struct Panel {
    caption: String,
    values: Vec<f64>,
    outlined: Option<(usize, usize)>,
    /// A sea state's headings add up (damage shares), else its largest shows.
    summed: bool,
}

/// The figure's panels, one per design value and one per fatigue entry.
pub fn cases(path: &Path, title: &str, report: &CasesReport) -> Result<(), PlotError> {
    let fail = |e: &dyn std::fmt::Display| PlotError::new(path, e);
    let tps = levels(&report.groups, |g| g.peak_period);
    let hss = levels(&report.groups, |g| g.significant_height);
    let cell_of = |g: &Group| {
        let x = tps.iter().position(|&t| t == g.peak_period).unwrap_or(0);
        let y = (hss.iter())
            .position(|&h| h == g.significant_height)
            .unwrap_or(0);
        (x, y)
    };
    let at: Vec<(usize, usize)> = report.groups.iter().map(cell_of).collect();
    let panels = panels(report, &cell_of);
    let xs: Vec<String> = tps.iter().map(|v| format!("{v}")).collect();
    let ys: Vec<String> = hss.iter().map(|v| format!("{v}")).collect();
    let height = 60 + 300 * panels.len().max(1) as u32;
    let root = SVGBackend::new(path, (900, height)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let root = (root.titled(title, ("sans-serif", 20))).map_err(|e| fail(&e))?;
    let areas = root.split_evenly((panels.len().max(1), 1));
    for (area, panel) in areas.iter().zip(&panels) {
        let grid = Cells {
            caption: &panel.caption,
            axes: ["peak period Tp (s)", "significant wave height Hs (m)"],
            xs: &xs,
            ys: &ys,
            cells: cells(&at, panel),
        };
        draw_cells(area, &grid).map_err(|e| fail(&e))?;
    }
    root.present().map_err(|e| fail(&e))
}

/// Per design value the groups' extremes; per fatigue entry their shares of
/// the damage per year (%).
fn panels(report: &CasesReport, cell_of: &dyn Fn(&Group) -> (usize, usize)) -> Vec<Panel> {
    let mut panels = Vec::new();
    for design in &report.design {
        let extreme = |g: &Group| {
            (g.extremes.iter())
                .find(|e| e.signal == design.signal)
                .map_or(f64::NAN, |e| e.value)
        };
        panels.push(Panel {
            caption: format!(
                "{}: extreme per sea state (design value outlined)",
                design.signal
            ),
            values: report.groups.iter().map(extreme).collect(),
            outlined: report.groups.get(design.group).map(cell_of),
            summed: false,
        });
    }
    for life in &report.fatigue {
        panels.push(Panel {
            caption: format!("{}: share of the damage per year (%)", life.name),
            values: (life.contributions.iter())
                .map(|c| 100.0 * c / life.damage_per_year)
                .collect(),
            outlined: None,
            summed: true,
        });
    }
    panels
}

/// The distinct values of `of` over the groups, ascending.
fn levels(groups: &[Group], of: impl Fn(&Group) -> f64) -> Vec<f64> {
    let mut values: Vec<f64> = groups.iter().map(of).collect();
    values.sort_by(f64::total_cmp);
    values.dedup();
    values
}

/// One cell per sea state: the largest value of its groups (its headings),
/// or their sum for shares, coloured on a linear scale between the map's
/// least and largest.
fn cells(at: &[(usize, usize)], panel: &Panel) -> Vec<Cell> {
    let mut merged: Vec<((usize, usize), f64)> = Vec::new();
    for (&cell, &v) in at.iter().zip(&panel.values) {
        match merged.iter_mut().find(|(c, _)| *c == cell) {
            Some((_, kept)) if panel.summed => *kept += v,
            Some((_, kept)) => *kept = kept.max(v),
            None => merged.push((cell, v)),
        }
    }
    let finite = merged.iter().map(|m| m.1).filter(|v| v.is_finite());
    let (lo, hi) = finite.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
        (a.min(v), b.max(v))
    });
    merged
        .into_iter()
        .map(|(cell, v)| {
            let (fill, text) = if v.is_finite() {
                let t = if hi > lo { (v - lo) / (hi - lo) } else { 0.5 };
                (ViridisRGB::get_color(t), number(v))
            } else {
                (RGBColor(200, 200, 200), "none".to_owned())
            };
            Cell {
                at: cell,
                fill,
                text,
                outlined: panel.outlined == Some(cell),
            }
        })
        .collect()
}

/// A value in four significant figures, in exponent form when large or small.
fn number(v: f64) -> String {
    if v != 0.0 && (v.abs() >= 1e4 || v.abs() < 1e-2) {
        format!("{v:.3e}")
    } else {
        format!("{v:.4}")
    }
}
