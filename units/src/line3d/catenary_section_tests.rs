//! The catenary section (`catenary3d`) against the 3D line's statics, moved
//! by coupled velocities, its step Jacobian and what it refuses.

use super::catenary_section::CatenarySection;
use super::params::EndCondition;
use super::tests::{laid_line, line, output, started, step_from};
use crate::contract::{Driver, DriverSlot, Time, Unit};

/// A driver around a catenary section, initialised at t = 0 with `inputs`.
fn catenary(p: super::Line3dParams, inputs: &[f64]) -> Driver<CatenarySection> {
    let mut d = Driver::new(CatenarySection::new(p).expect("valid parameters"));
    d.set_inputs(inputs).unwrap();
    d.initialize(Time::ZERO).expect("catenary");
    d
}

/// Output `name` of a driver now.
fn value<U: Unit>(d: &Driver<U>, name: &str) -> f64 {
    let i = d.description().output_index(name).expect(name);
    let mut out = vec![0.0; d.description().outputs.len()];
    d.outputs(&mut out).unwrap();
    out[i]
}

#[test]
fn the_catenary_section_pulls_as_the_converged_3d_line_at_rest() {
    // In a plane at 35 degrees, against the 3D line's statics at 320
    // elements. Hanging free the line converges at second order (2e-6 of
    // the tension at 320 elements); partly laid at first order, with the
    // touchdown between nodes (5e-5 of the tension), and its anchor node's
    // reaction holds half an element's weight, which the seabed carries in
    // the closed form.
    let cases = [
        (line(320, 35.0, ""), 1e-5, 0.0),
        (laid_line(320, 35.0, ""), 2e-4, 50.0 * 380.0 / 640.0),
    ];
    for (p, tolerance, anchor_weight) in cases {
        let fine = started(p.clone());
        let closed = catenary(p, &[]);
        let scale = value(&closed, "end_tension");
        for name in [
            "end_force_x",
            "end_force_y",
            "end_force_z",
            "start_force_x",
            "start_force_y",
            "start_force_z",
        ] {
            let (a, b) = (value(&closed, name), output(&fine, name));
            let allowed = tolerance * scale
                + if name == "start_force_z" {
                    anchor_weight
                } else {
                    0.0
                };
            assert!((a - b).abs() < allowed, "{name}: {a} against {b}");
        }
        let arc = output(&fine, "touchdown_arc");
        assert!(
            (value(&closed, "touchdown_arc") - arc).abs() <= 2.0 * 380.0 / 320.0,
            "touchdown {arc}"
        );
    }
}

#[test]
fn a_moved_catenary_section_follows_its_velocity_and_its_jacobian_is_exact() {
    let mut p = laid_line(10, 35.0, "");
    p.end.condition = EndCondition::Velocity;
    let inputs = [0.4, -0.3, 0.2];
    let mut d = catenary(p.clone(), &inputs);
    let h = Time::from_secs(0.1).unwrap();
    let mut t = Time::ZERO;
    for _ in 0..50 {
        d.do_step(t, h).unwrap();
        t += h;
    }
    // 5 s at constant velocity: the end moved by 5 s times it, and pulls
    // as the catenary through the anchor and that point.
    let mut moved = p.clone();
    moved.end.condition = EndCondition::Fixed;
    for (c, u) in inputs.iter().enumerate() {
        moved.end.position[c] += 5.0 * u;
        let axis = ["x", "y", "z"][c];
        let at = value(&d, &format!("end_position_{axis}"));
        assert!((at - moved.end.position[c]).abs() < 1e-9, "{axis}: {at}");
    }
    let still = catenary(moved, &[]);
    for name in ["end_force_x", "end_force_y", "end_force_z", "start_force_x"] {
        let (a, b) = (value(&d, name), value(&still, name));
        assert!(
            (a - b).abs() < 1e-9 * b.abs().max(1.0),
            "{name}: {a} against {b}"
        );
    }
    // The step Jacobian against central differences of the step.
    let mut slot = DriverSlot::new();
    d.save(&mut slot).unwrap();
    let n_out = d.description().outputs.len();
    let step = |d: &mut Driver<CatenarySection>, u: &[f64]| step_from(d, &slot, (t, h), u);
    step(&mut d, &inputs);
    let mut jacobian = vec![0.0; n_out * 3];
    d.step_jacobian(&mut jacobian).unwrap();
    for j in 0..3 {
        let (mut up, mut down) = (inputs.to_vec(), inputs.to_vec());
        up[j] += 1e-3;
        down[j] -= 1e-3;
        let (plus, minus) = (step(&mut d, &up), step(&mut d, &down));
        for row in 0..18 {
            let fd = (plus[row] - minus[row]) / 2e-3;
            let exact = jacobian[row * 3 + j];
            assert!(
                (fd - exact).abs() <= 1e-5 * fd.abs().max(1.0),
                "output {row}, input {j}: {exact} against {fd}"
            );
        }
    }
}

