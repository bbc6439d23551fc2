//! Checks of the 3D line against closed forms and its own invariants.

use super::*;
use crate::contract::{Driver, Time};

/// A polyester-like line (EA 1e8 N, 50 N/m in water) from an anchor at
/// 100 m depth to a fairlead 300 m across, in a vertical plane at `azimuth`
/// (deg), with `elements`; `extra` TOML lines are appended.
pub(super) fn line(elements: usize, azimuth: f64, extra: &str) -> Line3dParams {
    let (s, c) = azimuth.to_radians().sin_cos();
    let text = format!(
        r#"
length = 350.0
elements = {elements}
axial_stiffness = 1.0e8
mass_per_length = 8.0
submerged_weight = 50.0
diameter = 0.1
start = {{ position = [0.0, 0.0, -100.0] }}
end = {{ position = [{x}, {y}, 0.0] }}
{extra}
"#,
        x = 300.0 * c,
        y = 300.0 * s,
    );
    toml::from_str(&text).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

/// A driver around a line, initialised at t = 0.
pub(super) fn started(p: Line3dParams) -> Driver<Line3d> {
    let mut d = Driver::new(Line3d::new(p).expect("valid parameters"));
    d.initialize(Time::from_secs(0.0).unwrap())
        .expect("statics");
    d
}

/// Restores `slot` into `d`, steps it from `t` by `h` under `inputs` and
/// returns its outputs: one step of a Jacobian check, repeatable.
pub(super) fn step_from<U: crate::contract::Unit>(
    d: &mut Driver<U>,
    slot: &crate::contract::DriverSlot,
    (t, h): (Time, Time),
    inputs: &[f64],
) -> Vec<f64> {
    d.restore(slot).unwrap();
    d.set_inputs(inputs).unwrap();
    d.do_step(t, h).unwrap();
    let mut out = vec![0.0; d.description().outputs.len()];
    d.outputs(&mut out).unwrap();
    out
}

/// Output `name` now.
pub(super) fn output(d: &Driver<Line3d>, name: &str) -> f64 {
    let i = d.description().output_index(name).expect(name);
    let mut out = vec![0.0; d.description().outputs.len()];
    d.outputs(&mut out).expect("outputs");
    out[i]
}

/// The line of [`line`] 380 m long: 271 m of it lie on a seabed at the
/// anchor's depth.
pub(super) fn laid_line(elements: usize, azimuth: f64, extra: &str) -> Line3dParams {
    let mut p = line(
        elements,
        azimuth,
        &format!("seabed = {{ depth = 100.0, stiffness = 1.0e7 }}\n{extra}"),
    );
    p.length = 380.0;
    p
}

/// Rotates (x, y) by `azimuth` (deg).
pub(super) fn rotated(v: [f64; 2], azimuth: f64) -> [f64; 2] {
    let (s, c) = azimuth.to_radians().sin_cos();
    [c * v[0] - s * v[1], s * v[0] + c * v[1]]
}

/// Two sines of a fairlead motion component (m).
fn sines(a: f64, b: f64) -> Vec<crate::signal::sine::Sine> {
    use crate::signal::sine::Sine;
    vec![
        Sine {
            amplitude: a,
            angular_frequency: 0.6,
            ..Sine::default()
        },
        Sine {
            amplitude: b,
            angular_frequency: 0.25,
            phase: 0.3,
            decay: 0.0,
        },
    ]
}

/// Steps `d` for `seconds` at `h` (s); the outputs after every second.
fn run(d: &mut Driver<Line3d>, seconds: usize, h: f64) -> Vec<Vec<f64>> {
    let steps_per_second = (1.0 / h).round() as usize;
    let h = Time::from_secs(h).unwrap();
    let mut t = Time::ZERO;
    let mut rows = Vec::new();
    let mut out = vec![0.0; d.description().outputs.len()];
    for k in 1..=seconds * steps_per_second {
        d.do_step(t, h).expect("step");
        t += h;
        if k % steps_per_second == 0 {
            d.outputs(&mut out).unwrap();
            rows.push(out.clone());
        }
    }
    rows
}

/// The laid line at `azimuth` with drag, a current across its plane and
/// seabed friction, its fairlead surging 1 m in the plane and swaying 1 m
/// across it: the outputs every second over `seconds`.
fn moving_line(azimuth: f64, seconds: usize) -> Vec<Vec<f64>> {
    let heading = azimuth + 90.0;
    let extra = format!(
        r#"drag_normal = 1.2
drag_tangential = 0.008
added_mass_normal = 1.0
current = [{{ depth = 0.0, speed = 0.8, heading_deg = {heading} }}, {{ depth = 100.0, speed = 0.2, heading_deg = {heading} }}]
"#
    );
    let mut p = laid_line(76, azimuth, &extra);
    // The invariance is the discrete equations'; Newton is converged well
    // below the 1e-9 asserted (at the default 1e-10 of 380 m, a step's
    // Newton started from its prediction may stop 4e-8 m from the solution:
    // 2e-9 of the tension apart between two planes).
    p.tolerance = 1e-13;
    let seabed = p.seabed.as_mut().unwrap();
    seabed.friction_axial = 0.6;
    seabed.friction_lateral = 1.0;
    seabed.damping = 1e3;
    let [sx, sy] = rotated([1.0, 0.0], azimuth);
    let [wx, wy] = rotated([0.0, 1.0], azimuth);
    p.end.condition = EndCondition::Motion;
    p.end.motion = [sines(sx, wx), sines(sy, wy), Vec::new()];
    run(&mut started(p), seconds, 0.1)
}

#[test]
fn a_line_answers_the_same_in_every_vertical_plane() {
    let reference = moving_line(0.0, 60);
    let names = [
        "end_force_x",
        "end_force_y",
        "end_force_z",
        "start_force_x",
        "start_force_y",
    ];
    let d = started(laid_line(76, 0.0, ""));
    let index = |n: &str| d.description().output_index(n).unwrap();
    for azimuth in [37.0, 90.0, 213.0] {
        let turned = moving_line(azimuth, 60);
        for (a, b) in reference.iter().zip(&turned) {
            for side in ["end", "start"] {
                let (x, y, z) = (
                    index(&format!("{side}_force_x")),
                    index(&format!("{side}_force_y")),
                    index(&format!("{side}_force_z")),
                );
                let expected = rotated([a[x], a[y]], azimuth);
                let scale = a[index("end_tension")];
                for (got, want) in [(b[x], expected[0]), (b[y], expected[1]), (b[z], a[z])] {
                    assert!(
                        (got - want).abs() < 1e-9 * scale,
                        "{azimuth}: {got} against {want} ({names:?})"
                    );
                }
            }
            for n in [
                "end_tension",
                "touchdown_arc",
                "largest_tension",
                "friction_work",
                "kinetic_energy",
            ] {
                let (got, want) = (b[index(n)], a[index(n)]);
                assert!(
                    (got - want).abs() <= 1e-9 * want.abs().max(1.0),
                    "{azimuth} {n}: {got} against {want}"
                );
            }
        }
    }
}

/// A 20 m pipe (EI 1e7 N m^2: it bows by millimetres; 50 N/m in water) lying straight along x on a
/// flat seabed, both ends dragged at `velocity` (m/s) by coupled inputs.
pub(super) fn dragged(velocity: [f64; 3]) -> Driver<Line3d> {
    let text = r#"
length = 20.0
elements = 20
axial_stiffness = 1.0e8
bending_stiffness = 1.0e7
mass_per_length = 8.0
submerged_weight = 50.0
start = { position = [0.0, 0.0, -100.0], condition = "velocity" }
end = { position = [20.0, 0.0, -100.0], condition = "velocity" }
seabed = { depth = 100.0, stiffness = 1.0e6, friction_axial = 0.5, friction_lateral = 0.8, stick_velocity = 0.01 }
"#;
    let mut d = Driver::new(Line3d::new(toml::from_str(text).unwrap()).unwrap());
    d.set_inputs(&[velocity, velocity].concat()).unwrap();
    d.initialize(Time::ZERO).expect("statics");
    d
}

/// (sum of the ends' force x, y, z on what drags them (N) after 20 s at
/// 0.05 s, friction work over the last 10 s and over all 20 s, energy
/// error (J)).
fn drag_result(velocity: [f64; 3]) -> ([f64; 3], [f64; 2], f64) {
    let mut d = dragged(velocity);
    let rows = run(&mut d, 20, 0.05);
    let at = |row: &Vec<f64>, n: &str| row[d.description().output_index(n).unwrap()];
    let last = rows.last().unwrap();
    (
        ["x", "y", "z"]
            .map(|c| at(last, &format!("start_force_{c}")) + at(last, &format!("end_force_{c}"))),
        [
            at(last, "friction_work") - at(&rows[9], "friction_work"),
            at(last, "friction_work"),
        ],
        at(last, "energy_error"),
    )
}

#[test]
fn a_line_dragged_on_the_seabed_carries_its_friction_along_and_across() {
    let weight = 50.0 * 20.0;
    for (velocity, mu, k) in [
        ([0.0, 0.05, 0.0], 0.8, 1),
        ([0.05, 0.0, 0.0], 0.5, 0),
        ([0.0, 0.005, 0.0], 0.8, 1),
    ] {
        let speed = velocity[k];
        let ([fx, fy, fz], [work, total], error) = drag_result(velocity);
        // The seabed carries the weight less what the held ends carry (the
        // ends themselves touch it at no depth).
        let normal = weight + fz;
        assert!(normal > 0.5 * weight && normal < weight, "{normal}");
        // mu N tanh(v / v_stick): the full limit when sliding, a fraction
        // of it (creeping) below the stick velocity.
        let expected = mu * normal * (speed / 0.01f64).tanh();
        let along = [fx, fy][k];
        let across = [fx, fy][1 - k];
        assert!(
            (along + expected).abs() < 1e-3 * expected,
            "{velocity:?}: {along} against -{expected}"
        );
        assert!(
            across.abs() < 1e-6 * expected,
            "{velocity:?}: {across} across the drag"
        );
        // Dissipated over the last 10 s: the friction force times the distance.
        let dissipated = expected * speed * 10.0;
        assert!(
            (work + dissipated).abs() < 1e-2 * dissipated,
            "{velocity:?}: work {work} against -{dissipated}"
        );
        // The ledger closes: what the ends put in, friction took out (to the
        // integrator's own dissipation of the start's axial vibration).
        assert!(
            error.abs() < 1e-3 * total.abs(),
            "{velocity:?}: energy error {error} J of {total} J"
        );
    }
}

#[test]
fn airy_waves_follow_the_dispersion_relation_and_the_closed_form() {
    use super::waves::{AiryWaves, GRAVITY, wavenumber};
    // Deep water: k = omega^2 / g; finite depth: omega^2 = g k tanh(k h).
    assert_eq!(wavenumber(0.6, f64::INFINITY), 0.36 / GRAVITY);
    for (omega, depth) in [(0.3, 50.0), (0.6, 20.0), (1.2, 200.0)] {
        let k = wavenumber(omega, depth);
        assert!((GRAVITY * k * (k * depth).tanh() / (omega * omega) - 1.0).abs() < 1e-12);
    }
    let waves: super::params::Waves = toml::from_str(
        "sines = [{ amplitude = 1.5, angular_frequency = 0.6, phase = 0.2 }]\nheading_deg = 30.0\nwater_depth = 40.0",
    )
    .unwrap();
    let airy = AiryWaves::new(&waves);
    let (k, h, a, w) = (wavenumber(0.6, 40.0), 40.0, 1.5, 0.6);
    let (x, y, z, t) = (12.0, -7.0, -15.0, 3.7);
    let (s, c) = 30f64.to_radians().sin_cos();
    let theta = w * t + 0.2 - k * (x * c + y * s);
    let eta = a * theta.sin();
    // Wheeler: the profile at z is the one at (z - eta) h / (h + eta).
    let zs = (z - eta) * h / (h + eta);
    let horizontal = a * w * (k * (zs + h)).cosh() / (k * h).sinh() * theta.sin();
    let vertical = a * w * (k * (zs + h)).sinh() / (k * h).sinh() * theta.cos();
    let got = airy.at(&nalgebra::Vector3::new(x, y, z), t).unwrap();
    assert!((got.elevation - eta).abs() < 1e-12);
    for (g, e) in got
        .velocity
        .iter()
        .zip([horizontal * c, horizontal * s, vertical])
    {
        assert!((g - e).abs() < 1e-12, "{g} against {e}");
    }
    let horizontal_rate = a * w * w * (k * (zs + h)).cosh() / (k * h).sinh() * theta.cos();
    assert!((got.acceleration.x - horizontal_rate * c).abs() < 1e-12);
    // A point above the crest is dry.
    assert!(
        airy.at(&nalgebra::Vector3::new(x, y, eta + 0.01), t)
            .is_none()
    );
}

#[test]
fn a_vertical_line_in_regular_waves_takes_morisons_force_by_hand() {
    let text = r#"
length = 39.99
elements = 20
axial_stiffness = 1.0e9
mass_per_length = 100.0
diameter = 0.5
drag_normal = 1.1
drag_tangential = 0.02
added_mass_normal = 0.9
added_mass_tangential = 0.1
start = { position = [0.0, 0.0, -45.0] }
end = { position = [0.0, 0.0, -5.0] }
waves = { sines = [{ amplitude = 2.0, angular_frequency = 0.7 }], heading_deg = 0.0 }
"#;
    let d = started(toml::from_str(text).unwrap());
    let unit = d.unit();
    let airy = super::waves::AiryWaves::new(unit.params.waves.as_ref().unwrap());
    let (q, v) = (&unit.state.q, vec![0.0; unit.state.q.len()]);
    let (rho, diameter, length) = (1025.0, 0.5, 39.99 / 20.0);
    let area = std::f64::consts::PI * diameter * diameter / 4.0;
    for t in [0.0, 1.3, 4.1] {
        for i in [3, 10, 17] {
            let f = unit.environment.node_forces(q, &v, t, i, None).hydrodynamic;
            let water = airy.at(&mechanics::node(q, i), t).unwrap();
            // The line is vertical: x, y normal to it, z along it.
            let (u, du) = (water.velocity, water.acceleration);
            let normal_speed = u.x.hypot(u.y);
            let fx = 0.5 * rho * diameter * 1.1 * length * normal_speed * u.x
                + rho * area * 1.9 * length * du.x;
            let fz = 0.5 * rho * std::f64::consts::PI * diameter * 0.02 * length * u.z.abs() * u.z
                + rho * area * 0.1 * length * du.z;
            assert!(
                (f.x - fx).abs() < 1e-9 * fx.abs().max(1.0),
                "{t} {i}: {} against {fx}",
                f.x
            );
            assert!(f.y.abs() < 1e-9 * fx.abs().max(1.0));
            assert!(
                (f.z - fz).abs() < 1e-9 * fz.abs().max(1.0),
                "{t} {i}: {} against {fz}",
                f.z
            );
        }
    }
}

#[test]
fn a_slack_chain_under_a_large_surge_stays_bounded_with_drag() {
    // The laid line's fairlead surging 6 m and swaying 2 m for 300 s: the
    // laid part goes slack and snaps taut every cycle.
    let mut p = laid_line(
        76,
        0.0,
        "drag_normal = 1.2\ndrag_tangential = 0.01\nadded_mass_normal = 1.0",
    );
    p.end.condition = EndCondition::Motion;
    p.end.motion = [sines(6.0, 0.0), sines(0.0, 2.0), Vec::new()];
    let mut d = started(p);
    let rows = run(&mut d, 300, 0.1);
    let at = |row: &Vec<f64>, n: &str| row[d.description().output_index(n).unwrap()];
    let kinetic: Vec<f64> = rows.iter().map(|r| at(r, "kinetic_energy")).collect();
    let first = kinetic[..60].iter().cloned().fold(0.0, f64::max);
    let later = kinetic[60..].iter().cloned().fold(0.0, f64::max);
    assert!(rows.iter().flatten().all(|v| v.is_finite()));
    assert!(
        later < 3.0 * first,
        "kinetic energy {later} J later against {first} J in the first minute"
    );
    let tension = rows
        .iter()
        .map(|r| at(r, "largest_tension"))
        .fold(0.0, f64::max);
    assert!(tension < 10.0 * at(&rows[0], "end_tension"), "{tension}");
}

#[test]
fn a_restored_line_steps_bit_identically() {
    let mut p = laid_line(40, 20.0, "drag_normal = 1.2");
    p.end.condition = EndCondition::Motion;
    p.end.motion = [sines(2.0, 0.0), sines(0.0, 1.0), Vec::new()];
    let mut d = started(p);
    run(&mut d, 5, 0.1);
    let mut slot = crate::contract::StateSlot::new();
    d.unit().save_state(&mut slot).unwrap();
    let first = run(&mut d, 3, 0.1);
    // The same steps again from the saved state (`run` counts time from 0
    // each time: both rounds read the motion at the same times).
    d.unit_mut_with_inputs().0.restore_state(&slot).unwrap();
    let second = run(&mut d, 3, 0.1);
    assert_eq!(first, second);
}

#[test]
fn what_the_line_cannot_model_is_refused_by_name() {
    let refused = |extra: &str, key: &str| {
        let text = format!(
            "length = 100.0\nelements = 10\naxial_stiffness = 1e8\nmass_per_length = 8.0\nstart = {{ position = [0.0, 0.0, -50.0] }}\nend = {{ position = [60.0, 0.0, 0.0] }}\n{extra}"
        );
        let p: Line3dParams = toml::from_str(&text).unwrap();
        let error = Line3d::new(p).err().expect(extra).to_string();
        assert!(error.contains(key), "{extra}: {error}");
    };
    refused("torsional_stiffness = 1e4", "torsion is not modelled");
    refused("drag_normal = 1.2", "diameter");
    refused("alpha = 0.5", "alpha");
    refused(
        "seabed = { depth = 50.0, stiffness = 0.0 }",
        "seabed.stiffness",
    );
    refused(
        "current = [{ depth = 10.0, speed = 1.0 }, { depth = 5.0, speed = 1.0 }]",
        "current[1].depth",
    );
    refused(
        "diameter = 0.1\nwaves = { heading_deg = 0.0 }",
        "either `spectrum` or `sines`",
    );
    let far = "length = 10.0\nelements = 10\naxial_stiffness = 1e8\nmass_per_length = 8.0\nstart = { position = [0.0, 0.0, -50.0] }\nend = { position = [60.0, 0.0, 0.0] }";
    let error = Line3d::new(toml::from_str(far).unwrap())
        .err()
        .unwrap()
        .to_string();
    assert!(error.contains("end.position"), "{error}");
    let misspelt = "length = 10.0\nelemnts = 10";
    assert!(
        toml::from_str::<Line3dParams>(misspelt)
            .unwrap_err()
            .to_string()
            .contains("elemnts")
    );
}

#[test]
fn a_faded_motion_starts_at_rest_and_its_rates_are_its_derivatives() {
    let end: super::params::EndSpec = toml::from_str(
        "position = [1.0, 2.0, 3.0]\ncondition = \"motion\"\nmotion = [[{ amplitude = 2.0, angular_frequency = 0.7, phase = 0.4 }], [], []]\nfade_in = 10.0",
    )
    .unwrap();
    let at = |t: f64| step::end_motion(&end, t);
    assert_eq!(at(0.0)[0], [1.0, 2.0, 3.0]);
    assert_eq!(at(0.0)[1], [0.0; 3]);
    let h = 1e-5;
    for t in [0.5, 4.0, 9.99, 12.0] {
        let rate = (at(t + h)[0][0] - at(t - h)[0][0]) / (2.0 * h);
        let acceleration = (at(t + h)[1][0] - at(t - h)[1][0]) / (2.0 * h);
        assert!((rate - at(t)[1][0]).abs() < 1e-7, "{t}");
        assert!((acceleration - at(t)[2][0]).abs() < 1e-6, "{t}");
    }
}

#[test]
fn faded_waves_start_calm_and_their_acceleration_is_their_velocity_s_rate() {
    use super::waves::AiryWaves;
    // Small waves (k A ~ 4e-4): Wheeler's stretch barely moves the profile,
    // so the water's acceleration at a point is its velocity's rate there.
    let waves: super::params::Waves = toml::from_str(
        "sines = [{ amplitude = 0.01, angular_frequency = 0.6, phase = 0.4 }]\nheading_deg = 20.0\nfade_in = 10.0",
    )
    .unwrap();
    let airy = AiryWaves::new(&waves);
    let p = nalgebra::Vector3::new(3.0, -4.0, -8.0);
    let at = |t: f64| airy.at(&p, t).unwrap();
    assert_eq!(at(0.0).velocity, nalgebra::Vector3::zeros());
    assert_eq!(airy.elevation(p.x, p.y, 0.0), 0.0);
    let h = 1e-4;
    for t in [1.0, 5.0, 9.9, 14.0] {
        let rate = (at(t + h).velocity - at(t - h).velocity) / (2.0 * h);
        let scale = at(t).acceleration.norm().max(1e-6);
        assert!(
            (rate - at(t).acceleration).norm() < 1e-3 * scale,
            "{t}: {rate:?} against {:?}",
            at(t).acceleration
        );
    }
}

#[test]
fn held_wave_kinematics_give_the_force_of_the_positions_they_were_taken_at() {
    // A wavy line's water force with the kinematics held at q equals the
    // one evaluated afresh at q; at another time they are not used.
    let p = line(
        20,
        30.0,
        "drag_normal = 1.2\nadded_mass_normal = 1.0\nwaves = { sines = [{ amplitude = 2.0, angular_frequency = 0.6 }, { amplitude = 1.0, angular_frequency = 1.1, phase = 0.3 }], heading_deg = 10.0, water_depth = 150.0 }",
    );
    let d = started(p);
    let line = d.unit();
    let (q, v) = (&line.state.q, &line.state.v);
    let mut environment = line.environment.clone();
    let fresh = |e: &environment::Environment, t: f64| {
        let mut f = vec![0.0; q.len()];
        e.add_hydrodynamic_force(q, v, t, &mut f);
        f
    };
    let (before, other) = (fresh(&environment, 7.3), fresh(&environment, 7.4));
    environment.hold_waves(q, 7.3);
    assert_eq!(fresh(&environment, 7.3), before);
    assert_eq!(fresh(&environment, 7.4), other);
    assert!(before.iter().any(|f| f.abs() > 1.0));
}
