//! Fidelities per section (issue 13): seed 000's mooring line as a structure whose
//! lower section is the geometrically nonlinear unit, seed 000's cable (linear
//! about its static state) or a coarser mesh. The cable follows the monolithic
//! twin to the model difference, a same-mesh partition to the coupling
//! tolerance; swapping a section's fidelity changes its unit and its cuts only;
//! `slender fidelity` reports every combination against the monolithic
//! reference, goes on past a combination that cannot run, and gives the same
//! errors whatever the number of jobs.

use slender_app::fidelity::{FidelityPlan, SectionChoices, run_fidelity};
use slender_app::study::Design;
use slender_scene::Scene;
use slender_tests::{impulsive, links_away_from, root, run, units_and_links};
use toml::Value;

/// The mooring example, `duration` s long, with its sections replaced by
/// `sections` (TOML of `[[structure.sections]]`).
fn mooring(duration: f64, sections: Option<&str>) -> String {
    let text = impulsive(
        &std::fs::read_to_string(root().join("examples/structure_mooring.toml")).unwrap(),
    );
    let text = text.replace("duration = 60.0", &format!("duration = {duration}"));
    match sections {
        None => text,
        Some(s) => {
            let (head, tail) = text.split_once("[[structure.sections]]").unwrap();
            let (_, output) = tail.split_once("[output]").unwrap();
            format!("{head}{s}\n[output]{output}")
        }
    }
}

fn parse(text: &str) -> Result<Scene, String> {
    Scene::parse(
        &root().join("examples/structure_mooring.toml"),
        text.to_owned(),
    )
    .map_err(|e| e.to_string())
}

/// epsilon of the top force (x and z) against the twin.
fn top_force_epsilon(text: &str) -> f64 {
    let s = run(&parse(text).expect("scene"));
    assert!(s.error.is_none(), "{:?}", s.error);
    let i = s.indicators.iter().find(|i| i.name == "top_force").unwrap();
    i.relative_error
}

const CABLE: &str = "[[structure.sections]]\nname = \"lower\"\nto = 1571.375\nfidelity = \"cable\"\n[[structure.sections]]\nname = \"upper\"\n";

#[test]
fn a_cable_lower_section_follows_the_nonlinear_twin() {
    // The cable leaves out the bending (EI = 100 N m^2 on a 1934 m line) and
    // the geometric nonlinearity about the static state: 5.3e-4 measured over
    // 20 s; a same-mesh nonlinear lower section: 1.8e-6, the coupling tolerance.
    let cable = top_force_epsilon(&mooring(20.0, Some(CABLE)));
    let same = top_force_epsilon(&mooring(
        20.0,
        Some(&CABLE.replace("fidelity = \"cable\"", "fidelity = \"nonlinear\"")),
    ));
    println!("epsilon of the top force: cable {cable:.3e}, nonlinear {same:.3e}");
    assert!(cable < 1e-3 && cable > 10.0 * same, "cable {cable:e}");
    assert!(same < 1e-5, "same mesh {same:e}");
}

#[test]
fn a_cable_between_two_nonlinear_sections_couples_at_both_its_ends() {
    let sections = format!(
        "[[structure.sections]]\nname = \"bottom\"\nto = 700.0\n{}",
        CABLE
    );
    let e = top_force_epsilon(&mooring(20.0, Some(&sections)));
    assert!(e < 1e-3, "{e:e}");
}

