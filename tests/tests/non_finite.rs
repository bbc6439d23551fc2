//! Non-finite values inside a unit stop the run with the unit, the time and
//! the quantity (issue 27), where before they could ride on in values no
//! output shows: the beam, the cable, the reduced section and the chord check
//! their state after every step (`contract::require_finite_state`); the
//! nonlinear section's Newton and the span's state-space units did already.

use slender_scene::Scene;
use slender_tests::{root, run};

/// A cantilever of EI = 1 N m^2 under a tip shear of 1e308 N: its deflection,
/// P L^3 / (3 EI), overflows.
const OVERFLOWING_BEAM: &str = r#"
title = "overflowing cantilever"
[simulation]
duration = 1.0
step = 0.1
[master]
scheme = "gauss_seidel"
[[units]]
name = "pipe"
kind = "beam"
[units.parameters]
length = 10.0
elements = 4
flexural_rigidity = 1.0
mass_per_length = 10.0
boundary.left = [{ quantity = "deflection", value = 0.0 }, { quantity = "rotation", value = 0.0 }]
boundary.right = [{ quantity = "moment", value = 0.0 }, { quantity = "shear", value = 1e308 }]
[output]
signals = ["pipe.right_deflection"]
"#;

#[test]
fn an_overflowing_beam_stops_the_run_naming_unit_time_and_quantity() {
    let scene = Scene::parse(&root().join("overflow.toml"), OVERFLOWING_BEAM.to_owned())
        .expect("the scene is valid: every value is finite");
    let series = run(&scene);
    let error = series.error.expect("the run stops");
    println!("{error}");
    assert!(error.contains("unit `pipe`"), "{error}");
    assert!(error.contains("failed at t = "), "{error}");
    assert!(
        error.contains("the beam's nodal displacements became non-finite"),
        "{error}"
    );
}

#[test]
fn a_finite_state_passes_and_a_non_finite_one_names_its_entry() {
    use slender_units::contract::require_finite_state;
    assert!(require_finite_state("q", &[0.0, -1e308, 5.0]).is_ok());
    let e = require_finite_state("the cable's nodal velocities", &[0.0, 1.0, f64::NAN])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("the cable's nodal velocities became non-finite (NaN at entry 2 of 3)"),
        "{e}"
    );
}
