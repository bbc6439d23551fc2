//! Scene files: every example loads; bad input gives an error naming the file, the
//! place and what was expected; a run that fails leaves readable partial results.

use slender_app::run::{RunOptions, run_scene};
use slender_scene::{Scene, kinds::KINDS};
use slender_tests::{load, root};
use std::path::Path;

const B1: &str = r#"
[simulation]
duration = 1.0
step = 0.01

[master]
scheme = "iterative_gauss_seidel"

[[units]]
name = "left"
kind = "oscillator"
parameters = { mass = 1.0, stiffness = 39.5, coupling_stiffness = 158.0, initial_displacement = 1.0 }

[[units]]
name = "right"
kind = "oscillator"
parameters = { mass = 1.0, stiffness = 39.5, coupling_stiffness = 158.0 }

[[connections]]
from = "left.displacement"
to = "right.coupling_displacement"

[[connections]]
from = "right.displacement"
to = "left.coupling_displacement"
"#;

fn error_of(text: &str) -> String {
    match Scene::parse(Path::new("bad.toml"), text.to_owned()) {
        Ok(_) => panic!("scene accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

/// The B1 scene with `from` replaced by `to`.
fn b1_with(from: &str, to: &str) -> String {
    assert!(B1.contains(from), "{from}");
    B1.replacen(from, to, 1)
}

fn expect(text: &str, parts: &[&str]) {
    let e = error_of(text);
    for p in parts {
        assert!(e.contains(p), "error `{e}` lacks `{p}`");
    }
    assert!(e.starts_with("bad.toml"), "{e}");
}

#[test]
fn every_example_scene_loads() {
    let mut count = 0;
    for entry in std::fs::read_dir(root().join("examples")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            Scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
            count += 1;
        }
    }
    assert!(count >= 4);
    Scene::parse(Path::new("b1.toml"), B1.into()).unwrap();
}

#[test]
fn malformed_toml_names_the_line() {
    expect(&b1_with("step = 0.01", "step = 0.01 0.02"), &["bad.toml:4"]);
}

#[test]
fn unknown_keys_are_rejected_everywhere() {
    expect(
        &b1_with("duration = 1.0", "duration = 1.0\nend = 3.0"),
        &["unknown field `end`"],
    );
    expect(
        &b1_with("scheme =", "schema = \"jacobi\"\nscheme ="),
        &["unknown field `schema`"],
    );
    expect(
        &b1_with(
            "mass = 1.0, stiffness = 39.5, coupling_stiffness = 158.0 }",
            "masss = 1.0 }",
        ),
        &[
            "units[1] (\"right\").parameters",
            "unknown field `masss`",
            "bad.toml:17",
        ],
    );
    expect(
        &b1_with(
            "to = \"right.coupling_displacement\"",
            "to = \"right.coupling_displacement\"\ngian = 2",
        ),
        &["unknown field `gian`"],
    );
}

#[test]
fn unknown_names_get_a_did_you_mean() {
    expect(
        &b1_with("kind = \"oscillator\"", "kind = \"oscilator\""),
        &[
            "units[0].kind",
            "unknown unit kind `oscilator`; did you mean `oscillator`?",
        ],
    );
    expect(
        &b1_with("right.coupling_displacement", "right.coupling_displacment"),
        &["connections[0]", "did you mean `coupling_displacement`?"],
    );
    expect(
        &b1_with(
            "from = \"left.displacement\"",
            "from = \"lefft.displacement\"",
        ),
        &["no unit named `lefft`; did you mean `left`?"],
    );
    expect(
        &b1_with(
            "from = \"left.displacement\"",
            "from = \"left.coupling_velocity\"",
        ),
        &["is not an output of unit `left` (it is the other way round)"],
    );
}

#[test]
fn incompatible_or_duplicate_connections_are_rejected() {
    expect(
        &b1_with(
            "to = \"right.coupling_displacement\"",
            "to = \"right.coupling_velocity\"",
        ),
        &["cannot connect a displacement output (m) to a velocity input (m/s)"],
    );
    expect(
        &b1_with(
            "from = \"left.displacement\"",
            "from = \"left.coupling_force\"",
        ),
        &["cannot connect a force output (N) to a displacement input (m)"],
    );
    expect(
        &b1_with(
            "to = \"left.coupling_displacement\"",
            "to = \"right.coupling_displacement\"",
        ),
        &["already driven by `left.displacement -> right.coupling_displacement`"],
    );
    expect(
        &b1_with("name = \"right\"", "name = \"left\""),
        &["units[1].name", "used twice"],
    );
}

#[test]
fn impossible_values_are_rejected() {
    expect(
        &b1_with("step = 0.01", "step = 0.0"),
        &["simulation.step", "expected a finite value > 0"],
    );
    expect(
        &b1_with("step = 0.01", "step = -0.01"),
        &["simulation.step"],
    );
    expect(
        &b1_with("step = 0.01", "step = 0.03"),
        &["simulation.duration", "not a whole number of steps"],
    );
    expect(
        &b1_with(
            "mass = 1.0, stiffness = 39.5, coupling_stiffness = 158.0, initial",
            "mass = nan, stiffness = 39.5, coupling_stiffness = 158.0, initial",
        ),
        &["parameter `mass` = NaN: expected a finite value > 0"],
    );
    expect(
        &b1_with(
            "stiffness = 39.5, coupling_stiffness = 158.0 }",
            "stiffness = -39.5, coupling_stiffness = 158.0 }",
        ),
        &["`stiffness` = -39.5"],
    );
    expect(
        &b1_with(
            "scheme = \"iterative_gauss_seidel\"",
            "scheme = \"iterative_gauss_seidel\"\ntolerances = { displacement = 0.0 }",
        ),
        &["tolerances.displacement: 0 is not a finite value > 0"],
    );
    expect(
        &b1_with(
            "scheme = \"iterative_gauss_seidel\"",
            "scheme = \"iterative_gauss_seidel\"\nmax_iterations = 0",
        ),
        &["max_iterations: expected at least 1"],
    );
    expect(
        &b1_with(
            "scheme = \"iterative_gauss_seidel\"",
            "scheme = \"jacobi\"\nacceleration = { kind = \"aitken\" }",
        ),
        &["acceleration `aitken` needs an iterative scheme"],
    );
    expect(
        &b1_with(
            "scheme = \"iterative_gauss_seidel\"",
            "scheme = \"iterative_gauss_seidel\"\nacceleration = { kind = \"constant\", factor = 3.0 }",
        ),
        &["expected a value in (0, 2]"],
    );
    expect(
        &b1_with(
            "kind = \"oscillator\"",
            "kind = \"oscillator\"\neffects = [\"drag\"]",
        ),
        &["effect `drag`: kind `oscillator` has no switchable effects"],
    );
    expect(
        &b1_with(
            "kind = \"oscillator\"",
            "kind = \"oscillator\"\ninputs = { force = 1.0 }",
        ),
        &["units[0].inputs.force", "has no input `force`"],
    );
    expect(
        &B1.replace("[master]\nscheme = \"iterative_gauss_seidel\"\n", ""),
        &["missing field `master`"],
    );
}

#[test]
fn a_failing_run_leaves_readable_partial_results() {
    // Explicit Jacobi on B3's stiff interface at 1 ms is unstable: the motion
    // overflows to infinity within 60 s.
    let mut scene = load("examples/b3_force_displacement.toml");
    scene.spec.master.scheme = slender_coupling::Scheme::Jacobi;
    scene.spec.master.acceleration = slender_coupling::Acceleration::None;
    scene.spec.simulation.duration = 60.0;
    scene.set_step(0.001).unwrap();
    let dir = std::env::temp_dir().join(format!("slender-partial-{}", std::process::id()));
    let result = run_scene(
        &scene,
        &RunOptions {
            output_dir: Some(dir.clone()),
            progress: false,
            realtime: false,
        },
    )
    .unwrap();
    let error = result.summary.error.clone().expect("the run must fail");
    assert!(
        error.contains("produced inf") || error.contains("produced NaN"),
        "{error}"
    );
    let summary = std::fs::read_to_string(dir.join("summary.json")).unwrap();
    assert!(summary.contains("\"status\": \"failed\""), "{summary}");
    let csv = std::fs::read_to_string(dir.join("timeseries.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().collect();
    assert_eq!(
        rows[0],
        "time [s],a.displacement [m],b.displacement [m],a.coupling_force [N],exact_a.value [m],exact_b.value [m]"
    );
    assert!(rows.len() > 100);
    for row in &rows[1..] {
        let fields: Vec<f64> = row.split(',').map(|f| f.parse().unwrap()).collect();
        assert_eq!(fields.len(), 6);
    }
    let last_time: f64 = rows
        .last()
        .unwrap()
        .split(',')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(last_time < 60.0 && (result.summary.simulated_s - last_time).abs() < 1e-9);
    std::fs::remove_dir_all(dir).unwrap();
}

/// The section of the scene reference from `heading` to the next heading of the
/// same or a higher level.
fn section<'a>(doc: &'a str, heading: &str) -> &'a str {
    let start = doc
        .find(heading)
        .unwrap_or_else(|| panic!("no section `{heading}` in the scene reference"));
    let level = heading.chars().take_while(|c| *c == '#').count();
    let rest = &doc[start + heading.len()..];
    let end = rest
        .match_indices("\n#")
        .find(|(i, _)| {
            let hashes = rest[i + 1..].chars().take_while(|c| *c == '#').count();
            hashes <= level
        })
        .map_or(rest.len(), |(i, _)| i);
    &rest[..end]
}

/// Every parameter of every kind, read from its parameter struct, is documented
/// in that kind's section (so a parameter cannot go undocumented), and every
/// master setting in the master's.
#[test]
fn the_scene_reference_documents_every_kind_parameter_and_master_setting() {
    let doc = std::fs::read_to_string(root().join("docs/scene-reference.md")).unwrap();
    let mut checked = 0;
    for k in KINDS {
        let text = section(&doc, &format!("### Kind `{}`", k.name));
        let parameters = (k.parameters)();
        assert!(
            !parameters.is_empty() || k.name == "loop_linear_pair",
            "kind {} lists no parameters",
            k.name
        );
        for p in parameters {
            assert!(
                text.contains(&format!("`{p}`")),
                "parameter `{p}` of kind `{}` is not documented in its section",
                k.name
            );
            checked += 1;
        }
        for e in k.effects {
            assert!(
                text.contains(&format!("`{e}`")),
                "effect `{e}` of `{}`",
                k.name
            );
        }
    }
    println!("{checked} kind parameters documented");
    let master = section(&doc, "## `[master]`");
    let master_keys = slender_scene::fields::field_names::<slender_coupling::MasterSettings>();
    assert!(master_keys.len() >= 6, "{master_keys:?}");
    for key in master_keys {
        assert!(
            master.contains(&format!("`{key}`")),
            "master setting `{key}` is not documented"
        );
    }
    let output = section(&doc, "## `[output]`");
    let output_keys = slender_scene::fields::field_names::<slender_scene::spec::OutputSpec>();
    assert!(output_keys.len() >= 4, "{output_keys:?}");
    for key in output_keys {
        assert!(
            output.contains(&format!("`{key}`")),
            "output key `{key}` is not documented"
        );
    }
}

/// Issue 28: one rule for angles, radians unless the key ends in `_deg`. The
/// keys that took degrees before the rule (a segment's `angle`, the hang-off's
/// `angle`, the characteristic load's angles) are refused by their old names,
/// the error listing the new one, never read as radians or dropped.
#[test]
fn angle_keys_in_degrees_say_so_and_the_old_names_are_refused() {
    let example = |name: &str| std::fs::read_to_string(root().join("examples").join(name)).unwrap();
    for (scene, new, old, key) in [
        (
            "polyester_line.toml",
            "angle_deg = 39.4",
            "angle = 39.4",
            "angle",
        ),
        (
            "structure_mooring.toml",
            "angle_deg = 39.4",
            "angle = 39.4",
            "angle",
        ),
        (
            "structure_riser.toml",
            "{ angle_deg = 12",
            "{ angle = 12",
            "angle",
        ),
        (
            "truncation_fig10.toml",
            "static_angle_from_vertical_deg",
            "static_angle_from_vertical",
            "static_angle_from_vertical",
        ),
    ] {
        let text = example(scene);
        assert!(text.contains(new), "{scene}: {new}");
        let e = error_of(&text.replacen(new, old, 1));
        assert!(e.contains(&format!("{key}`")), "{scene}: {e}");
        assert!(e.contains(&format!("`{key}_deg`")), "{scene}: {e}");
        assert!(e.contains("unknown"), "{scene}: {e}");
    }
}

/// Issue 27: an error inside an inline table of an array (a line that starts
/// with `{`, not with its key) names the key path, not the line's first word.
#[test]
fn an_error_in_an_inline_table_names_its_key_path() {
    let text = std::fs::read_to_string(root().join("examples/truncation_uq.toml")).unwrap();
    let drop_sd = "mean = 1.0, sd = 0.015 } },";
    assert!(text.contains(drop_sd));
    let e = error_of(&text.replacen(drop_sd, "mean = 1.0 } },", 1));
    assert!(
        e.contains("`uncertainty.inputs[0].distribution`: missing field `sd`"),
        "{e}"
    );
    let e = error_of(&text.replacen("kind = \"normal\"", "kind = \"norml\"", 1));
    assert!(
        e.contains("`uncertainty.inputs[0].distribution.kind`"),
        "{e}"
    );
    assert!(!e.contains("`{"), "{e}");
}

/// An indicator measured from `from` on a run that ends before it (a run
/// shortened by `--duration`) is left out with a warning naming it, not
/// reported as NaN; within the run it is measured.
#[test]
fn an_indicator_whose_window_lies_past_the_run_is_left_out_with_a_warning() {
    let scene = |from: f64| {
        let text = format!(
            "{B1}\n[output]\n[[output.indicators]]\nname = \"gap\"\nsignals = [\"left.displacement\"]\nreference = [\"right.displacement\"]\nfrom = {from:?}\n"
        );
        Scene::parse(Path::new("b1.toml"), text).unwrap_or_else(|e| panic!("{e}"))
    };
    let within = slender_tests::run(&scene(0.5));
    assert_eq!(within.indicators.len(), 1);
    assert!(within.indicators[0].relative_error.is_finite());
    let past = slender_tests::run(&scene(5.0));
    assert!(past.error.is_none(), "{:?}", past.error);
    assert!(past.indicators.is_empty(), "{:?}", past.indicators);
    assert!(
        past.warnings
            .iter()
            .any(|w| w.contains("output.indicators `gap`") && w.contains("not measured")),
        "{:?}",
        past.warnings
    );
}
