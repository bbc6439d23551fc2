//! `slender fidelity`'s plan: which runs it makes.

use super::*;

/// A one-section-at-a-time plan of `sections` (`NAME=CHOICE,...`).
fn one_at_a_time(sections: &[&str]) -> FidelityPlan {
    FidelityPlan {
        reference: ReferenceMode::Model,
        max_refinements: 3,
        from: None,
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
model = { segments = [{ length = 30.0, elements = 6, axial_stiffness = 1e9, bending_stiffness = 1e5, mass_per_length = 100.0 }] }
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
    let sections: Vec<SectionName> = (layout.sections.iter())
        .map(|s| SectionName::of(s.name.clone(), s))
        .collect();
    let labels: Vec<String> = combinations(&plan, &own_choices(&sections))
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
    assert!(e.is_input(), "{e}");
    let e = e.to_string();
    assert!(
        e.contains("--section lower: the section is given twice"),
        "{e}"
    );
}

/// The OC3 spar's mooring (20 s, 10-element lines): a section named alone
/// is studied in every line, `LINE.SECTION` in that line only, each against
/// a run with every line whole; the lines' tensions judge, the body's
/// motions are reported; a section no line has is refused with the names.
#[test]
fn a_mooring_s_line_sections_are_studied_against_every_line_whole() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/oc3_hywind_jonswap.toml");
    let mut plan = one_at_a_time(&["lower=nonlinear", "line1.upper=nonlinear:4"]);
    plan.duration = Some(20.0);
    plan.overrides = vec!["mooring.line.elements=10".into()];
    let report = run_fidelity(&path, &plan, |_| {}).unwrap();
    assert_eq!(
        report.judged,
        ["line1_tension", "line2_tension", "line3_tension"]
    );
    assert_eq!(report.quantities.len(), 9, "{:?}", report.quantities);
    assert_eq!(report.rows.len(), 3);
    for row in &report.rows {
        assert!(row.error.is_none(), "{:?}", row.error);
    }
    let label = |row: &FidelityRow, section: &str| {
        let found = row.combination.iter().find(|(s, _)| s == section);
        found.map(|(_, c)| c.clone()).unwrap_or_default()
    };
    let (all_lower, one_upper) = (&report.rows[1], &report.rows[2]);
    for line in ["line1", "line2", "line3"] {
        assert_eq!(label(all_lower, &format!("{line}.lower")), "nonlinear");
        assert_eq!(label(one_upper, &format!("{line}.lower")), "static");
    }
    assert_eq!(label(one_upper, "line1.upper"), "nonlinear:4");
    assert_eq!(label(one_upper, "line2.upper"), "nonlinear");
    // The lower halves as the line's own mesh: the whole line cut in two.
    assert!(all_lower.worst_error < 1e-3, "{}", all_lower.worst_error);
    // Four elements on line 1's upper half: that line's tension moves most.
    let error = |row: &FidelityRow, q: &str| row.errors.iter().find(|e| e.0 == q).unwrap().1;
    assert!(error(one_upper, "line1_tension") > error(one_upper, "line2_tension"));
    plan.sections = vec!["line4.lower=static".parse().unwrap()];
    let refused = run_fidelity(&path, &plan, |_| {})
        .expect_err("no line4")
        .to_string();
    assert!(
        refused.contains("line1.lower") && refused.contains("line4.lower"),
        "{refused}"
    );
}

/// Issue 49, item 18: `nonlinear` and `nonlinear:N` with N the section's
/// own mesh are the same run, refused as a choice listed twice.
#[test]
fn a_bare_choice_and_its_own_mesh_are_one_run() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/structure_mooring.toml");
    let table: Table = std::fs::read_to_string(&path).unwrap().parse().unwrap();
    let layout = slender_scene::structure::layout(&table).unwrap().unwrap();
    let mesh = layout.sections[0].mesh;
    assert_eq!(layout.sections[0].name, "lower");
    assert!(mesh > 1, "{mesh}");
    let same = one_at_a_time(&[&format!("lower=cable,nonlinear,nonlinear:{mesh}")]);
    let e = run_fidelity(&path, &same, |_| {})
        .expect_err("one run twice")
        .to_string();
    assert!(
        e.contains(&format!(
            "--section lower: `nonlinear` and `nonlinear:{mesh}` are the same run (the section's own mesh is {mesh} elements)"
        )),
        "{e}"
    );
    // Another count is another run: refused only by the bound, after.
    let mut other = one_at_a_time(&[&format!("lower=nonlinear,nonlinear:{}", mesh + 1)]);
    other.max_runs = 0;
    let e = run_fidelity(&path, &other, |_| {})
        .expect_err("the bound")
        .to_string();
    assert!(e.contains("more than the bound of 0"), "{e}");
}

/// Issue 49, item 5: `--from` measures the errors after a build-up (the
/// hanging pipe's end starts at full speed), and must lie in the runs.
#[test]
fn errors_measured_from_a_time_leave_out_the_build_up() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/structure_hanging_pipe.toml");
    let mut plan = one_at_a_time(&["middle=linear"]);
    plan.duration = Some(2.0);
    let whole = run_fidelity(&path, &plan, |_| {}).expect("the study");
    plan.from = Some(1.0);
    let late = run_fidelity(&path, &plan, |_| {}).expect("the study");
    assert_eq!(late.from, Some(1.0));
    let worst = |r: &FidelityReport| r.rows[1].worst_error;
    assert!(worst(&whole).is_finite() && worst(&late).is_finite());
    assert_ne!(worst(&whole), worst(&late));
    plan.from = Some(2.0);
    let e = run_fidelity(&path, &plan, |_| {})
        .expect_err("past the end")
        .to_string();
    assert!(
        e.contains("--from 2: expected a time (s) before the runs' end, 2"),
        "{e}"
    );
    // The scene says when its quantities are judged from; `--from` wins.
    plan.from = None;
    plan.overrides = vec!["output.quantities_from=1.0".into()];
    let declared = run_fidelity(&path, &plan, |_| {}).expect("the study");
    assert_eq!(declared.from, Some(1.0));
    assert_eq!(worst(&declared), worst(&late));
    plan.from = Some(0.0);
    let asked = run_fidelity(&path, &plan, |_| {}).expect("the study");
    assert_eq!(asked.from, Some(0.0));
    // A run shortened past it judges the whole run and says so.
    plan.from = None;
    plan.overrides = vec!["output.quantities_from=3.0".into()];
    let said = std::sync::Mutex::new(Vec::new());
    let shortened = run_fidelity(&path, &plan, |line| {
        said.lock().unwrap().push(line.to_owned())
    })
    .expect("the study");
    assert_eq!(shortened.from, None);
    assert_eq!(worst(&shortened), worst(&whole));
    let said = said.into_inner().unwrap();
    assert!(
        said.iter()
            .any(|l| l.contains("`[output] quantities_from` = 3 s is not before")),
        "{said:?}"
    );
}
