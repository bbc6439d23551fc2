//! What a study checks before its first run: its keys and cost units apply
//! to the scene, each sweep can be compared, and its size is within its
//! bound (counted, not built: a grid of many sweeps would not fit in memory).

use super::{Design, StudyPlan, label, scene_of};
use slender_scene::{Draft, Scene};
use std::path::Path;

/// Refuses what does not apply to the scene: a key (a typo, a unit that is not
/// there), a cost unit it does not have, a sweep of one value with no reference
/// scene to compare it with.
pub(super) fn check_plan(
    path: &Path,
    base: &Scene,
    draft: &Draft,
    plan: &StudyPlan,
    has_reference: bool,
) -> Result<(), crate::AppError> {
    for name in &plan.cost_units {
        if !base.spec.units.iter().any(|u| u.name.get_ref() == name) {
            return Err(format!(
                "cost unit `{name}`: {} has no unit of that name",
                path.display()
            )
            .into());
        }
    }
    for sweep in &plan.sweeps {
        if sweep.values.len() < 2 && !has_reference {
            return Err(format!(
                "{}: a sweep needs at least two values (or a reference scene)",
                sweep.setting
            )
            .into());
        }
        let mut probe = draft.clone();
        let origin = format!("--vary {}={}", sweep.setting, label(sweep.reference()));
        probe
            .edit(origin, |t| sweep.setting.apply(t, sweep.reference()))
            .map_err(|e| format!("{}: {e}", sweep.setting))?;
        scene_of(&probe, plan.duration)?;
    }
    // Last, so that a study refused for its size was otherwise valid.
    let runs = run_count(plan);
    if runs > plan.max_runs {
        return Err(crate::too_many_runs("the study", runs, plan.max_runs).into());
    }
    Ok(())
}

/// The runs the plan makes, saturating: one per value of each sweep
/// (one-at-a-time), or every combination (grid).
fn run_count(plan: &StudyPlan) -> usize {
    let values = plan.sweeps.iter().map(|s| {
        let reference = s.reference();
        1 + s.values.iter().filter(|v| *v != reference).count()
    });
    match plan.design {
        Design::OneAtATime => values.fold(0usize, usize::saturating_add),
        Design::Grid => values.fold(1usize, usize::saturating_mul),
    }
}
