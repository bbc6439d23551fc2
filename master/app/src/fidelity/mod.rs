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
pub mod reference;
mod reference_report;
pub mod report;
mod rows;
mod run;
mod structure_runs;
mod subject;

pub use choice::{Choice, SectionChoices};
pub use reference::{ReferenceCheck, ReferenceMode};
use subject::{SectionName, Subject};

use crate::study::Design;
use quantities::Features;
use serde::Serialize;
use slender_scene::structure::Layout;
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
    /// The time (s) the errors are measured from (`--from`, else the
    /// scene's `[output] quantities_from`): the build-up before it left
    /// out; the whole run when None.
    pub from: Option<f64>,
    /// The reference and how its own error is estimated (`--reference`).
    pub reference: ReferenceMode,
    /// The most halvings of the reference's element length and step
    /// `converged` may make (`--refinements`).
    pub max_refinements: u32,
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
    /// The reference's own error: its levels and the estimate.
    pub reference: ReferenceCheck,
}

/// One row's run: a combination of the sections' choices, or `None` for the
/// reference at the model's mesh.
type Task = Option<Vec<(String, Choice)>>;

/// One run of the study: a level of the reference (0: the model's mesh;
/// [`reference`]), or a combination.
enum Job {
    Level(u32),
    Combination(Vec<(String, Choice)>),
}

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
    let plan = &FidelityPlan {
        from: plan.from.or(declared_from(&scene, &progress)),
        ..plan.clone()
    };
    let subject = subject_of(draft.table())?;
    let subject = subject.as_ref();
    let sections = subject.sections();
    sections_asked(plan, &sections)?;
    let names = subject.quantities();
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    // Before any run (a misspelt quantity was refused after them all), and
    // the bound last, so that a study refused for its size was otherwise valid.
    let judged = judged_of(plan, draft.table(), &names, subject)?;
    within_bound(plan)?;
    // Runs record only what the study reads, and carry no twin.
    let mut table = draft.table().clone();
    subject.prepare(&mut table);
    table.remove("output");
    draft.change("the fidelity study (no twin, its own [output])", table);
    if let Some(kept) = kept {
        kept.claim()?;
    }
    let first = reference::first_levels(plan.reference);
    let mut jobs: Vec<Job> = (0..first).map(Job::Level).collect();
    jobs.extend(
        combinations(plan, &own_choices(&sections))
            .into_iter()
            .map(Job::Combination),
    );
    let order = order_of(&jobs);
    // Each finished run says which of how many it is, and the time left.
    let counter = crate::progress::Progress::new(jobs.len());
    let study = run::Study {
        draft: &draft,
        subject,
        plan,
        kept,
        progress: &progress,
    };
    let mut outcomes =
        crate::parallel::run_all(&jobs, &order, plan.jobs, |job| study.run(job, &counter));
    crate::interrupt::stop_if_requested(&outcomes, |o: &Outcome| o.error.is_none())?;
    let combination_outcomes = outcomes.split_off(first as usize);
    let step = scene.step.as_secs();
    let mut levels: Vec<(f64, Outcome)> = (outcomes.into_iter().enumerate())
        .map(|(k, o)| (step / (1u64 << k) as f64, o))
        .collect();
    let (scales, floors) = floors::floors(&names, &levels[0].1, plan.from);
    let measure = reference::Measure {
        names: &names,
        scales: &scales,
        from: plan.from,
    };
    study.refine_until_converged(&mut levels, &measure, &judged)?;
    let runs = (jobs, levels, combination_outcomes);
    let scene = path.display().to_string();
    Ok(report_of(
        subject,
        runs,
        &measure,
        (plan, judged, scene, floors),
    ))
}

