//! `slender fidelity`'s plan: which runs it makes.

use super::*;

/// A one-section-at-a-time plan of `sections` (`NAME=CHOICE,...`).
fn one_at_a_time(sections: &[&str]) -> FidelityPlan {
    FidelityPlan {
        overrides: Vec::new(),
        max_runs: crate::DEFAULT_MAX_RUNS,
        repeats: 1,
        sections: sections.iter().map(|s| s.parse().unwrap()).collect(),
        design: Design::OneAtATime,
        duration: None,
        jobs: 1,
        tolerance: 0.01,
        judged: Vec::new(),
    }
}

#[test]
fn one_section_at_a_time_runs_the_scene_as_written_once() {
    let table: Table = r#"
[structure]
name = "line"
model = { segments = [{ length = 30.0, elements = 6 }] }
[[structure.sections]]
name = "lower"
to = 10.0
fidelity = "cable"
[[structure.sections]]
name = "middle"
to = 20.0
elements = 4
[[structure.sections]]
name = "upper"
"#
    .parse()
    .unwrap();
    let plan = one_at_a_time(&[
        "lower=cable,static",
        "middle=nonlinear",
        "upper=nonlinear,nonlinear:8",
    ]);
    let layout = slender_scene::structure::layout(&table).unwrap().unwrap();
    let labels: Vec<String> = combinations(&plan, &own_choices(&layout))
        .iter()
        .map(|run| format!("{}={}", run[0].0, run[0].1.label()))
        .collect();
    // `lower=cable` is the scene as written; `upper=nonlinear` is it again
    // (dropped); `middle=nonlinear` is not (the scene gives 4 elements).
    assert_eq!(
        labels,
        [
            "lower=cable",
            "lower=static",
            "middle=nonlinear",
            "upper=nonlinear:8"
        ]
    );
}

#[test]
fn a_section_given_twice_is_refused() {
    let plan = one_at_a_time(&["lower=cable", "lower=static"]);
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/structure_mooring.toml");
    let e = run_fidelity(&path, &plan, |_| {}).expect_err("refused");
    assert!(
        e.contains("--section lower: the section is given twice"),
        "{e}"
    );
}
