//! The steel catenary riser of issue 26 (`examples/structure_riser.toml`): its
//! static start from the defaults at any mesh, its top placed by the hang-off
//! angle, a start time other than zero, a structure's keys checked, and the
//! warning where the touchdown point leaves its section for a `static` one.

use slender_scene::Scene;
use slender_tests::{root, run, units_and_links};
use slender_units::nonlinear::{NonlinearParams, NonlinearSection};
use slender_units::{Driver, Time};

/// The example's text with `elements` elements, run for `duration` s.
fn riser(elements: usize, duration: f64) -> String {
    let text = std::fs::read_to_string(root().join("examples/structure_riser.toml")).unwrap();
    assert!(text.contains("elements = 200,") && text.contains("duration = 200.0"));
    text.replace("elements = 200,", &format!("elements = {elements},"))
        .replace("duration = 200.0", &format!("duration = {duration:?}"))
}

fn parse(text: &str) -> Result<Scene, String> {
    Scene::parse(
        &root().join("examples/structure_riser.toml"),
        text.to_owned(),
    )
    .map_err(|e| e.to_string())
}

/// The twin's parameters after expansion, solved for its statics.
fn twin_at_rest(scene: &Scene) -> (Driver<NonlinearSection>, NonlinearParams) {
    let (units, _) = units_and_links(scene);
    let (_, twin) = units
        .iter()
        .find(|(name, _)| name == "riser_reference")
        .expect("the twin");
    let params: NonlinearParams = twin["parameters"].clone().try_into().unwrap();
    let mut driver = Driver::new(NonlinearSection::new(params.clone()).unwrap());
    driver.initialize(Time::ZERO).unwrap();
    (driver, params)
}

#[test]
fn the_riser_starts_from_the_defaults_at_any_mesh_with_its_hang_off_angle() {
    // The inextensible catenary on a rigid seabed (EI and stretch left out):
    // the top 1356.43 m from the anchor, the touchdown 765.10 m of arc from it.
    for elements in [100, 400, 2000] {
        let scene = parse(&riser(elements, 0.1)).unwrap_or_else(|e| panic!("{elements}: {e}"));
        let (driver, params) = twin_at_rest(&scene);
        let section = driver.unit();
        let last = section.model().reference.len() - 1;
        let angle = section.tangent_angle_at_node(last);
        let from_vertical = angle.cos().abs().atan2(angle.sin().abs()).to_degrees();
        assert!(
            (from_vertical - 12.0).abs() < 1e-5,
            "{elements}: {from_vertical} deg"
        );
        let top = section.position_at(2000.0);
        assert!(top[1].abs() < 1e-9, "{elements}: the top at {top:?}");
        assert!(
            (top[0] - 1356.43).abs() < 0.01 * 1356.43,
            "{elements}: {top:?}"
        );
        let touchdown = section.seabed_crossing().expect("on the seabed");
        assert!(
            (touchdown - 765.10).abs() < 0.03 * 765.10,
            "{elements}: touchdown at {touchdown} m"
        );
        eprintln!(
            "{elements} elements: top x {:.3} m, touchdown {touchdown:.2} m of arc, {} Newton iterations",
            top[0],
            section.last_newton_iterations()
        );
        assert_eq!(params.segments[0].elements, elements);
    }
}