#[test]
fn a_static_lower_section_is_the_line_s_stiffness_at_the_cut() {
    let text = mooring(20.0, Some(&CABLE.replace("\"cable\"", "\"static\"")));
    let (units, _) = expanded(&text);
    let lower = &units.iter().find(|(n, _)| n == "line_lower").unwrap().1;
    assert_eq!(lower["kind"].as_str(), Some("static_section"));
    let k: Vec<Vec<f64>> = lower["parameters"]["stiffness"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| {
            r.as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_float().unwrap())
                .collect()
        })
        .collect();
    // The tangent of a conservative section: symmetric in the end's
    // translations to the central differences' accuracy (1.3e-4 measured).
    let scale = k[0][0].abs().max(k[1][1].abs());
    assert!((k[0][1] - k[1][0]).abs() < 1e-3 * scale, "{k:?}");
    // A taut line pulls its end back when the end moves out along it.
    assert!(k[0][0] < 0.0 && k[1][1] < 0.0, "{k:?}");
    // Against the twin: 1.4 % on the top force over the first 20 s, 0.7 %
    // over 60 s (the static section has no mass, drag or current response of
    // its own).
    let e = top_force_epsilon(&text);
    println!("epsilon of the top force with a static lower section: {e:.3e}");
    assert!(e < 2e-2, "{e:e}");
    // Refused where it cannot stand: not first, or without the static start.
    let upper_static = "[[structure.sections]]\nname = \"lower\"\nto = 1571.375\n[[structure.sections]]\nname = \"upper\"\nfidelity = \"static\"\n";
    let e = parse(&mooring(20.0, Some(upper_static))).unwrap_err();
    assert!(e.contains("first section"), "{e}");
}

/// The expanded scene's units (by name) and connections.
fn expanded(text: &str) -> (Vec<(String, Value)>, Vec<Value>) {
    units_and_links(&parse(text).expect("scene"))
}

#[test]
fn swapping_a_section_to_cable_changes_its_unit_and_its_cuts_only() {
    let three = |middle: &str| {
        format!(
            "[[structure.sections]]\nname = \"bottom\"\nto = 700.0\n[[structure.sections]]\nname = \"lower\"\nto = 1571.375\nfidelity = \"{middle}\"\n[[structure.sections]]\nname = \"upper\"\n"
        )
    };
    let (a_units, a_links) = expanded(&mooring(20.0, Some(&three("nonlinear"))));
    let (b_units, b_links) = expanded(&mooring(20.0, Some(&three("cable"))));
    assert_eq!(a_units.len(), b_units.len());
    for ((name, a), (_, b)) in a_units.iter().zip(&b_units) {
        if name == "line_lower" {
            assert_eq!(b["kind"].as_str(), Some("cable"));
            continue;
        }
        // The neighbours differ only in the rotation at the shared cut, which
        // turns freely next to a section without bending (a pinned cut).
        let (mut a, mut b) = (a.clone(), b.clone());
        let side = match name.as_str() {
            "line_bottom" => Some("end"),
            "line_upper" => Some("start"),
            _ => None,
        };
        if let Some(side) = side {
            let rotation = |u: &mut Value| {
                u["parameters"]["ends"][side]
                    .as_table_mut()
                    .unwrap()
                    .remove("rotation")
            };
            assert_eq!(
                rotation(&mut b).and_then(|r| r.as_str().map(str::to_owned)),
                Some("free".into())
            );
            rotation(&mut a);
        }
        assert_eq!(a, b, "{name} changed beyond its cut's rotation");
    }
    let away = |links: &[Value]| links_away_from(links, "line_lower");
    assert_eq!(away(&a_links), away(&b_links));
    // Force and velocity cross a pinned cut; rotation and moment do not.
    assert_eq!(a_links.len(), 12);
    assert_eq!(b_links.len(), 8);
}

fn plan(sections: &[&str], design: Design, jobs: usize) -> FidelityPlan {
    FidelityPlan {
        reference: slender_app::fidelity::ReferenceMode::Model,
        max_refinements: 3,
        from: None,
        overrides: Vec::new(),
        max_runs: slender_app::DEFAULT_MAX_RUNS,
        repeats: 1,
        sections: sections
            .iter()
            .map(|s| s.parse::<SectionChoices>().unwrap())
            .collect(),
        design,
        duration: Some(10.0),
        jobs,
        tolerance: 1e-3,
        judged: vec![],
    }
}

