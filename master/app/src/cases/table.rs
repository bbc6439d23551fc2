//! A load-case matrix's table, `cases.csv`: a row per case (its sea state,
//! heading, seed and status, then the values it gives), written as the runs
//! finish and read back to resume a matrix or merge its shards. Values are
//! written in Rust's shortest round-trip form, so a row read back is the row
//! written, bit for bit, and the aggregate of merged shards is the local one's.

use super::{CasesPlan, Row};
use crate::analysis::Analysis;
use slender_scene::Scene;

/// The columns a case gives: each recorded signal's largest value over the
/// window (`SIGNAL/max`) and, with `extremes`, its most probable maxima
/// (`SIGNAL/rayleigh_mpm`, `SIGNAL/weibull_mpm`); each fatigue entry's
/// damage per year (`NAME/damage_per_year`).
pub fn columns(scene: &Scene, signals: &[String]) -> Vec<String> {
    let extremes = scene
        .spec
        .output
        .statistics
        .and_then(|s| s.extremes)
        .is_some();
    let mut columns = Vec::new();
    for s in signals {
        columns.push(format!("{s}/max"));
        if extremes {
            columns.push(format!("{s}/rayleigh_mpm"));
            columns.push(format!("{s}/weibull_mpm"));
        }
    }
    for f in &scene.spec.output.fatigue {
        columns.push(format!("{}/damage_per_year", f.name));
    }
    columns
}

/// A completed run's values in the order of `columns` (NaN where the window
/// gave none: a Weibull fit of under 10 peaks).
pub fn values(columns: &[String], analysis: &Analysis) -> Vec<f64> {
    (columns.iter())
        .map(|c| {
            let (name, what) = c.rsplit_once('/').unwrap_or((c, ""));
            let value = match what {
                "max" => analysis.statistics.get(name).map(|s| s.max),
                "rayleigh_mpm" => analysis.extremes.get(name).map(|e| e.rayleigh_mpm),
                "weibull_mpm" => (analysis.extremes.get(name))
                    .and_then(|e| e.weibull.as_ref())
                    .map(|w| w.mpm),
                "damage_per_year" => analysis.fatigue.get(name).map(|d| d.damage_per_year),
                _ => None,
            };
            value.unwrap_or(f64::NAN)
        })
        .collect()
}

/// The CSV header: the case's description, then the columns.
pub fn header(columns: &[String]) -> String {
    let mut text = "case,significant_height,peak_period,probability,heading_deg,heading_probability,seed,status".to_owned();
    for c in columns {
        text += &format!(",{c}");
    }
    text + "\n"
}

/// Case `k`'s row.
pub fn row(plan: &CasesPlan, k: usize, row: &Row) -> String {
    let case = plan.cases()[k];
    let sea = plan.seas[case.sea];
    let (heading, probability) = case.heading.map_or((String::new(), String::new()), |h| {
        let h = plan.headings[h];
        (format!("{}", h.degrees), format!("{}", h.probability))
    });
    let status = if row.1.is_none() {
        "completed"
    } else {
        "failed"
    };
    let mut text = format!(
        "{k},{},{},{},{heading},{probability},{},{status}",
        sea.significant_height, sea.peak_period, sea.probability, case.seed
    );
    for v in &row.0 {
        text += &format!(",{v}");
    }
    text + "\n"
}

/// The completed rows of a `cases.csv` written for this plan and these
/// columns, by case index; a row whose case is not the plan's case of that
/// index (another matrix's file) or that failed is left out, to run again.
pub fn read(text: &str, plan: &CasesPlan, columns: &[String]) -> Vec<Option<Row>> {
    let cases = plan.cases();
    let mut rows = vec![None; cases.len()];
    let Some(body) = text.strip_prefix(&header(columns)) else {
        return rows;
    };
    for line in body.lines() {
        let fields: Vec<&str> = line.split(',').collect();
        let Some(k) = fields.first().and_then(|f| f.parse::<usize>().ok()) else {
            continue;
        };
        if k >= cases.len() || fields.len() != 8 + columns.len() || fields[7] != "completed" {
            continue;
        }
        let again = format!("{}\n", line);
        let values: Option<Vec<f64>> = fields[8..].iter().map(|f| f.parse().ok()).collect();
        if let Some(values) = values {
            let row = (values, None);
            // The description must be this plan's case k, to the character.
            if self::row(plan, k, &row) == again {
                rows[k] = Some(row);
            }
        }
    }
    rows
}
