//! A study's rows as CSV and as a Markdown table.

use super::StudyRow;

/// The setting column: the key of a one-at-a-time sweep, or every key=value of a
/// grid point.
fn setting_of(r: &StudyRow) -> String {
    if r.settings.len() == 1 {
        r.settings[0].0.clone()
    } else {
        r.settings
            .iter()
            .map(|(k, v)| format!("{k}={v}"))
            .collect::<Vec<_>>()
            .join(";")
    }
}

fn value_of(r: &StudyRow) -> String {
    r.settings
        .first()
        .map(|(_, v)| v.clone())
        .unwrap_or_default()
}

fn names(rows: &[StudyRow]) -> Vec<&str> {
    rows.first()
        .map(|r| r.errors.iter().map(|(n, _)| n.as_str()).collect())
        .unwrap_or_default()
}

/// The rows as CSV: setting, value, epsilon and observed order per indicator,
/// iterations per step, the start check's change, cost, error.
pub fn to_csv(rows: &[StudyRow]) -> String {
    let names = names(rows);
    let eps: Vec<String> = names.iter().map(|n| format!("epsilon_{n}")).collect();
    let orders: Vec<String> = names.iter().map(|n| format!("order_{n}")).collect();
    let mut out = format!(
        "setting,value,{},{},iterations_per_step,start_change,cost_per_simulated_second,cost_spread,error\n",
        eps.join(","),
        orders.join(",")
    );
    for r in rows {
        let eps: Vec<String> = r.errors.iter().map(|(_, e)| format!("{e:e}")).collect();
        let orders: Vec<String> = r.orders.iter().map(|(_, p)| format!("{p}")).collect();
        out += &format!(
            "{},{},{},{},{},{},{:e},{},{}\n",
            setting_of(r).replace(',', ";"),
            value_of(r).replace(',', ";"),
            eps.join(","),
            orders.join(","),
            r.iterations_per_step,
            r.start_change.map(|c| format!("{c:e}")).unwrap_or_default(),
            r.cost_per_simulated_second,
            crate::costs::csv(r.cost_spread),
            r.error.as_deref().unwrap_or("").replace(',', ";")
        );
    }
    out
}

/// The rows as a Markdown table.
pub fn to_markdown(rows: &[StudyRow]) -> String {
    let names = names(rows);
    let mut out = format!(
        "| setting | value | {} | {} | iterations/step | start change | cost (s per simulated s) |\n|---|---|{}{}---|---|---|\n",
        names
            .iter()
            .map(|n| format!("epsilon {n}"))
            .collect::<Vec<_>>()
            .join(" | "),
        names
            .iter()
            .map(|n| format!("order {n}"))
            .collect::<Vec<_>>()
            .join(" | "),
        "---|".repeat(names.len()),
        "---|".repeat(names.len())
    );
    for r in rows {
        let eps: Vec<String> = r
            .errors
            .iter()
            .map(|(_, e)| {
                // The reference run against itself; an indicator with its
                // reference in the run (an analytic solution) has an error
                // there too, and shows it.
                if r.reference && *e == 0.0 {
                    "reference".into()
                } else {
                    format!("{e:.2e}")
                }
            })
            .collect();
        let orders: Vec<String> = r
            .orders
            .iter()
            .map(|(_, p)| {
                if p.is_finite() {
                    format!("{p:.2}")
                } else {
                    "-".into()
                }
            })
            .collect();
        out += &format!(
            "| {} | {} | {} | {} | {:.2} | {} | {} |{}\n",
            setting_of(r),
            value_of(r),
            eps.join(" | "),
            orders.join(" | "),
            r.iterations_per_step,
            start_change(r.start_change),
            crate::costs::cell(r.cost_per_simulated_second, r.cost_spread),
            r.error
                .as_ref()
                .map(|e| format!(" failed: {e}"))
                .unwrap_or_default()
        );
    }
    let mut floored: Vec<&String> = rows.iter().flat_map(|r| &r.floored).collect();
    floored.sort();
    floored.dedup();
    if !floored.is_empty() {
        out += &format!(
            "\nJudged against their indicator's largest component (their reference is round-off against it): {}.\n",
            floored
                .iter()
                .map(|f| format!("`{f}`"))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    out
}

/// The start check's change as a percentage, "-" where no section's statics
/// were solved under a coupled load.
pub fn start_change(change: Option<f64>) -> String {
    change.map_or("-".into(), |c| format!("{:.2} %", 100.0 * c))
}

/// The error-against-cost figure of a study: each run (its settings, the
/// worst epsilon over the indicators against its group's reference, its
/// cost); failed runs are left out.
pub fn tradeoff<'a>(rows: &[StudyRow], title: &'a str) -> crate::figures::tradeoff::Tradeoff<'a> {
    let points = rows
        .iter()
        .filter(|r| r.error.is_none())
        .map(|r| crate::figures::tradeoff::Point {
            label: r
                .settings
                .iter()
                .map(|(k, v)| format!("{k}={v}"))
                .collect::<Vec<_>>()
                .join(" "),
            cost: r.cost_per_simulated_second,
            error: r.errors.iter().map(|e| e.1).fold(0.0, f64::max),
        })
        .collect();
    crate::figures::tradeoff::Tradeoff {
        title,
        error_label: "worst epsilon against the reference (-)",
        points,
        tolerance: None,
        reference_cost: None,
        chosen: None,
    }
}
