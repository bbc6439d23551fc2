//! A `[structure]` whose model is a 3D line (`kind = "line3d"`): written out
//! as `line3d` sections between the whole line's static points and coupled
//! at their cuts by velocity and force, against the twin; what a 3D section
//! cannot be yet is refused by name.

use slender_tests::edited::run_edited;
use slender_tests::{Series, load, units_and_links};

const SCENE: &str = "examples/structure_mooring_3d.toml";

/// The largest difference (N) between the sections' and the twin's fairlead
/// force components over the run.
fn top_force_difference(s: &Series) -> f64 {
    ["x", "y", "z"]
        .iter()
        .flat_map(|c| {
            let a = s.get(&format!("line_upper.end_force_{c}"));
            let b = s.get(&format!("line_reference.end_force_{c}"));
            a.iter()
                .zip(b)
                .map(|(x, y)| (x - y).abs())
                .collect::<Vec<_>>()
        })
        .fold(0.0, f64::max)
}

#[test]
fn a_3d_structure_is_written_as_line3d_sections_meeting_at_their_cuts() {
    let scene = load(SCENE);
    let (units, links) = units_and_links(&scene);
    let names: Vec<&str> = units.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["line_lower", "line_upper", "line_reference"]);
    let parameters = |k: usize| units[k].1["parameters"].as_table().unwrap().clone();
    let (lower, upper) = (parameters(0), parameters(1));
    assert_eq!(lower["end"]["position"], upper["start"]["position"]);
    assert_eq!(lower["end"]["condition"].as_str(), Some("velocity"));
    assert_eq!(upper["start"]["condition"].as_str(), Some("force"));
    // Elements shared by arc length: 1200 of 1934 m of 80 elements.
    assert_eq!(lower["elements"].as_integer(), Some(50));
    assert_eq!(upper["elements"].as_integer(), Some(30));
    assert_eq!(links.len(), 6);
    // The cut lies on the line between the anchor (z -1200.11) and the top.
    let z = lower["end"]["position"][2].as_float().unwrap();
    assert!(z > -1200.11 && z < 0.0, "{z}");
}

#[test]
fn the_3d_sections_follow_their_twin() {
    // Cut at a node of the twin (50 of its 80 elements of 24.175 m), the
    // trapezoidal rule (alpha 0): the sections are the twin to the coupling
    // tolerance (1e-3 N here, on a tension of 2.5 MN).
    let exact = run_edited(
        SCENE,
        &[
            ("kind = \"line3d\"", "kind = \"line3d\"\nalpha = 0.0"),
            ("force = 1.0", "force = 1e-3"),
            ("to = 1200.0", "to = 1208.75"),
        ],
    )
    .unwrap();
    let difference = top_force_difference(&exact);
    eprintln!("alpha 0, cut at a node: {difference:.3e} N");
    assert!(difference < 1e-2, "{difference:e} N");
    // The example as shipped (alpha 0.3, the cut between nodes, so each
    // section's mesh is its own): the cut node's inertia enters the loaded
    // side alpha-weighted, 1e-4 of the tension at most.
    let shipped = run_edited(SCENE, &[]).unwrap();
    let difference = top_force_difference(&shipped);
    eprintln!("as shipped: {difference:.3e} N");
    assert!(difference < 1e-4 * 2.5e6, "{difference:e} N");
    // A coarser lower section: a discretisation difference, still small.
    let coarse = run_edited(SCENE, &[("to = 1200.0", "to = 1200.0\nelements = 16")]).unwrap();
    let difference = top_force_difference(&coarse);
    eprintln!("lower at 16 elements: {difference:.3e} N");
    assert!(difference < 1e-2 * 2.5e6, "{difference:e} N");
}

#[test]
fn what_a_3d_section_cannot_be_yet_is_refused_by_name() {
    let refused = |from: &str, to: &str, expected: &str| {
        let error = run_edited(SCENE, &[(from, to)]).err().expect(to);
        assert!(error.contains(expected), "{to}: {error}");
    };
    refused(
        "to = 1200.0",
        "to = 1200.0\nfidelity = \"cable\"",
        "the other fidelities are planar so far",
    );
    refused(
        "name = \"upper\"",
        "name = \"upper\"\nfidelity = \"static\"",
        "the first of several sections",
    );
    refused(
        "to = 1200.0",
        "to = 1200.0\nsubsteps = 2",
        "`substeps` is not offered",
    );
    refused(
        "start = { position = [0.0, 0.0, -1200.11] }",
        "start = { position = [0.0, 0.0, -1200.11], condition = \"force\" }",
        "a loaded end needs its force at the start",
    );
    refused("to = 1200.0", "to = 2000.0", "structure.sections[0].to");
    refused(
        "bending_stiffness = 100.0",
        "bending_stiffnes = 100.0",
        "bending_stiffnes",
    );
}

