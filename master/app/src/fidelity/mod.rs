//! `slender fidelity`: a structure's sections at chosen fidelities (which model,
//! how fine), each combination run in parallel and measured against the
//! monolithic reference (the whole structure as one `nonlinear` unit at the
//! model's own mesh): the relative error epsilon (seed 000 eqs. 10-11) of each
//! quantity of interest, cost per simulated second, speed-up, iterations per
//! step and non-converged steps; the Pareto front of worst error against cost,
//! and the cheapest combination within a tolerance. A combination that cannot
//! be set up or fails is reported with its reason and the study goes on. A
//! `[mooring]`'s lines are studied the same way ([`mooring`]), against a run
//! with every line whole.

mod choice;
pub mod floors;
mod mooring;
pub mod quantities;
pub mod report;
mod rows;
mod run;
mod subject;

pub use choice::{Choice, SectionChoices};
use subject::{SectionName, Subject};

use crate::study::Design;
use quantities::{Features, SectionUnit};
use serde::Serialize;
use slender_scene::structure::{Layout, SectionLayout};
use std::path::Path;
use toml::{Table, Value};

/// What a fidelity study runs.
#[derive(Clone, Debug)]
pub struct FidelityPlan {
    /// Each section's choices.
    pub sections: Vec<SectionChoices>,
    /// Every combination, or one section's choices at a time (the others as
    /// the scene has them).
    pub design: Design,
    /// Simulated time of each run (s); the scene's when `None`.
    pub duration: Option<f64>,
    /// Runs at once.
    pub jobs: usize,
    /// The largest epsilon of every judged quantity a combination may have to
    /// count as good enough.
    pub tolerance: f64,
    /// The quantities whose worst epsilon judges a combination (its `worst`,
    /// the Pareto front, the tolerance); empty: all of them.
    pub judged: Vec<String>,
    /// The most runs the study may start (`--max-runs`).
    pub max_runs: usize,
    /// Times each run is timed (`--repeats`): its cost is their median.
    pub repeats: usize,
    /// Scene keys set over the file first (`KEY=VALUE`, `--set`).
    pub overrides: Vec<String>,
    /// The time (s) the errors are measured from (`--from`): the build-up
    /// before it left out; the whole run when None.
    pub from: Option<f64>,
}

/// One run: a combination (or the reference) and what it measured.
#[derive(Clone, Debug, Serialize)]
pub struct FidelityRow {
    /// Each section's choice (all sections, in order).
    pub combination: Vec<(String, String)>,
    /// Whether it is the reference (the structure as one model).
    pub reference: bool,
    /// epsilon of each quantity against the reference.
    pub errors: Vec<(String, f64)>,
    /// The largest of `errors` over the judged quantities.
    pub worst_error: f64,
    /// The median of the run's timed repeats.
    pub cost_per_simulated_second: f64,
    /// (max - min) / median of the repeats' costs (NaN for one).
    pub cost_spread: f64,
    /// The reference's cost over this run's.
    pub speed_up: f64,
    /// Coupling iterations per synchronisation step.
    pub iterations_per_step: f64,
    /// Steps the master did not converge in.
    pub non_converged_steps: u64,
    /// The master's start check: the largest relative change over the first
    /// step of a load a section's statics were solved under.
    pub start_change: Option<f64>,
    /// Not beaten in both worst error and cost by another combination.
    pub pareto: bool,
    /// Its worst error is within the tolerance.
    pub within_tolerance: bool,
    /// Why the run failed, when it did.
    pub error: Option<String>,
    /// The run's warnings: the scene's advisories (a section's model that
    /// follows the touchdown point poorly) and the plausibility watch's.
    pub warnings: Vec<String>,
}

/// A fidelity study's result.
#[derive(Clone, Debug, Serialize)]
pub struct FidelityReport {
    /// The scene file.
    pub scene: String,
    /// The largest worst error a combination may have.
    pub tolerance: f64,
    /// The time (s) the errors were measured from (`--from`), when given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub from: Option<f64>,
    /// Every quantity measured.
    pub quantities: Vec<String>,
    /// The quantities `worst` is taken over.
    pub judged: Vec<String>,
    /// The reference first, then the combinations.
    pub rows: Vec<FidelityRow>,
    /// Index in `rows` of the cheapest combination within the tolerance.
    pub cheapest: Option<usize>,
    /// Quantities whose reference is zero to round-off, judged against
    /// their kind's scale.
    pub floors: Vec<floors::Floor>,
}

