//! A run's report page: its outcome, the coupling's counters, the indicators,
//! the warnings, each signal's unit (and its statistics, extremes, spectral
//! moments and fatigue damage, when the scene asks for them) and every figure.

use super::Part;
use crate::run::Summary;
use std::path::PathBuf;

/// The parts of a run's page: the summary as tables, then the figures.
pub fn parts(summary: &Summary, figures: &[PathBuf]) -> Vec<Part> {
    let c = &summary.counters;
    let iterations = if c.steps > 0 {
        c.iterations as f64 / c.steps as f64
    } else {
        f64::NAN
    };
    let mut md = format!(
        "| status | simulated (s) | step (s) | cost (s per simulated s) | steps | iterations per step | non-converged steps | rollbacks |\n|---|---|---|---|---|---|---|---|\n| {} | {} | {} | {:.3e} | {} | {iterations:.2} | {} | {} |\n\n",
        summary.status,
        summary.simulated_s,
        summary.step_s,
        summary.cost_per_simulated_second,
        c.steps,
        c.non_converged_steps,
        c.rollbacks
    );
    if let Some(a) = &c.adaptive {
        md += &adaptive_steps(a);
    }
    if let Some(error) = &summary.error {
        md += &format!("Error: {}\n\n", error.replace('\n', " "));
    }
    for warning in &summary.warnings {
        md += &format!("Warning: {}\n\n", warning.replace('\n', " "));
    }
    if !summary.indicators.is_empty() {
        md += "| indicator | relative error epsilon | fidelity phi |\n|---|---|---|\n";
        for i in &summary.indicators {
            md += &format!(
                "| {} | {:.3e} | {:.3} |\n",
                i.name, i.relative_error, i.fidelity
            );
        }
        md += "\n";
    }
    md += &units_and_statistics(summary);
    md += &extremes_and_spectra(summary);
    md += &fatigue(summary);
    md += &envelopes(summary);
    let mut parts = vec![Part::Heading(summary.title.clone()), Part::Markdown(md)];
    parts.extend(figures.iter().map(|f| Part::figure(f, Vec::new())));
    parts
}

/// The adaptive step's table: steps accepted per size, then the repeated ones.
fn adaptive_steps(a: &slender_coupling::counters::StepSizes) -> String {
    let mut md = "| adaptive step (s) | steps accepted |\n|---|---|\n".to_owned();
    for (n, h) in a.accepted.iter().zip(&a.sizes_s) {
        md += &format!("| {h} | {n} |\n");
    }
    md += &format!(
        "\n{} steps repeated at half the size over the tolerance, {} after a failure, {} accepted at the smallest step over it; largest estimate {:.3} x the tolerance{}.\n\n",
        a.rejected,
        a.failed,
        a.over_tolerance,
        a.largest_estimate,
        if a.largest_at.is_empty() {
            String::new()
        } else {
            format!(" (on {})", a.largest_at)
        }
    );
    md
}

/// A row per recorded signal: its unit, and with `[output] statistics` its
/// statistics over the window asked for.
fn units_and_statistics(summary: &Summary) -> String {
    if summary.analysis.statistics.is_empty() {
        let mut md = "| signal | unit |\n|---|---|\n".to_owned();
        for (signal, unit) in &summary.units {
            md += &format!(
                "| {signal} | {} |\n",
                if unit.is_empty() { "-" } else { unit }
            );
        }
        return md;
    }
    let mut md = "| signal | unit | mean | standard deviation | skewness | kurtosis | min | max | zero-up-crossing period (s) |\n|---|---|---|---|---|---|---|---|---|\n".to_owned();
    for (signal, unit) in &summary.units {
        let unit = if unit.is_empty() { "-" } else { unit };
        let Some(s) = summary.analysis.statistics.get(signal) else {
            md += &format!("| {signal} | {unit} | | | | | | | |\n");
            continue;
        };
        let period = s
            .zero_up_crossing_period
            .map_or("-".to_owned(), |t| format!("{t:.3}"));
        md += &format!(
            "| {signal} | {unit} | {:.4e} | {:.4e} | {:.3} | {:.3} | {:.4e} | {:.4e} | {period} |\n",
            s.mean, s.std_dev, s.skewness, s.kurtosis, s.min, s.max
        );
    }
    md
}

