//! A study's request in the command line's words: what a results folder's
//! `request.txt` holds and what the refusal of another study into it names.
//! Only what shapes the results is written (not `--jobs`, `--max-runs`,
//! `--out` or `--fresh`), in a fixed order, so the same study asked with its
//! options in another order is the same request.

use slender_app::fidelity::{FidelityPlan, ReferenceMode};
use slender_app::study::StudyPlan;
use std::path::Path;

/// `slender study SCENE --vary ... [--grid] ...` for `plan`.
pub(super) fn study(scene: &Path, plan: &StudyPlan) -> String {
    let mut words = format!("slender study {}", scene.display());
    for sweep in &plan.sweeps {
        let values: Vec<String> = sweep.values.iter().map(value_as_given).collect();
        words += &format!(" --vary {}={}", sweep.setting, values.join(","));
    }
    if plan.design == slender_app::study::Design::Grid {
        words += " --grid";
    }
    if let Some(reference) = &plan.reference {
        words += &format!(" --reference {}", reference.display());
    }
    if !plan.cost_units.is_empty() {
        words += &format!(" --cost {}", plan.cost_units.join(","));
    }
    words + &runs(plan.duration, plan.repeats, &plan.overrides)
}

/// `slender fidelity SCENE --section ... [--grid] ...` for `plan`.
pub(super) fn fidelity(scene: &Path, plan: &FidelityPlan) -> String {
    let mut words = format!("slender fidelity {}", scene.display());
    for section in &plan.sections {
        let choices: Vec<String> = section.choices.iter().map(|c| c.label()).collect();
        words += &format!(" --section {}={}", section.section, choices.join(","));
    }
    if plan.design == slender_app::study::Design::Grid {
        words += " --grid";
    }
    words += &format!(" --tolerance {}", plan.tolerance);
    if !plan.judged.is_empty() {
        words += &format!(" --quantities {}", plan.judged.join(","));
    }
    if let Some(from) = plan.from {
        words += &format!(" --from {from}");
    }
    words += match plan.reference {
        ReferenceMode::Model => " --reference model",
        ReferenceMode::Estimate => " --reference estimate",
        ReferenceMode::Converged => " --reference converged",
    };
    if plan.reference == ReferenceMode::Converged {
        words += &format!(" --refinements {}", plan.max_refinements);
    }
    words + &runs(plan.duration, plan.repeats, &plan.overrides)
}

/// The options every study shares: `--duration`, `--repeats`, `--set`.
fn runs(duration: Option<f64>, repeats: usize, overrides: &[String]) -> String {
    let mut words = String::new();
    if let Some(d) = duration {
        words += &format!(" --duration {d}");
    }
    if repeats != 1 {
        words += &format!(" --repeats {repeats}");
    }
    for set in overrides {
        words += &format!(" --set {set}");
    }
    words
}

/// A swept value as the command line gave it (a word without quotes).
fn value_as_given(value: &toml::Value) -> String {
    match value {
        toml::Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use slender_app::study::{Design, Sweep};

    #[test]
    fn a_study_is_asked_in_the_command_line_s_words_whatever_the_order_of_its_options() {
        let sweep = |s: &str| s.parse::<Sweep>().expect("a sweep");
        let plan = StudyPlan {
            sweeps: vec![
                sweep("master.scheme=jacobi,gauss_seidel"),
                sweep("simulation.step=0.1,0.05"),
            ],
            design: Design::Grid,
            duration: Some(10.0),
            jobs: 2,
            cost_units: vec!["line".into()],
            reference: None,
            max_runs: 100,
            repeats: 3,
            overrides: vec!["master.max_iterations=20".into()],
        };
        assert_eq!(
            study(Path::new("examples/b1_two_masses.toml"), &plan),
            "slender study examples/b1_two_masses.toml --vary master.scheme=jacobi,gauss_seidel --vary simulation.step=0.1,0.05 --grid --cost line --duration 10 --repeats 3 --set master.max_iterations=20"
        );
        // What does not shape the results is not part of the request.
        let other = StudyPlan {
            jobs: 1,
            max_runs: 5,
            ..plan.clone()
        };
        assert_eq!(
            study(Path::new("a.toml"), &plan),
            study(Path::new("a.toml"), &other)
        );
    }
}
