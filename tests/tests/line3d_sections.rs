//! A 3D line cut in two `line3d` sections at a node, coupled at the cut by
//! velocity (the lower section's end follows the upper section's start) and
//! force (the upper section's start carries the lower section's pull), with
//! the Newton master on the units' step Jacobians: against the same line as
//! one unit (its twin), at the same mesh and step. Seed 000's polyester line
//! with a current across its plane and its fairlead surging and swaying.

use slender_scene::Scene;
use slender_tests::{Series, root, run};
use slender_units::line3d::{Line3d, Line3dParams};
use slender_units::{Driver, Time, Unit};

const ELEMENTS: usize = 40;
const CUT: usize = 16;
const LENGTH: f64 = 1934.0;

/// The line's parameters with `elements` and HHT `alpha`, between `start`
/// and `end`, its ends' conditions given as TOML (`start_extra`, `end_extra`).
fn params(
    elements: usize,
    alpha: f64,
    (start, end): ([f64; 3], [f64; 3]),
    start_extra: &str,
    end_extra: &str,
) -> String {
    format!(
        r#"length = {length}
elements = {elements}
axial_stiffness = 4.6598e8
bending_stiffness = 100.0
mass_per_length = 44.7
submerged_weight = 93.2
diameter = 0.264
drag_normal = 1.6
added_mass_normal = 1.0
alpha = {alpha}
start = {{ position = {start:?}{start_extra} }}
end = {{ position = {end:?}{end_extra} }}
current = [{{ depth = 0.0, speed = 0.5, heading_deg = 90.0 }}, {{ depth = 1200.0, speed = 0.0, heading_deg = 90.0 }}]
"#,
        length = LENGTH * elements as f64 / ELEMENTS as f64,
    )
}

const ANCHOR: [f64; 3] = [0.0, 0.0, -1200.11];
const FAIRLEAD: [f64; 3] = [1529.11, 0.0, 0.0];
const MOTION: &str = r#", condition = "motion", motion = [[{ amplitude = 3.0, angular_frequency = 0.6 }], [{ amplitude = 2.0, angular_frequency = 0.3 }], []], fade_in = 10.0"#;

/// Where the whole line's statics put node `CUT` (m).
fn cut_position() -> [f64; 3] {
    let text = params(ELEMENTS, 0.0, (ANCHOR, FAIRLEAD), "", MOTION);
    let p: Line3dParams = toml::from_str(&text).unwrap();
    let mut d = Driver::new(Line3d::new(p).unwrap());
    d.initialize(Time::ZERO).unwrap();
    let mut position = [0.0; 3];
    for (axis, p) in position.iter_mut().enumerate() {
        let mut values = vec![0.0; ELEMENTS + 1];
        d.unit().field_values(axis, &mut values).unwrap();
        *p = values[CUT];
    }
    position
}

/// Indents a parameter table under `[units.parameters]`.
fn unit(name: &str, parameters: &str) -> String {
    format!("[[units]]\nname = \"{name}\"\nkind = \"line3d\"\n[units.parameters]\n{parameters}\n")
}

fn scene(alpha: f64) -> Scene {
    let cut = cut_position();
    let lower = params(CUT, alpha, (ANCHOR, cut), "", ", condition = \"velocity\"");
    let upper = params(
        ELEMENTS - CUT,
        alpha,
        (cut, FAIRLEAD),
        ", condition = \"force\"",
        MOTION,
    );
    let twin = params(ELEMENTS, alpha, (ANCHOR, FAIRLEAD), "", MOTION);
    let mut links = String::new();
    for axis in ["x", "y", "z"] {
        links += &format!(
            "[[connections]]\nfrom = \"upper.start_velocity_{axis}\"\nto = \"lower.end_velocity_{axis}\"\n\n"
        );
        links += &format!(
            "[[connections]]\nfrom = \"lower.end_force_{axis}\"\nto = \"upper.start_force_{axis}\"\n\n"
        );
    }
    let text = format!(
        r#"title = "line3d in two sections against its twin"

[simulation]
duration = 60.0
step = 0.1

[master]
scheme = "iterative_jacobi"
extrapolation = "linear"
max_iterations = 30
tolerances = {{ velocity = 1e-9, force = 1e-3 }}
newton = {{ derivatives = "units" }}

{lower}
{upper}
{twin}
{links}
[output]
signals = ["upper.end_force_x", "upper.end_force_y", "upper.end_force_z", "twin.end_force_x", "twin.end_force_y", "twin.end_force_z", "lower.start_force_y", "twin.start_force_y", "lower.end_position_y", "upper.start_position_y"]
"#,
        lower = unit("lower", &lower),
        upper = unit("upper", &upper),
        twin = unit("twin", &twin),
    );
    Scene::parse(&root().join("line3d_sections.toml"), text).unwrap_or_else(|e| panic!("{e}"))
}

/// The largest difference of `a` from `b` over the run, relative to `scale`.
fn worst(series: &Series, a: &str, b: &str, scale: f64) -> f64 {
    series
        .get(a)
        .iter()
        .zip(series.get(b))
        .map(|(x, y)| (x - y).abs() / scale)
        .fold(0.0, f64::max)
}

/// The largest difference (N) of the sections' fairlead and anchor forces
/// from the twin's over the run, and the largest gap at the cut (m).
fn differences(alpha: f64) -> (f64, f64) {
    let series = run(&scene(alpha));
    assert!(series.error.is_none(), "{:?}", series.error);
    let mut force = 0.0f64;
    for c in ["x", "y", "z"] {
        force = force.max(worst(
            &series,
            &format!("upper.end_force_{c}"),
            &format!("twin.end_force_{c}"),
            1.0,
        ));
    }
    force = force.max(worst(
        &series,
        "lower.start_force_y",
        "twin.start_force_y",
        1.0,
    ));
    let gap = worst(
        &series,
        "lower.end_position_y",
        "upper.start_position_y",
        1.0,
    );
    (force, gap)
}

#[test]
fn two_3d_sections_coupled_by_newton_follow_their_twin() {
    // The trapezoidal rule (alpha 0): the sections are the twin to the
    // coupling tolerance (1e-3 N on forces of 2.5 MN).
    let (force, gap) = differences(0.0);
    assert!(force < 1e-2, "forces {force:e} N from the twin's");
    assert!(gap < 1e-6, "gap at the cut: {gap:e} m");
    // With numerical damping the cut node's inertia enters the loaded side
    // alpha-weighted (the twin weights it fully): a difference linear in alpha.
    let (strong, _) = differences(0.3);
    let (light, _) = differences(0.1);
    assert!(strong < 1e-4 * 2.5e6, "{strong:e} N at alpha 0.3");
    assert!(
        light < 0.5 * strong && light > 0.2 * strong,
        "{light:e} N at 0.1 against {strong:e} N at 0.3"
    );
}