/// One run: a combination of the sections' choices, or `None` for the
/// reference.
type Task = Option<Vec<(String, Choice)>>;

/// The structure as the study sees it: its sections as the scene writes them
/// (the expansion's layout) and what its model has.
struct Structure {
    layout: Layout,
    features: Features,
}

/// A run's recording reduced to the quantities (kept to resume a study).
#[derive(Serialize, serde::Deserialize)]
struct Outcome {
    time: Vec<f64>,
    series: Vec<Vec<f64>>,
    iterations_per_step: f64,
    non_converged_steps: u64,
    start_change: Option<f64>,
    /// The median of the run's timed repeats, and their spread.
    cost: f64,
    cost_spread: f64,
    error: Option<String>,
    /// The run's warnings (none in runs kept before they were).
    #[serde(default)]
    warnings: Vec<String>,
}

/// Runs the plan on the scene at `path`. `Err` when the study cannot start (the
/// scene does not load or has no `[structure]`, a section is not there).
pub fn run_fidelity(
    path: &Path,
    plan: &FidelityPlan,
    progress: impl Fn(&str) + Sync,
) -> Result<FidelityReport, crate::AppError> {
    run_fidelity_kept(path, plan, None, progress)
}

/// [`run_fidelity`] that reads back the runs `kept` holds instead of running
/// them again, and keeps each run it finishes without error (see
/// [`crate::resume`]).
pub fn run_fidelity_kept(
    path: &Path,
    plan: &FidelityPlan,
    kept: Option<&crate::resume::Kept>,
    progress: impl Fn(&str) + Sync,
) -> Result<FidelityReport, crate::AppError> {
    let mut draft = crate::study::draft_of(path, &plan.overrides)?;
    // The scene must load as written, and `--from` lie in its runs.
    let scene = crate::study::scene_of(&draft, plan.duration)?;
    window_in(plan.from, &scene)?;
    let subject = subject_of(draft.table())?;
    let subject = subject.as_ref();
    let sections = subject.sections();
    sections_asked(plan, &sections)?;
    // Runs record only what the study reads, and carry no twin.
    let mut table = draft.table().clone();
    subject.prepare(&mut table);
    table.remove("output");
    draft.change("the fidelity study (no twin, its own [output])", table);
    let names = subject.quantities();
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    // Before any run (a misspelt quantity was refused after them all), and
    // the bound last, so that a study refused for its size was otherwise valid.
    let judged = judged_of(plan, &names, subject)?;
    within_bound(plan)?;
    if let Some(kept) = kept {
        kept.claim()?;
    }
    let mut tasks: Vec<Task> = vec![None];
    tasks.extend(
        combinations(plan, &own_choices(&sections))
            .into_iter()
            .map(Some),
    );
    let order = order_of(&tasks);
    // Each finished run says which of how many it is, and the time left.
    let counter = crate::progress::Progress::new(tasks.len());
    let outcomes = crate::parallel::run_all(&tasks, &order, plan.jobs, |task| {
        let what = run::combination_label(task.as_deref());
        let fetched = crate::resume::run_or_reuse(
            kept,
            &what,
            |o: &Outcome| o.error.is_none(),
            || run::run_one(&draft, subject, task.as_deref(), plan),
        );
        let (outcome, reused) = (fetched.outcome, fetched.note);
        let k = counter.tick(!fetched.reused);
        let how = run::describe(&outcome);
        progress(&format!("{k} {what}: {how}{reused}"));
        outcome
    });
    crate::interrupt::stop_if_requested(&outcomes, |o: &Outcome| o.error.is_none())?;
    let (scales, floors) = floors::floors(&names, &outcomes[0], plan.from);
    let rows = rows::rows_of(
        subject,
        (&tasks, &outcomes),
        (&names, &scales),
        (plan.tolerance, &judged, plan.from),
    );
    let cheapest = rows
        .iter()
        .enumerate()
        .filter(|(_, r)| !r.reference && r.within_tolerance)
        .min_by(|a, b| {
            a.1.cost_per_simulated_second
                .total_cmp(&b.1.cost_per_simulated_second)
        })
        .map(|(k, _)| k);
    Ok(FidelityReport {
        scene: path.display().to_string(),
        tolerance: plan.tolerance,
        from: plan.from,
        quantities: names.iter().map(|n| (*n).to_owned()).collect(),
        judged,
        rows,
        cheapest,
        floors,
    })
}