#[test]
fn a_riser_started_at_10_s_equals_one_started_at_0_shifted_in_time() {
    // Without the fade (which counts from t = 0), the vessel's motion at t in
    // the later run is the earlier one's at t - 10 s.
    let base = riser(100, 3.0).replace(", fade_in = 20.0", "");
    let heave = "amplitude = 2.0, angular_frequency = 0.6283185307179586";
    let surge = "amplitude = 5.0, angular_frequency = 0.06283185307179587";
    assert!(base.contains(heave) && base.contains(surge));
    let shifted = base
        .replace("duration = 3.0", "start = 10.0\nduration = 3.0")
        .replace(
            heave,
            &format!("{heave}, phase = {}", -0.6283185307179586 * 10.0),
        )
        .replace(
            surge,
            &format!("{surge}, phase = {}", -0.06283185307179587 * 10.0),
        );
    let (a, b) = (run(&parse(&base).unwrap()), run(&parse(&shifted).unwrap()));
    assert!(
        a.error.is_none() && b.error.is_none(),
        "{:?} {:?}",
        a.error,
        b.error
    );
    assert_eq!(a.time.len(), b.time.len());
    assert!(
        (b.time[0] - a.time[0] - 10.0).abs() < 1e-12,
        "{} {}",
        a.time[0],
        b.time[0]
    );
    for name in [
        "riser_top.end_force_z",
        "riser_reference.end_force_z",
        "riser_sagbend.sagbend_moment",
    ] {
        let (x, y) = (a.get(name), b.get(name));
        let peak = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let worst = x
            .iter()
            .zip(y)
            .fold(0.0f64, |m, (p, q)| m.max((p - q).abs()));
        // The coupling's own tolerance: 1 N on the forces.
        assert!(worst < 1e-6 * peak + 1.0, "{name}: {worst} of {peak}");
    }
}

/// The line of the first line of `text` that starts with `start` (1-based).
fn line_of(text: &str, start: &str) -> usize {
    text.lines()
        .position(|l| l.starts_with(start))
        .expect(start)
        + 1
}

#[test]
fn errors_in_a_structure_name_the_users_line() {
    // An unknown key: its own line.
    let text = riser(100, 0.1).replace("reference = true", "reference = true\nhangoff = 12.0");
    let e = parse(&text).unwrap_err();
    let line = line_of(&text, "hangoff");
    assert!(
        e.contains(&format!(
            "structure_riser.toml:{line}: structure: `structure.hangoff`"
        )),
        "{e}"
    );
    // A bad fidelity: the section's table.
    let text = riser(100, 0.1).replace(
        "name = \"laid\"\n",
        "name = \"laid\"\nfidelity = \"cabel\"\n",
    );
    let e = parse(&text).unwrap_err();
    let line = line_of(&text, "fidelity = \"cabel\"");
    assert!(e.contains(&format!("structure_riser.toml:{line}:")), "{e}");
    // A model parameter found bad only in the units the structure writes
    // out: the model's line, not a line of the expanded text.
    let text = riser(100, 0.1)
        .replace("static_start = true\n", "")
        .replace("hang_off = { angle_deg = 12.0 }\n", "")
        .replace(
            "integrator = {",
            "rayleigh_stiffness = -1.0\nintegrator = {",
        );
    let e = parse(&text).unwrap_err();
    let line = line_of(&text, "rayleigh_stiffness");
    assert!(
        e.contains(&format!("structure_riser.toml:{line}:")) && e.contains("rayleigh_stiffness"),
        "{e}"
    );
    // Keys outside the structure, in a scene that has one: their own lines
    // (the scene is read once, from the file's text; the structure's units
    // are appended typed, not written out as text and read again).
    for (from, to, key) in [
        ("step = 0.05", "step = \"x\"", "step"),
        ("scheme = \"iterative_jacobi\"", "scheme = 3", "scheme"),
        (
            "max_iterations = 50",
            "max_iterations = 1.5",
            "max_iterations",
        ),
    ] {
        let text = riser(100, 0.1).replacen(from, to, 1);
        assert!(text.contains(to), "{to}");
        let e = parse(&text).unwrap_err();
        let line = line_of(&text, to);
        assert!(
            e.contains(&format!("structure_riser.toml:{line}: `{key}`")),
            "{to}: {e}"
        );
    }
    // A unit of the user's own beside a structure: the lines of its keys.
    let path = root().join("examples/structure_truncation.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    for (from, to) in [
        ("static_tension = 2.5e6", "static_tension = -2.5e6"),
        (
            "kind = \"characteristic_load\"",
            "kind = \"characteristic_lod\"",
        ),
    ] {
        let text = text.replacen(from, to, 1);
        let e = Scene::parse(&path, text.clone()).unwrap_err().to_string();
        let line = (text.lines().position(|l| l.contains(to))).expect(to) + 1;
        assert!(
            e.contains(&format!("structure_truncation.toml:{line}: units[0]")),
            "{to}: {e}"
        );
    }
}