#[test]
fn what_the_catenary_cannot_represent_is_refused_by_name() {
    let mut sloped = laid_line(10, 0.0, "");
    sloped.seabed.as_mut().unwrap().slope = [0.05, 0.0];
    let mut raised = laid_line(10, 0.0, "");
    raised.seabed.as_mut().unwrap().depth = Some(120.0);
    let mut loaded = line(10, 0.0, "");
    loaded.end.condition = EndCondition::Force;
    let mut moving_anchor = line(10, 0.0, "");
    moving_anchor.start.condition = EndCondition::Velocity;
    for (p, key) in [
        (sloped, "seabed"),
        (raised, "seabed"),
        (loaded, "end.condition"),
        (moving_anchor, "start.condition"),
    ] {
        let error = CatenarySection::new(p).err().expect(key).to_string();
        assert!(error.contains(key), "{error}");
    }
}

/// Fields `names` of a unit now, each as a vector.
fn fields_of<U: Unit>(d: &Driver<U>, names: &[&str]) -> Vec<Vec<f64>> {
    let fields = d.unit().fields();
    (names.iter())
        .map(|name| {
            let k = fields.iter().position(|f| f.name == *name).expect(name);
            let mut values = vec![0.0; fields[k].len];
            d.unit().field_values(k, &mut values).unwrap();
            values
        })
        .collect()
}

#[test]
fn the_catenary_s_stations_and_tensions_are_the_3d_line_s_at_rest() {
    // Against the 3D line's statics at the same 320 elements, in a plane at
    // 35 degrees: the stations (the line's nodes at the same unstretched
    // arc) and the tension along the line. Measured: hanging free 9.3e-7
    // of the length and 2.4e-6 of the top tension; partly laid 4.1e-5 and
    // 1.7e-4 (nodal contact puts the touchdown at a node: first order).
    let cases = [
        (line(320, 35.0, ""), 1e-5, 1e-5),
        (laid_line(320, 35.0, ""), 2e-4, 1e-3),
    ];
    for (p, position_tolerance, tension_tolerance) in cases {
        let length = p.length;
        let fine = started(p.clone());
        let closed = catenary(p, &[]);
        let names = ["x", "y", "z", "tension"];
        let (a, b) = (fields_of(&fine, &names), fields_of(&closed, &names));
        let largest = |k: usize| {
            (a[k].iter().zip(&b[k]))
                .map(|(x, y)| (x - y).abs())
                .fold(0.0, f64::max)
        };
        let position = largest(0).max(largest(1)).max(largest(2)) / length;
        let scale = value(&closed, "end_tension");
        let tension = largest(3) / scale;
        eprintln!("stations {position:.2e} of the length, tension {tension:.2e} of the top's");
        assert_eq!((a[0].len(), a[3].len()), (b[0].len(), b[3].len()));
        assert!(position < position_tolerance, "{position}");
        assert!(tension < tension_tolerance, "{tension}");
        // The last station is the end the section is held at.
        let end = [
            value(&closed, "end_position_x"),
            value(&closed, "end_position_z"),
        ];
        assert!((b[0][320] - end[0]).abs() + (b[2][320] - end[1]).abs() < 1e-9 * length);
    }
}