/// Refuses a `--from` that is not a time before the runs' end.
fn window_in(from: Option<f64>, scene: &slender_scene::Scene) -> Result<(), String> {
    let (start, end) = (scene.start.as_secs(), scene.end().as_secs());
    match from {
        Some(from) if !(from.is_finite() && from < end) => Err(format!(
            "--from {from}: expected a time (s) before the runs' end, {end} (they start at {start})"
        )),
        _ => Ok(()),
    }
}

/// Refuses a study of more runs than `plan.max_runs`, counted before they
/// are built (a grid of many sections would not fit in memory).
fn within_bound(plan: &FidelityPlan) -> Result<(), String> {
    let choices = plan.sections.iter().map(|s| s.choices.len());
    let runs = match plan.design {
        Design::OneAtATime => choices.fold(1usize, usize::saturating_add),
        Design::Grid => choices
            .fold(1usize, usize::saturating_mul)
            .saturating_add(1),
    };
    if runs > plan.max_runs {
        return Err(crate::too_many_runs(
            "the reference and the combinations",
            runs,
            plan.max_runs,
        ));
    }
    Ok(())
}

/// Refuses a section given twice or not in the structure, naming them.
fn sections_asked(plan: &FidelityPlan, sections: &[SectionName]) -> Result<(), String> {
    for (k, s) in plan.sections.iter().enumerate() {
        if plan.sections[..k]
            .iter()
            .any(|earlier| earlier.section == s.section)
        {
            return Err(format!(
                "--section {}: the section is given twice; list its choices once, separated by commas",
                s.section
            ));
        }
        let found = sections.iter().find(|section| section.name == s.section);
        if let Some((earlier, later)) = found.and_then(|f| s.same_run(f.mesh)) {
            return Err(format!(
                "--section {}: `{}` and `{}` are the same run (the section's own mesh is {} elements); each choice runs once",
                s.section,
                earlier.label(),
                later.label(),
                found.map_or(0, |f| f.mesh)
            ));
        }
        if found.is_none() {
            let names: Vec<&str> = sections.iter().map(|s| s.name.as_str()).collect();
            return Err(format!(
                "--section {}: the structure has no section `{}`; its sections are {}",
                s.section,
                s.section,
                names.join(", ")
            ));
        }
    }
    Ok(())
}

/// What the scene's study varies: its `[mooring]`'s lines, else its
/// `[structure]`.
fn subject_of(table: &Table) -> Result<Box<dyn Subject>, String> {
    Ok(if table.contains_key("mooring") {
        Box::new(mooring::MooringLines::of(table)?)
    } else {
        Box::new(structure_of(table)?)
    })
}

/// The scene's `[structure]`: its layout and what its model has.
fn structure_of(table: &Table) -> Result<Structure, String> {
    let layout = slender_scene::structure::layout(table)?
        .ok_or("a fidelity study needs a scene with a `[structure]` or a `[mooring]`")?;
    let features = Features {
        seabed: layout.seabed,
        stinger: layout.stinger,
        // A 3D line has no stations to read its twin's force at a cut.
        cuts: (layout.sections.windows(2))
            .filter(|_| layout.planar)
            .map(|w| format!("cut_{}_{}", w[0].name, w[1].name))
            .collect(),
    };
    Ok(Structure { layout, features })
}

/// Each section's choice as the scene writes it, where it is a plain one (a
/// fidelity word, no count, sub-steps or options): (section, choice).
fn own_choices(sections: &[SectionName]) -> Vec<(String, Choice)> {
    (sections.iter())
        .filter(|s| s.plain)
        .map(|s| {
            let choice = Choice {
                fidelity: s.choice.clone(),
                elements: None,
                substeps: None,
                training: None,
            };
            (s.name.clone(), choice)
        })
        .collect()
}