#[test]
fn a_fidelity_study_measures_every_combination_against_the_monolithic_line() {
    let path = root().join("examples/structure_mooring.toml");
    let sections = [
        "lower=nonlinear,cable,nonlinear:16",
        "upper=nonlinear,cable",
    ];
    // Judged on the line's end forces; the force at the cut is reported too.
    let mut ends = plan(&sections, Design::OneAtATime, 2);
    ends.judged = vec!["top_force".into(), "start_force".into()];
    let report = run_fidelity(&path, &ends, |_| {}).unwrap();
    let row = |label: &str| {
        report
            .rows
            .iter()
            .find(|r| {
                r.combination
                    .iter()
                    .any(|(s, c)| format!("{s}={c}") == label)
                    && {
                        let first = &r.combination;
                        label.starts_with("upper") || first[1].1 == "nonlinear"
                    }
            })
            .unwrap_or_else(|| panic!("no row {label}"))
    };
    assert!(report.rows[0].reference && report.rows[0].worst_error == 0.0);
    assert_eq!(
        report.quantities,
        ["top_force", "start_force", "cut_lower_upper"]
    );
    let same = row("lower=nonlinear");
    let cable = row("lower=cable");
    let coarse = row("lower=nonlinear:16");
    println!(
        "worst epsilon: same mesh {:.2e}, cable {:.2e}, 16 elements {:.2e}",
        same.worst_error, cable.worst_error, coarse.worst_error
    );
    assert!(same.worst_error < 1e-5, "{}", same.worst_error);
    // The force at the cut: the mean of the two elements' internal forces there,
    // in the reference and, where both sides are nonlinear, in the partition
    // (measured 1.9e-6 at the same mesh, 5.3e-4 with 16 elements below); next
    // to the cable, the upper section's start force, which also carries the
    // cut node's inertia and drag (3.9e-3).
    let cut = |r: &slender_app::fidelity::FidelityRow| r.errors[2].1;
    println!(
        "force at the cut: same mesh {:.2e}, cable {:.2e}, 16 elements {:.2e}",
        cut(same),
        cut(cable),
        cut(coarse)
    );
    assert!(cut(same) < 1e-5);
    assert!(cut(coarse) > cut(same) && cut(coarse) < 1e-3);
    assert!(cut(cable) < 6e-3);
    assert!(cable.worst_error < 1e-3 && cable.worst_error > same.worst_error);
    assert!(coarse.worst_error < 1e-3 && coarse.worst_error > same.worst_error);
    for r in [same, cable, coarse] {
        assert!(r.error.is_none() && r.non_converged_steps == 0);
        assert!(r.iterations_per_step > 1.0 && r.speed_up > 0.0);
        // The start check saw the load at the cut (the fairlead's motion
        // starts at full speed: a few per cent) and let it pass.
        assert!(r.start_change.is_some_and(|c| c > 0.0 && c < 0.2), "{r:?}");
    }
    // The monolithic line solves its statics under no coupled load.
    assert_eq!(report.rows[0].start_change, None);
    // The structure's top cannot be a cable: reported, and the study goes on.
    let failed = row("upper=cable");
    assert!(
        failed
            .error
            .as_deref()
            .is_some_and(|e| e.contains("last section")),
        "{:?}",
        failed.error
    );
    // The cheapest within the tolerance is on the Pareto front.
    let cheapest = &report.rows[report.cheapest.expect("a combination within 1e-3")];
    assert!(cheapest.pareto && cheapest.within_tolerance);
    assert!(report.rows.iter().all(|r| !r.within_tolerance
        || r.cost_per_simulated_second >= cheapest.cost_per_simulated_second));
}

#[test]
fn a_fidelity_grid_gives_the_same_errors_on_one_job_and_on_two() {
    let path = root().join("examples/structure_mooring.toml");
    let sections = ["lower=cable,nonlinear:16"];
    let errors = |jobs| {
        // Two jobs time each run twice: its cost is the median of two, with
        // their spread; the errors are those of one run.
        let mut plan = plan(&sections, Design::Grid, jobs);
        plan.repeats = jobs;
        let report = run_fidelity(&path, &plan, |_| {}).unwrap();
        let spread_given = report.rows.iter().all(|r| r.cost_spread >= 0.0);
        assert_eq!(spread_given, jobs == 2, "cost spreads with {jobs} job(s)");
        report
            .rows
            .iter()
            .map(|r| {
                (
                    r.combination.clone(),
                    r.errors.clone(),
                    r.iterations_per_step,
                )
            })
            .collect::<Vec<_>>()
    };
    assert_eq!(errors(1), errors(2));
}

