//! The runs a study makes: each group's assignments of values to the varied
//! keys (its reference first), and the order that starts the costliest first.

use super::setting::{Refinement, Setting, numeric};
use super::{Design, StudyPlan};

/// A varied key with its value.
pub(super) type Assignment = (Setting, toml::Value);

/// Task indices by likely cost, descending: a run's cost grows with its element
/// counts and falls with its step.
pub(super) fn costliest_first(tasks: &[&Vec<Assignment>]) -> Vec<usize> {
    let weight = |task: &Vec<Assignment>| {
        task.iter()
            .fold(1.0f64, |w, (s, v)| match (s.refinement(), numeric(v)) {
                (Refinement::Larger, Some(x)) => w * x,
                (Refinement::Smaller, Some(x)) if s.to_string().contains("step") => w / x,
                _ => w,
            })
    };
    let mut order: Vec<usize> = (0..tasks.len()).collect();
    order.sort_by(|&a, &b| weight(tasks[b]).total_cmp(&weight(tasks[a])));
    order
}

/// The runs of each group, the reference first.
pub(super) fn groups(plan: &StudyPlan) -> Vec<(String, Vec<Vec<Assignment>>)> {
    match plan.design {
        Design::OneAtATime => plan
            .sweeps
            .iter()
            .map(|s| {
                let mut values: Vec<&toml::Value> = vec![s.reference()];
                values.extend(s.values.iter().filter(|v| *v != s.reference()));
                let runs = values
                    .into_iter()
                    .map(|v| vec![(s.setting.clone(), v.clone())])
                    .collect();
                (s.setting.to_string(), runs)
            })
            .collect(),
        Design::Grid => {
            let mut runs: Vec<Vec<Assignment>> = vec![Vec::new()];
            for s in &plan.sweeps {
                let mut values: Vec<&toml::Value> = vec![s.reference()];
                values.extend(s.values.iter().filter(|v| *v != s.reference()));
                runs = runs
                    .into_iter()
                    .flat_map(|run| {
                        values.iter().map(move |v| {
                            let mut next = run.clone();
                            next.push((s.setting.clone(), (*v).clone()));
                            next
                        })
                    })
                    .collect();
            }
            vec![("grid".into(), runs)]
        }
    }
}