/// The combinations the plan asks for. One section at a time, a choice that
/// is the section's own (`own`) leaves the scene as it is: that run (the
/// scene's own combination) is made once, under the first section that asks
/// for it, not once per section.
fn combinations(plan: &FidelityPlan, own: &[(String, Choice)]) -> Vec<Vec<(String, Choice)>> {
    let is_own = |section: &str, c: &Choice| own.iter().any(|(s, o)| s == section && o == c);
    match plan.design {
        Design::OneAtATime => {
            let mut scene_as_written = false;
            let mut runs = Vec::new();
            for s in &plan.sections {
                for c in &s.choices {
                    if is_own(&s.section, c) {
                        if scene_as_written {
                            continue;
                        }
                        scene_as_written = true;
                    }
                    runs.push(vec![(s.section.clone(), c.clone())]);
                }
            }
            runs
        }
        Design::Grid => plan.sections.iter().fold(vec![Vec::new()], |runs, s| {
            runs.into_iter()
                .flat_map(|run| {
                    s.choices.iter().map(move |c| {
                        let mut next = run.clone();
                        next.push((s.section.clone(), c.clone()));
                        next
                    })
                })
                .collect()
        }),
    }
}

/// Start order: the reference first, then the combinations with the most
/// nonlinear elements asked for (the likely costliest).
fn order_of(tasks: &[Task]) -> Vec<usize> {
    let weight = |t: &Task| match t {
        None => f64::INFINITY,
        Some(c) => c
            .iter()
            .map(|(_, c)| match c.fidelity.as_str() {
                "nonlinear" => c.elements.map_or(1e6, |n| n as f64),
                _ => c.elements.map_or(1.0, |n| n as f64 * 1e-3),
            })
            .sum(),
    };
    let mut order: Vec<usize> = (0..tasks.len()).collect();
    order.sort_by(|&a, &b| weight(&tasks[b]).total_cmp(&weight(&tasks[a])));
    order
}

/// The scene of one run: the combination's choices on the sections, or (for
/// the reference, `None`) the whole structure as one section; and its sections'
/// units, as the run's layout names them.
fn run_table(
    table: &Table,
    structure: &Structure,
    combination: Option<&[(String, Choice)]>,
) -> Result<(Table, Vec<SectionUnit>), String> {
    let mut table = table.clone();
    let s = table
        .get_mut("structure")
        .and_then(Value::as_table_mut)
        .ok_or("no `[structure]`")?;
    let sections = s
        .get_mut("sections")
        .and_then(Value::as_array_mut)
        .ok_or("`structure.sections`: expected a list")?;
    let Some(combination) = combination else {
        let mut whole = Table::new();
        whole.insert("name".into(), Value::String("monolithic".into()));
        *sections = vec![Value::Table(whole)];
        let planar = structure.layout.planar;
        let first = planar
            .then(|| add_cut_stations(s, &structure.layout))
            .transpose()?;
        let mut units = run_sections(&table)?;
        if let [whole] = units.as_mut_slice() {
            whole.cut_stations = first;
        }
        return finish(table, units, &structure.features);
    };
    for (name, choice) in combination {
        let section = sections
            .iter_mut()
            .filter_map(Value::as_table_mut)
            .find(|t| t.get("name").and_then(Value::as_str) == Some(name))
            .ok_or(format!("no section `{name}`"))?;
        slender_scene::structure::write_choice(
            section,
            &choice.fidelity,
            choice.elements,
            choice.substeps,
        )?;
        if let Some(t) = choice.training {
            slender_scene::structure::write_training(section, t)?;
        }
    }
    let mut units = run_sections(&table)?;
    let end_stations = add_end_stations(&mut table, &units)?;
    for (unit, ends) in units.iter_mut().zip(end_stations) {
        unit.end_stations = ends;
    }
    finish(table, units, &structure.features)
}

/// The sections' units of a run's scene, from its layout.
fn run_sections(table: &Table) -> Result<Vec<SectionUnit>, String> {
    let layout = slender_scene::structure::layout(table)?.ok_or("no `[structure]`")?;
    Ok(layout.sections.into_iter().map(SectionUnit::new).collect())
}

