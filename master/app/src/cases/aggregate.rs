//! A load-case matrix's aggregate: per sea state and heading (a group of
//! seeds), each signal's extreme and each fatigue entry's mean damage; over
//! the matrix, each signal's design value (the largest group's) and each
//! entry's damage per year summed with the groups' probabilities, as
//! DNV-OS-E301 combines them.
//!
//! A group's extreme: with 3 seeds or more, the most probable value of a
//! Gumbel distribution fitted to the seeds' largest values over the window
//! (method of moments), carried to the storm's duration when the scene's
//! `extremes` gives one (the largest of k windows is Gumbel with the same
//! scale and its location moved by scale ln k); with fewer, the mean over
//! the seeds of each run's Weibull MPM over the storm (when every seed has a
//! fit), else of its Rayleigh MPM, else of its largest value in the window.
//! The basis is said beside each value.

use super::{CasesPlan, Row};
use serde::Serialize;

/// One sea state and heading over its seeds.
#[derive(Clone, Debug, Serialize)]
pub struct Group {
    /// Significant wave height Hs (m).
    pub significant_height: f64,
    /// Peak period Tp (s).
    pub peak_period: f64,
    /// Heading (deg); none: the scene's own.
    pub heading_deg: Option<f64>,
    /// The sea state's probability times the heading's.
    pub probability: f64,
    /// The seeds that completed.
    pub completed: usize,
    /// Per signal: its extreme and the basis of it.
    pub extremes: Vec<Extreme>,
    /// Per fatigue entry: the mean damage per year over the seeds.
    pub damage_per_year: Vec<(String, f64)>,
}

/// A signal's extreme in a group.
#[derive(Clone, Debug, Serialize)]
pub struct Extreme {
    /// The signal's name.
    pub signal: String,
    /// Its extreme (the signal's unit).
    pub value: f64,
    /// `gumbel`, `weibull`, `rayleigh` or `largest seen`.
    pub basis: &'static str,
    /// The Gumbel fit's location and scale, with 3 seeds or more.
    pub gumbel: Option<(f64, f64)>,
}

/// A signal's design value: the largest of its groups' extremes.
#[derive(Clone, Debug, Serialize)]
pub struct DesignValue {
    /// The signal's name.
    pub signal: String,
    /// Its design value (the signal's unit).
    pub value: f64,
    /// How the group's extreme was found (see [`Extreme::basis`]).
    pub basis: &'static str,
    /// The group it comes from (an index into `CasesReport::groups`).
    pub group: usize,
}

/// A fatigue entry's damage over the scatter.
#[derive(Clone, Debug, Serialize)]
pub struct FatigueLife {
    /// The fatigue entry's name (`[[fatigue]]`).
    pub name: String,
    /// The sum over the groups of probability x mean damage per year; NaN
    /// when a group has no completed seed.
    pub damage_per_year: f64,
    /// 1 / damage per year (years).
    pub life_years: f64,
    /// Each group's share of the damage (probability x its damage).
    pub contributions: Vec<f64>,
}

/// The times the extremes are over (s).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Durations {
    /// Each run's window: its duration less the statistics' `from`.
    pub window_s: f64,
    /// The scene's `extremes.duration`, when it gives one.
    pub storm_s: Option<f64>,
}

/// What `cases.json` holds.
#[derive(Clone, Debug, Serialize)]
pub struct CasesReport {
    /// The scene file.
    pub scene: String,
    /// How many cases the matrix has.
    pub cases: usize,
    /// The times the extremes are over.
    pub durations: Durations,
    /// Each failed case's index and reason.
    pub failed: Vec<(usize, String)>,
    /// The sum of the groups' probabilities (1 for a whole scatter).
    pub probability_sum: f64,
    /// One group per sea state and heading.
    pub groups: Vec<Group>,
    /// Each signal's design value over the groups.
    pub design: Vec<DesignValue>,
    /// Each fatigue entry's damage over the scatter.
    pub fatigue: Vec<FatigueLife>,
}