/// The report of a study's runs: the reference's check from its levels, the
/// rows judged against the level the plan asks for, the cheapest within the
/// tolerance.
fn report_of(
    subject: &dyn Subject,
    (jobs, mut levels, combination_outcomes): (Vec<Job>, Vec<(f64, Outcome)>, Vec<Outcome>),
    measure: &reference::Measure,
    (plan, judged, scene, floors): (&FidelityPlan, Vec<String>, String, Vec<floors::Floor>),
) -> FidelityReport {
    let judging = match plan.reference {
        ReferenceMode::Converged => levels.len() - 1,
        _ => 0,
    };
    let check = reference::check(
        (plan.reference, &levels, judging),
        measure,
        (&judged, plan.tolerance),
    );
    let tasks: Vec<Task> = std::iter::once(None)
        .chain(jobs.into_iter().filter_map(|job| match job {
            Job::Combination(c) => Some(Some(c)),
            Job::Level(_) => None,
        }))
        .collect();
    // The finer level judged against (the last), then the model's mesh, the
    // first row: moved out, not copied.
    let finer = (judging > 0)
        .then(|| levels.pop())
        .flatten()
        .map(|(_, o)| o);
    let model_mesh = levels.into_iter().next().map(|(_, o)| o);
    let row_outcomes: Vec<Outcome> = model_mesh.into_iter().chain(combination_outcomes).collect();
    let rows = rows::rows_of(
        subject,
        (&tasks, &row_outcomes, finer.as_ref()),
        (measure.names, measure.scales),
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
    FidelityReport {
        scene,
        tolerance: plan.tolerance,
        from: plan.from,
        quantities: measure.names.iter().map(|n| (*n).to_owned()).collect(),
        judged,
        rows,
        cheapest,
        floors,
        reference: check,
    }
}

/// The scene's `[output] quantities_from`, unless a run shortened by
/// `--duration` ends before it: then the whole run is judged, said through
/// `progress` (a scene's indicator past a shortened run is left out alike).
fn declared_from(scene: &slender_scene::Scene, progress: &dyn Fn(&str)) -> Option<f64> {
    let from = scene.spec.output.quantities_from?;
    let end = scene.end().as_secs();
    if from < end {
        return Some(from);
    }
    progress(&format!(
        "warning: `[output] quantities_from` = {from} s is not before the runs' end ({end} s): the errors are measured over the whole run"
    ));
    None
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
/// are built (a grid of many sections would not fit in memory); a converged
/// reference counts every level it may run.
fn within_bound(plan: &FidelityPlan) -> Result<(), String> {
    let choices = plan.sections.iter().map(|s| s.choices.len());
    let combinations = match plan.design {
        Design::OneAtATime => choices.fold(0usize, usize::saturating_add),
        Design::Grid => choices.fold(1usize, usize::saturating_mul),
    };
    let runs = combinations.saturating_add(reference::most_levels(plan) as usize);
    if runs > plan.max_runs {
        return Err(crate::too_many_runs(
            "the reference's levels and the combinations",
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

/// Start order: the reference's levels first (the finest first), then the
/// combinations with the most nonlinear elements asked for (the likely
/// costliest).
fn order_of(jobs: &[Job]) -> Vec<usize> {
    // (level + 1 for a level, else 0; the combination's weight), largest first.
    let key = |job: &Job| match job {
        Job::Level(k) => (k + 1, 0.0),
        Job::Combination(c) => {
            let weight = (c.iter())
                .map(|(_, c)| match c.fidelity.as_str() {
                    "nonlinear" => c.elements.map_or(1e6, |n| n as f64),
                    _ => c.elements.map_or(1.0, |n| n as f64 * 1e-3),
                })
                .sum();
            (0, weight)
        }
    };
    let mut order: Vec<usize> = (0..jobs.len()).collect();
    order.sort_by(|&a, &b| {
        let ((la, wa), (lb, wb)) = (key(&jobs[a]), key(&jobs[b]));
        lb.cmp(&la).then(wb.total_cmp(&wa))
    });
    order
}

/// The judged quantities: the plan's (`--quantities`), else the scene's
/// `[output] quantities`, each one the structure has; or the subject's
/// default.
fn judged_of(
    plan: &FidelityPlan,
    scene: &Table,
    names: &[&str],
    subject: &dyn Subject,
) -> Result<Vec<String>, String> {
    let declared: Vec<String> = (scene.get("output"))
        .and_then(|o| o.get("quantities"))
        .and_then(Value::as_array)
        .map(|q| {
            q.iter()
                .filter_map(Value::as_str)
                .map(str::to_owned)
                .collect()
        })
        .unwrap_or_default();
    let (asked, source) = match (plan.judged.is_empty(), declared.is_empty()) {
        (false, _) => (&plan.judged, "--quantities"),
        (true, false) => (&declared, "`[output] quantities` of the scene"),
        (true, true) => return Ok(subject.default_judged()),
    };
    if let Some(unknown) = asked.iter().find(|q| !names.contains(&q.as_str())) {
        return Err(format!(
            "{source}: `{unknown}` is not a quantity of this structure; it has {}",
            names.join(", ")
        ));
    }
    Ok(asked.clone())
}

#[cfg(test)]
mod tests;