#[test]
fn a_fidelity_study_refuses_a_section_that_is_not_there() {
    let path = root().join("examples/structure_mooring.toml");
    let e = run_fidelity(&path, &plan(&["middle=cable"], Design::Grid, 1), |_| {})
        .unwrap_err()
        .to_string();
    assert!(e.contains("middle") && e.contains("lower, upper"), "{e}");
    let e = "lower=shell".parse::<SectionChoices>().unwrap_err();
    assert!(e.contains("static"), "{e}");
    assert!(
        e.contains("beam") && e.contains("span") && e.contains("cable"),
        "{e}"
    );
    let e = "lower=nonlinear:0".parse::<SectionChoices>().unwrap_err();
    assert!(e.contains("whole number"), "{e}");
    // A cable section needs the static start and the water depth.
    let text = mooring(10.0, Some(CABLE));
    let e = parse(&text.replace("static_start = true", "")).unwrap_err();
    assert!(e.contains("static_start"), "{e}");
    let e = parse(&text.replace("water_depth = 1200.0", "")).unwrap_err();
    assert!(e.contains("water_depth"), "{e}");
}

/// A quantity whose reference is zero to round-off (the hanging pipe's free
/// bottom end carries 1e-8 N) is judged against its kind's scale, and the
/// report says so: the exact partition is not called 88 % off (issue 27).
#[test]
fn a_quantity_at_round_off_is_judged_against_its_kinds_scale() {
    let mut plan = plan(&["middle=nonlinear"], Design::OneAtATime, 1);
    plan.duration = Some(2.0);
    let path = root().join("examples/structure_hanging_pipe.toml");
    let report = run_fidelity(&path, &plan, |_| {}).unwrap();
    let floors: Vec<&str> = report.floors.iter().map(|f| f.quantity.as_str()).collect();
    assert_eq!(floors, ["top_force"], "{:?}", report.floors);
    let floor = &report.floors[0];
    assert!(floor.reference_rms < 1e-9 * floor.scale && floor.unit == "N");
    let partition = &report.rows[1];
    assert!(partition.error.is_none(), "{:?}", partition.error);
    // The same-mesh partition: at the coupling tolerance on every quantity.
    assert!(partition.worst_error < 1e-6, "{:?}", partition.errors);
    assert!(
        slender_app::fidelity::report::conclusion(&report).contains("top_force (reference RMS"),
        "{}",
        slender_app::fidelity::report::conclusion(&report)
    );
}

/// The layout `slender fidelity` reads (issue 26: names, kinds and outputs
/// written once, in the scene crate) names the units the expansion writes
/// and outputs they have: the S-lay's touchdown section at each fidelity that
/// lies on the seabed (nonlinear, linear, static) beside each suspended one,
/// and the mooring line's lower section as each fidelity, every output the
/// layout names recorded over a few steps. A `linear` section reports its
/// touchdown point as a `nonlinear` one does (the study used to leave it out
/// and judge the touchdown 100 % off).
#[test]
fn the_layout_names_the_units_and_outputs_the_expansion_writes() {
    for (touchdown, suspended) in [
        ("nonlinear", "beam"),
        ("linear", "span"),
        ("static", "nonlinear"),
        ("linear", "reduced"),
    ] {
        let (layout, series) = layout_run("structure_slay_fidelity.toml", &[touchdown, suspended]);
        let lying = &layout.sections[0];
        assert_eq!(lying.choice, touchdown);
        assert_eq!(lying.outputs.stations, touchdown != "static");
        // The touchdown point lies inside the lying section (m of arc).
        let output = lying.outputs.touchdown.as_ref().expect(touchdown);
        let arc = series.last(&format!("{}.{output}", lying.unit));
        println!(
            "{touchdown}/{suspended}: touchdown at {arc:.2} m of {:.2} m",
            lying.to
        );
        assert!(arc > 0.0 && arc < lying.to, "{touchdown}: {arc}");
    }
    for lower in ["cable", "static", "linear", "reduced"] {
        let (layout, _) = layout_run("structure_mooring.toml", &[lower]);
        // Without a seabed no section reports a touchdown point.
        assert!(
            layout
                .sections
                .iter()
                .all(|s| s.outputs.touchdown.is_none())
        );
        assert_eq!(
            layout.sections[0].outputs.end_force.is_none(),
            lower == "cable"
        );
    }
}

