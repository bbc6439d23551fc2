//! The body's ports. Inputs: per fairlead the force it receives (x, y, z,
//! global, N), then an external force and moment at the reference point
//! (global axes). Outputs: the reference point's position (m) and the roll,
//! pitch and yaw (rad, z-y'-x''), its velocity and the angular velocity;
//! per fairlead its global position, velocity and acceleration; then the
//! energies, the work of the loads that do work and the balance's error (J),
//! and the Newton iterations of the last step.

use super::Body;
use super::params::BodyParams;
use super::step::Kinematics;
use crate::contract::{Port, PortKind};

const AXES: [&str; 3] = ["x", "y", "z"];

/// The outputs after the fairleads' (name, unit of measure).
const EXTRA_OUTPUTS: [(&str, &str); 5] = [
    ("kinetic_energy", "J"),
    ("potential_energy", "J"),
    ("work", "J"),
    ("energy_error", "J"),
    ("newton_iterations", ""),
];

/// How many outputs come before the fairleads'.
const POSE_OUTPUTS: usize = 12;

pub(super) fn inputs(p: &BodyParams) -> Vec<Port> {
    let mut out = Vec::new();
    for f in &p.fairleads {
        for a in AXES {
            out.push(Port::input(
                &format!("{}_force_{a}", f.name),
                PortKind::Force,
            ));
        }
    }
    for a in AXES {
        out.push(Port::input(&format!("force_{a}"), PortKind::Force));
    }
    for a in AXES {
        out.push(Port::input(&format!("moment_{a}"), PortKind::Moment));
    }
    out
}

pub(super) fn outputs(p: &BodyParams) -> Vec<Port> {
    let mut out: Vec<Port> = AXES
        .iter()
        .map(|a| Port::output(a, PortKind::Displacement))
        .collect();
    for angle in ["roll", "pitch", "yaw"] {
        out.push(Port::output(angle, PortKind::Rotation));
    }
    for a in AXES {
        out.push(Port::output(&format!("velocity_{a}"), PortKind::Velocity));
    }
    for a in AXES {
        out.push(
            Port::output(&format!("angular_velocity_{a}"), PortKind::Generic).with_unit("rad/s"),
        );
    }
    for f in &p.fairleads {
        for a in AXES {
            out.push(Port::output(
                &format!("{}_position_{a}", f.name),
                PortKind::Displacement,
            ));
        }
        for a in AXES {
            out.push(Port::output(
                &format!("{}_velocity_{a}", f.name),
                PortKind::Velocity,
            ));
        }
        for a in AXES {
            out.push(
                Port::output(&format!("{}_acceleration_{a}", f.name), PortKind::Generic)
                    .with_unit("m/s2"),
            );
        }
    }
    for (name, unit) in EXTRA_OUTPUTS {
        out.push(Port::output(name, PortKind::Generic).with_unit(unit));
    }
    out
}

/// The outputs of `body` at kinematics `k` into `out`.
pub(super) fn write_outputs(body: &Body, k: &Kinematics, out: &mut [f64]) {
    let i = write_motion(body, k, out);
    let [kinetic, potential] = body.model.energies(&k.motion);
    let s = &body.state;
    let error = kinetic + potential - s.initial_energy - s.work;
    out[i..i + 5].copy_from_slice(&[
        kinetic,
        potential,
        s.work,
        error,
        f64::from(s.newton_iterations),
    ]);
}

/// The pose, velocity and fairlead outputs at kinematics `k` into `out`
/// (what the step Jacobian differentiates); returns the index of the first
/// output after them.
pub(super) fn write_motion(body: &Body, k: &Kinematics, out: &mut [f64]) -> usize {
    let model = &body.model;
    let m = &k.motion;
    let eta = model.displacement(m);
    out[..3].copy_from_slice(m.position.as_slice());
    out[3..6].copy_from_slice(&eta.as_slice()[3..]);
    out[6..12].copy_from_slice(m.velocity.as_slice());
    let mut i = POSE_OUTPUTS;
    for p in &model.fairleads {
        for v in model.point(m, &k.acceleration, p) {
            out[i..i + 3].copy_from_slice(v.as_slice());
            i += 3;
        }
    }
    i
}

/// Marks the energy and iteration rows of a step Jacobian unknown (NaN):
/// they depend on the step's history, not only its end.
pub(super) fn clear_energy_rows(body: &Body, jacobian: &mut [f64], n_in: usize) {
    let first = POSE_OUTPUTS + 9 * body.model.fairleads.len();
    jacobian[first * n_in..].fill(f64::NAN);
}