#[test]
fn a_structure_refuses_unknown_keys_and_an_unreachable_hang_off() {
    let text = riser(100, 0.1);
    let e =
        parse(&text.replace("reference = true", "reference = true\nhangoff = 12.0")).unwrap_err();
    assert!(
        e.contains("`structure.hangoff`: unknown field") && e.contains("hang_off"),
        "{e}"
    );
    let e = parse(&text.replace("angle_deg = 12.0 }", "angle_deg = 95.0 }")).unwrap_err();
    assert!(e.contains("between 0 and 90"), "{e}");
    let e = parse(&text.replace("static_start = true\n", "")).unwrap_err();
    assert!(e.contains("static_start = true"), "{e}");
    // Models without seabed contact on a section that lies on it are refused
    // at expansion (so at `slender check`), with where it lies.
    let with = |section: &str, fidelity: &str| {
        text.replace(
            &format!("name = \"{section}\"\n"),
            &format!("name = \"{section}\"\nfidelity = \"{fidelity}\"\n"),
        )
        .replace(
            "hang_off = { angle_deg = 12.0 }",
            "hang_off = { angle_deg = 12.0 }\nwater_depth = 1000.0\nseabed = -1000.0",
        )
    };
    for (section, fidelity) in [("laid", "cable"), ("sagbend", "beam"), ("sagbend", "span")] {
        let e = parse(&with(section, fidelity)).unwrap_err();
        assert!(
            e.contains(&format!("`structure.sections.{section}.fidelity` = \"{fidelity}\": the section lies on the seabed from")),
            "{e}"
        );
    }
    // 2000 m of pipe cannot hang at 89 deg from 1000 m: the line would have to
    // lie flat at the top.
    let e = parse(&text.replace("angle_deg = 12.0 }", "angle_deg = 89.0 }")).unwrap_err();
    assert!(e.contains("`structure.hang_off"), "{e}");
}

#[test]
fn a_touchdown_point_that_leaves_its_section_for_a_static_one_is_a_warning() {
    // The point moves over 730-780 m of arc under the example's heave and
    // surge: a laid `static` section cut at 745 m takes it from the sag bend
    // (at 10.7 s), one cut at 700 m (the example's) never does, and a laid
    // `nonlinear` section at 745 m follows it, so neither of those warns.
    let warnings = |cut: &str, laid: &str| {
        let text = riser(200, 20.0).replace("to = 700.0", cut).replace(
            "name = \"laid\"",
            &format!("name = \"laid\"\nfidelity = \"{laid}\""),
        );
        let s = run(&parse(&text).unwrap());
        assert!(s.error.is_none(), "{:?}", s.error);
        s.warnings
    };
    let left = warnings("to = 745.0", "static");
    assert!(
        left.iter().any(|w| w.starts_with(
            "the touchdown point left `riser_sagbend`: from t = 10.7 s none of it lies on the seabed"
        ) && w.contains("the section below it, `riser_laid`, is `static`")),
        "{left:?}"
    );
    assert_eq!(warnings("to = 700.0", "static"), Vec::<String>::new());
    // The sag bend ending at 760 m under a `linear:30` top (the example's
    // study's choice): the point reaches the top, which keeps its start's
    // contact state (none).
    let text = riser(200, 20.0)
        .replace("to = 950.0", "to = 760.0")
        .replace("name = \"top\"", "name = \"top\"\nfidelity = \"linear:30\"");
    let s = run(&parse(&text).unwrap());
    assert!(
        s.warnings.iter().any(|w| w
            .starts_with("the touchdown point reached `riser_top`: from t = ")
            && w.contains("it is `linear:30`")),
        "{:?}",
        s.warnings
    );
    assert_eq!(warnings("to = 745.0", "nonlinear"), Vec::<String>::new());
}