/// The example `example`'s layout with its first sections at `choices`, and a
/// run of a few steps recording every output the layout names (each checked
/// finite).
fn layout_run(
    example: &str,
    choices: &[&str],
) -> (slender_scene::structure::Layout, slender_tests::Series) {
    use slender_scene::structure::{layout, write_choice};
    let path = root().join("examples").join(example);
    let mut table: toml::Table = std::fs::read_to_string(&path).unwrap().parse().unwrap();
    table["simulation"]["duration"] = Value::Float(0.25);
    let sections = table["structure"]["sections"].as_array_mut().unwrap();
    for (section, word) in sections.iter_mut().zip(choices) {
        write_choice(section.as_table_mut().unwrap(), word, None, None).unwrap();
    }
    let layout = layout(&table).unwrap().unwrap();
    let mut signals = Vec::new();
    for s in &layout.sections {
        let names = s.outputs.names();
        signals.extend(
            names
                .into_iter()
                .map(|n| Value::String(format!("{}.{n}", s.unit))),
        );
    }
    let mut output = toml::Table::new();
    output.insert("signals".into(), Value::Array(signals.clone()));
    table.insert("output".into(), Value::Table(output));
    let what = format!("{example} {choices:?}");
    let scene = Scene::parse(&path, toml::to_string(&table).unwrap())
        .unwrap_or_else(|e| panic!("{what}: {e}"));
    let series = run(&scene);
    assert!(series.error.is_none(), "{what}: {:?}", series.error);
    for signal in signals.iter().filter_map(Value::as_str) {
        assert!(
            series.get(signal).iter().all(|v| v.is_finite()),
            "{what}: {signal}"
        );
    }
    (layout, series)
}

/// A fidelity study carries each run's warnings into its rows and reports:
/// the riser's sag bend `linear` (it holds the touchdown point and keeps its
/// contact state) is named in its row, in the CSV's last column and under the
/// Markdown table; the `nonlinear` sag bend's row has none.
#[test]
fn a_fidelity_study_reports_the_advisories_of_its_runs() {
    let path = root().join("examples/structure_riser.toml");
    let plan = plan(&["sagbend=nonlinear,linear"], Design::OneAtATime, 1);
    let report = run_fidelity(&path, &plan, |_| {}).unwrap();
    let row = |choice: &str| {
        let found = report.rows.iter().find(|r| {
            !r.reference
                && r.combination
                    .iter()
                    .any(|(s, c)| s == "sagbend" && c == choice)
        });
        found.unwrap_or_else(|| panic!("no row sagbend={choice}"))
    };
    assert!(
        row("nonlinear").warnings.is_empty(),
        "{:?}",
        row("nonlinear").warnings
    );
    let warned = &row("linear").warnings;
    assert_eq!(warned.len(), 1, "{warned:?}");
    assert!(
        warned[0].contains("the touchdown point lies in this section"),
        "{}",
        warned[0]
    );
    let markdown = slender_app::fidelity::report::to_markdown(&report);
    assert!(markdown.contains("Warnings of the runs:"), "{markdown}");
    assert!(
        markdown.contains("(laid=nonlinear sagbend=linear top=nonlinear)"),
        "{markdown}"
    );
    let csv = slender_app::fidelity::report::to_csv(&report);
    let header = csv.lines().next().unwrap();
    assert!(header.ends_with(",error,warnings"), "{header}");
}