/// The location and scale of a Gumbel distribution fitted to `maxima` by the
/// method of moments: scale = s sqrt(6) / pi (s with n - 1), location =
/// mean minus 0.5772 scale; the location is its most probable value. None
/// with fewer than three.
pub fn gumbel_fit(maxima: &[f64]) -> Option<(f64, f64)> {
    if maxima.len() < 3 {
        return None;
    }
    let n = maxima.len() as f64;
    let mean = maxima.iter().sum::<f64>() / n;
    let sd = (maxima.iter().map(|m| (m - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
    let scale = sd * 6f64.sqrt() / std::f64::consts::PI;
    const EULER_GAMMA: f64 = 0.577_215_664_901_532_9;
    Some((mean - EULER_GAMMA * scale, scale))
}

/// The aggregate of `rows` (by case index; None: not run or failed) whose
/// values are in `columns` (`table::columns`).
pub fn aggregate(
    plan: &CasesPlan,
    columns: &[String],
    rows: &[Option<Row>],
    durations: Durations,
) -> Vec<Group> {
    let cases = plan.cases();
    let mut groups: Vec<Group> = Vec::new();
    let mut members: Vec<Vec<&Vec<f64>>> = Vec::new();
    for (k, case) in cases.iter().enumerate() {
        if case.seed == 1 {
            let sea = plan.seas[case.sea];
            let heading = case.heading.map(|h| plan.headings[h]);
            groups.push(Group {
                significant_height: sea.significant_height,
                peak_period: sea.peak_period,
                heading_deg: heading.map(|h| h.degrees),
                probability: sea.probability * heading.map_or(1.0, |h| h.probability),
                completed: 0,
                extremes: Vec::new(),
                damage_per_year: Vec::new(),
            });
            members.push(Vec::new());
        }
        if let (Some(Some((values, None))), Some(m)) = (rows.get(k), members.last_mut()) {
            m.push(values);
        }
    }
    for (group, values) in groups.iter_mut().zip(&members) {
        group.completed = values.len();
        let column = |name: &str| -> Vec<f64> {
            let i = columns.iter().position(|c| c == name);
            i.map_or(Vec::new(), |i| values.iter().map(|v| v[i]).collect())
        };
        for c in columns {
            if let Some(signal) = c.strip_suffix("/max") {
                let m = |what: &str| column(&format!("{signal}/{what}"));
                group.extremes.push(extreme(
                    durations,
                    signal,
                    &m("max"),
                    &m("weibull_mpm"),
                    &m("rayleigh_mpm"),
                ));
            } else if let Some(name) = c.strip_suffix("/damage_per_year") {
                group
                    .damage_per_year
                    .push((name.to_owned(), mean(&column(c))));
            }
        }
    }
    groups
}

/// A signal's extreme from its seeds' maxima, Weibull and Rayleigh MPMs.
fn extreme(
    durations: Durations,
    signal: &str,
    maxima: &[f64],
    weibull: &[f64],
    rayleigh: &[f64],
) -> Extreme {
    let whole = |v: &[f64]| !v.is_empty() && v.iter().all(|x| x.is_finite());
    let windows = durations
        .storm_s
        .map_or(1.0, |storm| storm / durations.window_s);
    let (value, basis, gumbel) = match gumbel_fit(maxima) {
        Some((location, scale)) => (
            location + scale * windows.ln(),
            "gumbel",
            Some((location, scale)),
        ),
        None if whole(weibull) => (mean(weibull), "weibull", None),
        None if whole(rayleigh) => (mean(rayleigh), "rayleigh", None),
        None => (mean(maxima), "largest seen", None),
    };
    Extreme {
        signal: signal.to_owned(),
        value,
        basis,
        gumbel,
    }
}

/// The mean of `values`; NaN for none.
fn mean(values: &[f64]) -> f64 {
    values.iter().sum::<f64>() / values.len() as f64
}

/// The report: the groups, each signal's design value and each fatigue
/// entry's damage summed over the scatter.
pub fn report(
    scene: String,
    plan: &CasesPlan,
    (columns, durations): (&[String], Durations),
    rows: &[Option<Row>],
    failed: Vec<(usize, String)>,
) -> CasesReport {
    let groups = aggregate(plan, columns, rows, durations);
    let mut design: Vec<DesignValue> = Vec::new();
    for (g, group) in groups.iter().enumerate() {
        for (i, e) in group.extremes.iter().enumerate() {
            match design.get_mut(i) {
                None => design.push(DesignValue {
                    signal: e.signal.clone(),
                    value: e.value,
                    basis: e.basis,
                    group: g,
                }),
                Some(d) if e.value > d.value || d.value.is_nan() => {
                    (d.value, d.basis, d.group) = (e.value, e.basis, g);
                }
                Some(_) => {}
            }
        }
    }
    let names: Vec<String> = groups.first().map_or(Vec::new(), |g| {
        g.damage_per_year.iter().map(|d| d.0.clone()).collect()
    });
    let fatigue = (names.iter().enumerate())
        .map(|(i, name)| {
            let contributions: Vec<f64> = groups
                .iter()
                .map(|g| g.probability * g.damage_per_year[i].1)
                .collect();
            let total: f64 = contributions.iter().sum();
            FatigueLife {
                name: name.clone(),
                damage_per_year: total,
                life_years: 1.0 / total,
                contributions,
            }
        })
        .collect();
    CasesReport {
        scene,
        cases: plan.cases().len(),
        durations,
        failed,
        probability_sum: groups.iter().map(|g| g.probability).sum(),
        groups,
        design,
        fatigue,
    }
}