#[test]
fn a_3d_lower_section_linearised_or_as_its_catenary_follows_the_twin() {
    // The polyester line's lower 1200 m hang clear of any seabed: linear
    // about its statics (the fairlead moves 3 m; 8e-5 of the 2.5 MN tension
    // measured) or quasi-static (its inertia and drag left out; 3.8e-3).
    for (fidelity, tolerance) in [("linear", 5e-4), ("static", 6e-3)] {
        let edit = format!("to = 1200.0\nfidelity = \"{fidelity}\"");
        let run = run_edited(SCENE, &[("to = 1200.0", edit.as_str())]).unwrap();
        let difference = top_force_difference(&run);
        eprintln!("lower {fidelity}: {difference:.3e} N");
        assert!(
            difference < tolerance * 2.5e6,
            "{fidelity}: {difference:e} N"
        );
        assert!(
            run.get("line_upper.end_tension")
                .iter()
                .all(|t| t.is_finite())
        );
    }
}

/// The example's fairlead moved by a coupled velocity from a `signal` unit
/// (a vessel's or a body's fairlead) instead of its own sines.
const VESSEL: &str = r#"[[units]]
name = "vessel"
kind = "signal"
[units.parameters]
quantity = "velocity"
sines = [{ amplitude = 1.8, angular_frequency = 0.6, phase = 1.5707963267948966 }]
fade_in = { shape = "smoothstep", time = 20.0 }

[[connections]]
from = "vessel.value"
to = "line_upper.end_velocity_x"

[[connections]]
from = "vessel.value"
to = "line_reference.end_velocity_x"

[[structure.sections]]
name = "lower""#;

#[test]
fn a_3d_structure_s_fairlead_follows_a_coupled_velocity() {
    let moved = "end = { position = [1529.11, 0.0, 0.0], condition = \"motion\", motion = [[{ amplitude = 3.0, angular_frequency = 0.6 }], [{ amplitude = 2.0, angular_frequency = 0.3 }], []], fade_in = 20.0 }";
    let coupled = "end = { position = [1529.11, 0.0, 0.0], condition = \"velocity\" }";
    let series = run_edited(
        SCENE,
        &[
            (moved, coupled),
            ("[[structure.sections]]\nname = \"lower\"", VESSEL),
        ],
    )
    .unwrap();
    // The fairlead surges: the top force swings by hundreds of kN, and the
    // sections follow the twin as with the fairlead's own sines.
    let force = series.get("line_upper.end_force_x");
    let swing = force.iter().cloned().fold(f64::MIN, f64::max)
        - force.iter().cloned().fold(f64::MAX, f64::min);
    assert!(swing > 1e5, "{swing} N");
    let difference = top_force_difference(&series);
    assert!(difference < 1e-4 * 2.5e6, "{difference:e} N");
}

#[test]
fn one_sweep_per_step_closed_by_the_sections_correction_follows_the_iterated_run() {
    // `newton.one_sweep`: a step whose first sweep misses the tolerance is
    // closed by the Newton update with each section moved to it by its own
    // step derivatives (`Unit::correct_step`), not by a second sweep; what
    // the correction leaves (second order in the update) is checked against
    // the tolerance, and the step iterated as before where it is not met
    // (a unit that cannot correct: `one_sweep.rs`).
    const NEWTON: &str = "newton = { derivatives = \"units\" }";
    const ONE_SWEEP: &str = "newton = { derivatives = \"units\", one_sweep = true }";
    // The example ships with one sweep.
    let iterated = run_edited(SCENE, &[(ONE_SWEEP, NEWTON)]).unwrap();
    let corrected = run_edited(SCENE, &[]).unwrap();
    let c = &corrected.counters;
    let sweeps = c.iterations as f64 / c.steps as f64;
    eprintln!(
        "{} of {} steps corrected, {sweeps:.3} sweeps per step (iterated: {:.3})",
        c.corrected_steps,
        c.steps,
        iterated.counters.iterations as f64 / iterated.counters.steps as f64
    );
    assert!(c.corrected_steps as f64 >= 0.8 * c.steps as f64);
    assert!(sweeps <= 1.2, "{sweeps}");
    assert!(c.max_residual <= 1.0, "every step within the tolerance");
    // The two runs agree within one coupling tolerance (1 N on 2.5 MN;
    // 1.3e-2 N measured).
    let mut worst = 0.0f64;
    for axis in ["x", "y", "z"] {
        let name = format!("line_upper.end_force_{axis}");
        for (a, b) in corrected.get(&name).iter().zip(iterated.get(&name)) {
            worst = worst.max((a - b).abs());
        }
    }
    eprintln!("fairlead force, corrected against iterated: {worst:.3e} N");
    assert!(worst < 1.0, "{worst} N");
}

#[test]
fn one_sweep_is_refused_without_the_units_derivatives_of_each_step() {
    for newton in [
        "newton = { derivatives = \"sweeps\", one_sweep = true }",
        "newton = { derivatives = \"units\", jacobian = \"reuse\", one_sweep = true }",
    ] {
        let shipped = "newton = { derivatives = \"units\", one_sweep = true }";
        let Err(error) = run_edited(SCENE, &[(shipped, newton)]) else {
            panic!("{newton}: accepted");
        };
        assert!(error.contains("one_sweep"), "{error}");
    }
}