impl SectionUnit {
    /// A section of a run, before its stations are placed.
    fn new(section: SectionLayout) -> SectionUnit {
        SectionUnit {
            unit: section.unit,
            from: section.from,
            outputs: section.outputs,
            cut_stations: None,
            end_stations: [None, None],
        }
    }
}

/// The structure model's `stations` list (made empty when there is none).
fn model_stations(structure_table: &mut Table) -> Result<&mut Vec<Value>, String> {
    structure_table
        .get_mut("model")
        .and_then(Value::as_table_mut)
        .ok_or("`structure.model`: expected a table")?
        .entry("stations")
        .or_insert_with(|| Value::Array(Vec::new()))
        .as_array_mut()
        .ok_or_else(|| "`structure.model.stations`: expected a list".to_owned())
}

/// Puts stations in the elements on both sides of every cut between two
/// sections that take stations (native `nonlinear` units), just below the
/// cut in the lower section and at the cut in the upper one (a section holds
/// the model's stations in [from, to), numbered from 1 in the model's order);
/// returns each section's numbers of its first- and last-element stations.
fn add_end_stations(
    table: &mut Table,
    sections: &[SectionUnit],
) -> Result<Vec<[Option<usize>; 2]>, String> {
    let n = sections.len();
    let mut ends = vec![[None, None]; n];
    if !sections.iter().any(|s| s.outputs.stations) {
        return Ok(ends);
    }
    let structure_table = table
        .get_mut("structure")
        .and_then(Value::as_table_mut)
        .ok_or("no `[structure]`")?;
    let stations = model_stations(structure_table)?;
    let arc = |v: &Value| v.as_float().or_else(|| v.as_integer().map(|i| i as f64));
    let mut count = vec![0usize; n];
    let section_of = |s: f64| sections.iter().rposition(|section| section.from <= s);
    for s in stations.iter().filter_map(arc) {
        if let Some(k) = section_of(s) {
            count[k] += 1;
        }
    }
    for k in 0..n.saturating_sub(1) {
        if !sections[k].outputs.stations || !sections[k + 1].outputs.stations {
            continue;
        }
        let cut = sections[k + 1].from;
        // Inside the lower section's last element, clear of round-off.
        stations.push(Value::Float(cut - 1e-6 * cut.abs().max(1.0)));
        count[k] += 1;
        ends[k][1] = Some(count[k]);
        stations.push(Value::Float(cut));
        count[k + 1] += 1;
        ends[k + 1][0] = Some(count[k + 1]);
    }
    Ok(ends)
}

/// Puts a station at each cut on the whole structure's model (the reference),
/// after the model's own; returns the number of the first.
fn add_cut_stations(structure_table: &mut Table, layout: &Layout) -> Result<usize, String> {
    let stations = model_stations(structure_table)?;
    let first = stations.len() + 1;
    stations.extend((layout.sections.iter().skip(1)).map(|section| Value::Float(section.from)));
    Ok(first)
}

/// Adds the `[output]` that records the quantities' signals.
fn finish(
    mut table: Table,
    units: Vec<SectionUnit>,
    features: &Features,
) -> Result<(Table, Vec<SectionUnit>), String> {
    let signals = quantities::signals(&units, features);
    let mut output = Table::new();
    output.insert(
        "signals".into(),
        Value::Array(signals.into_iter().map(Value::String).collect()),
    );
    table.insert("output".into(), Value::Table(output));
    Ok((table, units))
}

/// The judged quantities: the plan's, each one the structure has, or the
/// subject's default.
fn judged_of(
    plan: &FidelityPlan,
    names: &[&str],
    subject: &dyn Subject,
) -> Result<Vec<String>, String> {
    if let Some(unknown) = plan.judged.iter().find(|q| !names.contains(&q.as_str())) {
        return Err(format!(
            "--quantities: `{unknown}` is not a quantity of this structure; it has {}",
            names.join(", ")
        ));
    }
    Ok(if plan.judged.is_empty() {
        subject.default_judged()
    } else {
        plan.judged.clone()
    })
}

#[cfg(test)]
mod tests;
