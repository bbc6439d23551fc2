//! The twin's own error in a study (issue 48): a study whose indicators judge
//! a run against reference signals inside it (a structure's twin) runs the
//! scene as written once more at half its element length and half its step
//! (the fidelity study's level 1, [`crate::fidelity::reference::refine`]) and
//! reports, per such indicator, the epsilon of its reference signals between
//! the two runs: the twin's estimated discretisation error (for a method of
//! order p >= 1 its true error lies between this and twice it), to read beside
//! the errors the study measures against that twin.

use super::{QUIET, StudyPlan, draft_of, scene_of};
use crate::AppError;
use crate::indicators::{indicator, interpolate, normalized_error, window};
use crate::record::Recorder;
use crate::run::run_scene;
use serde::Serialize;
use slender_scene::spec::Combine;
use std::path::Path;

/// What a study knows of its in-run twin's own error.
#[derive(Clone, Debug, Serialize)]
pub enum TwinError {
    /// Estimated from the scene and the same at half its element length
    /// and step.
    Estimated {
        /// Per indicator with reference signals: their epsilon at the
        /// scene's mesh and step against the same at half of each.
        estimates: Vec<(String, f64)>,
        /// The refined run's cost (s per simulated s).
        refined_cost: f64,
    },
    /// Why it was not estimated (no structure to refine, a run failed).
    NotEstimated(String),
}

/// The twin's error of the study `plan` on the scene at `path`; None when no
/// indicator has reference signals of its own. `Err` only when the scene does
/// not load (the study itself would have refused it).
pub fn twin_error(path: &Path, plan: &StudyPlan) -> Result<Option<TwinError>, AppError> {
    let draft = draft_of(path, &plan.overrides)?;
    let base = scene_of(&draft, plan.duration)?;
    let in_run: Vec<_> = (base.spec.output.indicators.iter())
        .filter(|i| !i.reference.is_empty())
        .map(|i| (i.name.clone(), i.reference.clone(), (i.from, i.combine)))
        .collect();
    if in_run.is_empty() {
        return Ok(None);
    }
    let mut table = draft.table().clone();
    if !(table.contains_key("structure") || table.contains_key("mooring")) {
        return Ok(Some(TwinError::NotEstimated(
            "the scene has no [structure] or [mooring] whose mesh a study can refine".into(),
        )));
    }
    if let Err(e) = crate::fidelity::reference::refine(&mut table, 1) {
        return Ok(Some(TwinError::NotEstimated(e)));
    }
    let mut refined = draft.clone();
    refined.change("the twin at half its element length and step", table);
    // The study itself ran: a refined scene that does not load (its step
    // bound, say) leaves the estimate out, not the study.
    let refined = match scene_of(&refined, plan.duration) {
        Ok(scene) => scene,
        Err(e) => {
            return Ok(Some(TwinError::NotEstimated(format!(
                "the refined scene: {e}"
            ))));
        }
    };
    let run = |scene| match run_scene(scene, &QUIET) {
        Ok(r) if r.summary.error.is_none() => Ok(r),
        Ok(r) => Err(r.summary.error.unwrap_or_default()),
        Err(e) => Err(e.to_string()),
    };
    let (coarse, fine) = match (run(&base), run(&refined)) {
        (Ok(c), Ok(f)) => (c, f),
        (Err(e), _) => {
            return Ok(Some(TwinError::NotEstimated(format!(
                "the scene's run: {e}"
            ))));
        }
        (_, Err(e)) => {
            return Ok(Some(TwinError::NotEstimated(format!(
                "the refined run: {e}"
            ))));
        }
    };
    let estimates = (in_run.iter())
        .map(|(name, signals, window)| {
            let e = change(&coarse.recorder, &fine.recorder, signals, *window);
            (name.clone(), e.unwrap_or(f64::NAN))
        })
        .collect();
    Ok(Some(TwinError::Estimated {
        estimates,
        refined_cost: fine.summary.cost_per_simulated_second,
    }))
}

/// epsilon of `signals` in `coarse` against `fine` (resampled at the coarse
/// run's times), from `from` (s) on, their components made by `combine`;
/// None where a signal was not recorded.
fn change(
    coarse: &Recorder,
    fine: &Recorder,
    signals: &[String],
    (from, combine): (Option<f64>, Combine),
) -> Option<f64> {
    let mut x: Vec<&[f64]> = Vec::new();
    let mut r: Vec<Vec<f64>> = Vec::new();
    for s in signals {
        x.push(coarse.column(s)?);
        let f = fine.column(s)?;
        r.push(
            coarse
                .time
                .iter()
                .map(|&t| interpolate(&fine.time, f, t))
                .collect(),
        );
    }
    let (x, r) = (
        combine.apply(x),
        combine.apply(r.iter().map(Vec::as_slice).collect()),
    );
    let x: Vec<&[f64]> = x.iter().map(|c| &**c).collect();
    let r: Vec<&[f64]> = r.iter().map(|c| &**c).collect();
    let (time, x) = window(&coarse.time, &x, from);
    let (_, r) = window(&coarse.time, &r, from);
    Some(indicator("", normalized_error(time, &x, &r)).relative_error)
}

/// The twin's error as Markdown, for the study's report.
pub fn to_markdown(twin: &TwinError) -> String {
    match twin {
        TwinError::Estimated {
            estimates,
            refined_cost,
        } => {
            let items: Vec<String> = (estimates.iter())
                .map(|(n, e)| format!("{n} {e:.2e}"))
                .collect();
            format!(
                "\nThe twin's own error, estimated by the epsilon of each indicator's reference signals between the scene as written and the same at half its element length and half its step ({refined_cost:.3e} s per simulated s); its true error is between this and twice it for a method of order p >= 1: {}. An epsilon against the twin below its own error says nothing more about the physics.\n",
                items.join(", ")
            )
        }
        TwinError::NotEstimated(why) => {
            format!("\nThe twin's own error is not estimated: {why}.\n")
        }
    }
}
