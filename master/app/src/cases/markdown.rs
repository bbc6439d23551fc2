//! A load-case matrix's report as Markdown (`cases.md`, the report page):
//! the design values, the fatigue over the scatter, each group's extremes
//! and damage, and the cases that failed.

use super::aggregate::CasesReport;

/// The report's tables.
pub fn to_markdown(report: &CasesReport) -> String {
    let mut md = format!(
        "# Load-case matrix of {}\n\n{} cases in {} sea states and headings; the probabilities sum to {}.\n\n",
        report.scene,
        report.cases,
        report.groups.len(),
        report.probability_sum
    );
    let place = |g: usize| {
        let group = &report.groups[g];
        let heading = group
            .heading_deg
            .map_or(String::new(), |h| format!(", {h} deg"));
        format!(
            "Hs {} m, Tp {} s{heading}",
            group.significant_height, group.peak_period
        )
    };
    if !report.design.is_empty() {
        let over = report
            .durations
            .storm_s
            .unwrap_or(report.durations.window_s);
        md += &format!(
            "## Design values\n\nThe largest of the groups' extremes (a group: a sea state and heading over its seeds), each the most probable largest value over {over} s (basis `gumbel`: the seeds' largest values in their {} s windows, carried to it; `weibull`, `rayleigh`: the runs' own most probable maxima; `largest seen`: the windows' largest values).\n\n| signal | design value | basis | from |\n|---|---|---|---|\n",
            report.durations.window_s
        );
        for d in &report.design {
            md += &format!(
                "| {} | {:.6e} | {} | {} |\n",
                d.signal,
                d.value,
                d.basis,
                place(d.group)
            );
        }
        md += "\n";
    }
    for f in &report.fatigue {
        md += &format!(
            "## Fatigue: {}\n\nDamage per year over the scatter {:.4e}: a life of {:.4e} years (no design fatigue factor).\n\n| sea state | probability | damage per year there | share of the damage |\n|---|---|---|---|\n",
            f.name, f.damage_per_year, f.life_years
        );
        for (g, c) in f.contributions.iter().enumerate() {
            let group = &report.groups[g];
            let there = c / group.probability;
            md += &format!(
                "| {} | {} | {there:.4e} | {:.3} |\n",
                place(g),
                group.probability,
                c / f.damage_per_year
            );
        }
        md += "\n";
    }
    md += "## Extremes per group\n\n| sea state | seeds completed | signal | extreme | basis | Gumbel location, scale |\n|---|---|---|---|---|---|\n";
    for (g, group) in report.groups.iter().enumerate() {
        for e in &group.extremes {
            let gumbel = e
                .gumbel
                .map_or("-".to_owned(), |(l, s)| format!("{l:.6e}, {s:.4e}"));
            md += &format!(
                "| {} | {} | {} | {:.6e} | {} | {gumbel} |\n",
                place(g),
                group.completed,
                e.signal,
                e.value,
                e.basis
            );
        }
    }
    if !report.failed.is_empty() {
        md += "\n## Failed cases\n\n| case | reason |\n|---|---|\n";
        for (k, why) in &report.failed {
            md += &format!("| {k} | {} |\n", why.replace('|', "/").replace('\n', " "));
        }
    }
    md
}
