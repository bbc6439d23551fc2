//! One run of a fidelity study: a combination's scene built, run (timed
//! `--repeats` times) and reduced to the quantities.

use super::reference::{self, ReferenceMode};
use super::{Choice, FidelityPlan, Job, Outcome, Subject};
use crate::costs::repeated;
use crate::run::{RunOptions, run_scene};
use slender_scene::Draft;

/// What every run of a study shares.
pub(super) struct Study<'a, P> {
    pub(super) draft: &'a slender_scene::Draft,
    pub(super) subject: &'a dyn Subject,
    pub(super) plan: &'a FidelityPlan,
    pub(super) kept: Option<&'a crate::resume::Kept>,
    pub(super) progress: &'a P,
}

impl<P: Fn(&str) + Sync> Study<'_, P> {
    /// Runs one job (or reads it back from the kept runs) and says so.
    pub(super) fn run(&self, job: &Job, counter: &crate::progress::Progress) -> Outcome {
        let (what, level, combination) = match job {
            Job::Level(k) => (reference::label(*k), *k, None),
            Job::Combination(c) => (combination_label(Some(c)), 0, Some(c.as_slice())),
        };
        let fetched = crate::resume::run_or_reuse(
            self.kept,
            &what,
            |o: &Outcome| o.error.is_none(),
            || run_one(self.draft, self.subject, (combination, level), self.plan),
        );
        let (outcome, reused) = (fetched.outcome, fetched.note);
        let k = counter.tick(!fetched.reused);
        let how = describe(&outcome);
        (self.progress)(&format!("{k} {what}: {how}{reused}"));
        outcome
    }

    /// `converged`: runs finer levels of the reference, one at a time, until
    /// the two finest differ by less than a fifth of the tolerance on every
    /// judged quantity, a level fails, or the plan's refinements are spent.
    pub(super) fn refine_until_converged(
        &self,
        levels: &mut Vec<(f64, Outcome)>,
        measure: &reference::Measure,
        judged: &[String],
    ) -> Result<(), crate::AppError> {
        if self.plan.reference != ReferenceMode::Converged {
            return Ok(());
        }
        while levels.len() <= self.plan.max_refinements as usize {
            let [.., (_, coarser), (step, finer)] = levels.as_slice() else {
                break;
            };
            let change = measure.errors(coarser, finer);
            if finer.error.is_some() || !reference::wants_more(&change, judged, self.plan.tolerance)
            {
                break;
            }
            let step = step / 2.0;
            let outcome = self.run(
                &Job::Level(levels.len() as u32),
                &crate::progress::Progress::new(1),
            );
            crate::interrupt::stop_if_requested(std::slice::from_ref(&outcome), |o: &Outcome| {
                o.error.is_none()
            })?;
            levels.push((step, outcome));
        }
        Ok(())
    }
}

/// Runs one combination (for `None`, the reference at `level`, see
/// [`super::reference`]) and reduces its recording to the quantities; its
/// cost is the median of `plan.repeats` timed runs.
pub(super) fn run_one(
    draft: &Draft,
    subject: &dyn Subject,
    (combination, level): (Option<&[(String, Choice)]>, u32),
    plan: &FidelityPlan,
) -> Outcome {
    let failed = |error: String| Outcome {
        time: Vec::new(),
        series: Vec::new(),
        iterations_per_step: f64::NAN,
        non_converged_steps: 0,
        start_change: None,
        cost: f64::NAN,
        cost_spread: f64::NAN,
        error: Some(error),
        warnings: Vec::new(),
    };
    let (mut table, reader) = match subject.run_table(draft.table(), combination) {
        Ok(t) => t,
        Err(e) => return failed(e),
    };
    let what = match combination {
        None => super::reference::label(level),
        Some(_) => combination_label(combination),
    };
    if combination.is_none()
        && let Err(e) = super::reference::refine(&mut table, level)
    {
        return failed(e);
    }
    let mut draft = draft.clone();
    draft.change(format!("the fidelity study's {what}"), table);
    let scene = match crate::study::scene_of(&draft, plan.duration) {
        Ok(s) => s,
        Err(e) => return failed(e.to_string()),
    };
    let options = RunOptions {
        output_dir: None,
        progress: false,
        realtime: false,
    };
    let result = match run_scene(&scene, &options) {
        Ok(r) => r,
        Err(e) => return failed(e.to_string()),
    };
    let series = reader(&result.recorder);
    let counters = &result.summary.counters;
    let again =
        || run_scene(&scene, &options).map_or(f64::NAN, |r| r.summary.cost_per_simulated_second);
    let (cost, cost_spread) = match result.summary.error {
        None => repeated(
            plan.repeats,
            result.summary.cost_per_simulated_second,
            again,
        ),
        Some(_) => (result.summary.cost_per_simulated_second, f64::NAN),
    };
    match series {
        Ok(series) => Outcome {
            time: result.recorder.time.clone(),
            series,
            iterations_per_step: counters.mean_iterations(),
            non_converged_steps: counters.non_converged_steps,
            start_change: counters.start_load.as_ref().map(|l| l.relative_change),
            cost,
            cost_spread,
            error: result.summary.error.clone(),
            warnings: result.summary.warnings.clone(),
        },
        Err(e) => failed(e),
    }
}

/// A combination in words (the reference's name for `None`).
pub(super) fn combination_label(combination: Option<&[(String, Choice)]>) -> String {
    match combination {
        None => "reference (monolithic)".to_owned(),
        Some(c) => c
            .iter()
            .map(|(s, c)| format!("{s}={}", c.label()))
            .collect::<Vec<_>>()
            .join(" "),
    }
}

/// A line of progress for a finished run: its cost, or why it failed.
pub(super) fn describe(o: &Outcome) -> String {
    match &o.error {
        Some(e) => format!("FAILED: {e}"),
        None if o.cost_spread.is_finite() => format!(
            "{:.3e} s per simulated s (median, spread {:.0} %)",
            o.cost,
            100.0 * o.cost_spread
        ),
        None => format!("{:.3e} s per simulated s", o.cost),
    }
}