/// A row per signal with `statistics.extremes` or `statistics.spectra`: the
/// most probable maxima (Rayleigh, Weibull with its fit) and the spectrum's
/// variance and periods.
fn extremes_and_spectra(summary: &Summary) -> String {
    let a = &summary.analysis;
    if a.extremes.is_empty() && a.spectra.is_empty() {
        return String::new();
    }
    let mut md = "\n| signal | peaks | largest seen | MPM Rayleigh | MPM Weibull | Weibull shape | Weibull R2 | MPM GPD | GPD shape | GPD KS | m0 of spectrum | peak period (s) | Tz of spectrum (s) |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n".to_owned();
    let or_dash =
        |v: Option<f64>, digits: usize| v.map_or("-".to_owned(), |v| format!("{v:.digits$}"));
    for signal in summary.units.keys() {
        let (e, p) = (a.extremes.get(signal), a.spectra.get(signal));
        if e.is_none() && p.is_none() {
            continue;
        }
        let w = e.and_then(|e| e.weibull.as_ref());
        let g = e.and_then(|e| e.gpd.as_ref());
        let sci = |v: Option<f64>| v.map_or("-".to_owned(), |v| format!("{v:.4e}"));
        md += &format!(
            "| {signal} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
            e.map_or("-".to_owned(), |e| e.peaks.to_string()),
            sci(e.map(|e| e.largest_seen)),
            sci(e.map(|e| e.rayleigh_mpm)),
            sci(w.map(|w| w.mpm)),
            or_dash(w.map(|w| w.shape), 3),
            or_dash(w.map(|w| w.r_squared), 4),
            sci(g.map(|g| g.mpm)),
            or_dash(g.map(|g| g.shape), 3),
            or_dash(g.map(|g| g.ks_distance), 3),
            sci(p.map(|p| p.m0)),
            or_dash(p.and_then(|p| p.peak_period_s), 3),
            or_dash(p.and_then(|p| p.zero_crossing_period_s), 3),
        );
    }
    if let Some(e) = a.extremes.values().next() {
        md += &format!("\nMost probable maxima over {} s.\n", e.duration_s);
    }
    md
}

/// A row per `[[output.fatigue]]` entry: its cycles, largest range and damage.
fn fatigue(summary: &Summary) -> String {
    if summary.analysis.fatigue.is_empty() {
        return String::new();
    }
    let mut md = "\n| fatigue | window (s) | cycles | largest range | damage | damage per year | life (years) |\n|---|---|---|---|---|---|---|\n".to_owned();
    for (name, d) in &summary.analysis.fatigue {
        md += &format!(
            "| {name} | {} | {} | {:.4e} | {:.4e} | {:.4e} | {:.4e} |\n",
            d.window_s, d.cycles, d.largest_range, d.damage, d.damage_per_year, d.life_years
        );
    }
    md
}

/// A row per unit and field with `[output] envelopes`: its extremes along
/// the unit and where they are.
fn envelopes(summary: &Summary) -> String {
    if summary.analysis.envelopes.is_empty() {
        return String::new();
    }
    let mut md = "\n| unit | field | max | at arc (m) | min | at arc (m) | steps |\n|---|---|---|---|---|---|---|\n".to_owned();
    for e in &summary.analysis.envelopes {
        md += &format!(
            "| {} | {} ({}) | {:.4e} | {:.1} | {:.4e} | {:.1} | {} |\n",
            e.unit, e.field, e.unit_of_measure, e.max, e.max_arc_m, e.min, e.min_arc_m, e.samples
        );
    }
    md
}