/// Every fidelity on every section of every structure example that the
/// scene accepts: each output its layout names (end forces, touchdown point,
/// moments) is an output of the unit the expansion writes, and a section that
/// takes stations is a `nonlinear` unit. So a fidelity's declaration of its
/// outputs (its `SectionModel::outputs`) is checked against its unit, not
/// trusted.
#[test]
fn every_fidelity_s_layout_matches_the_units_it_writes() {
    use slender_scene::structure::{layout, write_choice};
    let mut checked = 0;
    for example in [
        "structure_mooring.toml",
        "structure_slay.toml",
        "structure_slay_fidelity.toml",
        "structure_riser.toml",
        "structure_truncation.toml",
        "structure_hanging_pipe.toml",
        "structure_frame_reduced.toml",
    ] {
        let path = root().join("examples").join(example);
        let base: toml::Table = std::fs::read_to_string(&path).unwrap().parse().unwrap();
        let count = base["structure"]["sections"].as_array().unwrap().len();
        for k in 0..count {
            for word in slender_scene::structure::FIDELITIES {
                let mut table = base.clone();
                let sections = table["structure"]["sections"].as_array_mut().unwrap();
                write_choice(sections[k].as_table_mut().unwrap(), word, None, None).unwrap();
                let Ok(scene) = Scene::parse(&path, toml::to_string(&table).unwrap()) else {
                    continue; // refused with its reason (tested elsewhere)
                };
                let master = scene.build().unwrap();
                let layout = layout(&table).unwrap().unwrap();
                for s in &layout.sections {
                    let u = master.unit_names().position(|n| n == s.unit);
                    let u = u.unwrap_or_else(|| panic!("{example} {word}: no unit {}", s.unit));
                    let d = master.description(u);
                    let has = |o: &str| d.outputs.iter().any(|p| p.name == o);
                    let o = &s.outputs;
                    for name in o.names() {
                        assert!(has(name), "{example} {k}={word}: {} has no {name}", s.unit);
                    }
                    if o.stations {
                        assert_eq!(d.kind, "nonlinear", "{example} {k}={word}: {}", s.unit);
                    }
                    checked += 1;
                }
            }
        }
    }
    println!("{checked} sections checked");
    assert!(checked > 100, "{checked}");
}

#[test]
fn a_fidelity_study_measures_a_3d_line_s_sections_against_its_twin() {
    // The 3D polyester line (issue 46): its lower section as the 3D line,
    // linearised, as its catenary; the upper as a catenary is reported as
    // refused (a static section is the first) and the study goes on. The
    // forces are the magnitudes of their x, y, z; no force at the cut (a 3D
    // line has no stations).
    let path = root().join("examples/structure_mooring_3d.toml");
    let mut study = plan(
        &["lower=nonlinear,linear,static", "upper=static"],
        Design::OneAtATime,
        1,
    );
    study.duration = Some(20.0);
    let report = run_fidelity(&path, &study, |_| {}).unwrap();
    assert_eq!(report.quantities, ["top_force", "start_force"]);
    let row = |label: &str| {
        (report.rows.iter())
            .find(|r| {
                r.combination
                    .iter()
                    .any(|(s, c)| format!("{s}={c}") == label)
            })
            .unwrap_or_else(|| panic!("no row {label}"))
    };
    let (same, linear, catenary) = (
        row("lower=nonlinear"),
        row("lower=linear"),
        row("lower=static"),
    );
    println!(
        "worst epsilon: same mesh {:.2e}, linear {:.2e}, catenary {:.2e}",
        same.worst_error, linear.worst_error, catenary.worst_error
    );
    assert!(same.worst_error < 1e-4, "{}", same.worst_error);
    // Measured over 20 s: 5.1e-6, 2.2e-5 and 4.2e-3.
    assert!(linear.worst_error < 1e-4 && linear.worst_error > same.worst_error);
    assert!(catenary.worst_error < 1e-2 && catenary.worst_error > linear.worst_error);
    for r in [same, linear, catenary] {
        assert!(r.error.is_none() && r.non_converged_steps == 0, "{r:?}");
    }
    let refused = row("upper=static");
    assert!(
        (refused.error.as_deref()).is_some_and(|e| e.contains("the first of several sections")),
        "{:?}",
        refused.error
    );
}
