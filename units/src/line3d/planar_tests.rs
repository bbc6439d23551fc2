//! The 3D line in a vertical plane against the planar `nonlinear` section on
//! the same problem: seed 000's polyester line hanging from a top force.

use super::Line3d;
use super::tests::{output, rotated};
use crate::contract::{Driver, Time};

/// The polyester line of seed 000 hanging from a top force (N, x and z)
/// with `elements`: the planar `nonlinear` section's top (x, z) and anchor
/// force (x, z) after `seconds` of a 250 kN surge force at 0.6 rad/s.
fn planar_polyester(elements: usize, seconds: usize) -> [f64; 4] {
    use crate::nonlinear::{NonlinearParams, NonlinearSection};
    let text = format!(
        r#"
static_start = true
segments = [{{ length = 1934.0, angle_deg = 39.4, elements = {elements}, axial_stiffness = 4.6598e8, bending_stiffness = 100.0, mass_per_length = 44.7, submerged_weight = 93.2, diameter = 0.264, drag_normal = 1.6, added_mass_normal = 1.0 }}]
ends.start = {{ kind = "pinned" }}
ends.end = {{ x = {{ force = {{ offset = 1.9151e6, amplitude = 2.5e5, angular_frequency = 0.6 }} }}, z = {{ force = 1.6070e6 }} }}
integrator = {{ kind = "hht", alpha = 0.3 }}
"#,
    );
    let params: NonlinearParams = toml::from_str(&text).unwrap();
    let mut d = Driver::new(NonlinearSection::new(params).unwrap());
    d.initialize(Time::ZERO).unwrap();
    let h = Time::from_secs(0.1).unwrap();
    let mut t = Time::ZERO;
    for _ in 0..seconds * 10 {
        d.do_step(t, h).unwrap();
        t += h;
    }
    let mut out = vec![0.0; d.description().outputs.len()];
    d.outputs(&mut out).unwrap();
    let at = |n: &str| out[d.description().output_index(n).unwrap()];
    [
        at("end_position_x"),
        at("end_position_z"),
        at("start_force_x"),
        at("start_force_z"),
    ]
}

/// The same with `line3d` in the plane at `azimuth`, rotated back to it, the
/// anchor 1200.11 m down.
fn line3d_polyester(elements: usize, seconds: usize, azimuth: f64) -> [f64; 4] {
    let [x, y] = rotated([1529.11, 0.0], azimuth);
    let text = format!(
        r#"
length = 1934.0
elements = {elements}
axial_stiffness = 4.6598e8
bending_stiffness = 100.0
mass_per_length = 44.7
submerged_weight = 93.2
diameter = 0.264
drag_normal = 1.6
added_mass_normal = 1.0
start = {{ position = [0.0, 0.0, -1200.11] }}
end = {{ position = [{x}, {y}, 0.0], condition = "force" }}
"#,
    );
    let mut d = Driver::new(Line3d::new(toml::from_str(&text).unwrap()).unwrap());
    let force = |t: f64| {
        let [fx, fy] = rotated([1.9151e6 + 2.5e5 * (0.6 * t).sin(), 0.0], azimuth);
        [fx, fy, 1.6070e6]
    };
    d.set_inputs(&force(0.0)).unwrap();
    d.initialize(Time::ZERO).unwrap();
    let h = Time::from_secs(0.1).unwrap();
    let mut t = Time::ZERO;
    for k in 1..=seconds * 10 {
        d.set_inputs(&force(k as f64 * 0.1)).unwrap();
        d.do_step(t, h).unwrap();
        t += h;
    }
    let [x, _] = rotated(
        [output(&d, "end_position_x"), output(&d, "end_position_y")],
        -azimuth,
    );
    // The planar section reports the force on the anchor's support: the
    // line's pull reversed, as line3d's start force is.
    let [fx, _] = rotated(
        [output(&d, "start_force_x"), output(&d, "start_force_y")],
        -azimuth,
    );
    // Under water (z < 0): the planar section's z is from its anchor.
    [
        x,
        output(&d, "end_position_z") + 1200.11,
        fx,
        output(&d, "start_force_z"),
    ]
}

#[test]
fn in_its_plane_the_3d_line_converges_to_the_planar_section() {
    // The planar section is a co-rotational beam with rotations, line3d a
    // rotation-free line: at one mesh they differ by their discretisations,
    // which vanish together. Static (0 s) and after 60 s of surge force
    // with drag and added mass, line3d's plane turned by 37 degrees.
    for seconds in [0, 60] {
        let differences: Vec<[f64; 2]> = [40, 160]
            .iter()
            .map(|&n| {
                let planar = planar_polyester(n, seconds);
                let turned = line3d_polyester(n, seconds, 37.0);
                let top = (planar[0] - turned[0]).hypot(planar[1] - turned[1]) / 1934.0;
                let anchor = (planar[2] - turned[2]).hypot(planar[3] - turned[3]) / 2.5e6;
                [top, anchor]
            })
            .collect();
        let [coarse, fine] = [differences[0], differences[1]];
        // The top converges at second order (or faster), the anchor's force
        // (whose inertia each model lumps its own way) more slowly.
        assert!(
            fine[0] < coarse[0] / 4.0 && fine[0] < 1e-4,
            "{seconds} s: {differences:?}"
        );
        assert!(
            fine[1] <= coarse[1].max(1e-11) && fine[1] < 5e-4,
            "{seconds} s: {differences:?}"
        );
    }
}
