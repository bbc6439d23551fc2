//! The ends of a nonlinear section resolved to DOFs, their prescribed motion and
//! loads at a time, and the unit's ports.

use super::params::{DofCondition, Ends, NonlinearParams};
use crate::beam::boundary::TimeFunction;
use crate::contract::{Inputs, Port, PortKind, UnitError, require_finite};

/// Names of the three DOFs of a node, as in port names.
const DOF_NAMES: [&str; 3] = ["x", "z", "rotation"];
const SIDES: [&str; 2] = ["start", "end"];

/// `Resolved::end` of an interior support.
pub const INTERIOR: usize = 2;

/// One end DOF with its condition.
#[derive(Clone, Debug)]
pub struct Resolved {
    /// 0 start, 1 end, [`INTERIOR`] for an interior support.
    pub end: usize,
    /// 0 x, 1 z, 2 rotation.
    pub component: usize,
    /// The DOF's index in the model.
    pub dof: usize,
    /// How it is held or loaded.
    pub condition: DofCondition,
    /// The input port feeding it, if coupled.
    pub input: Option<usize>,
}

impl Resolved {
    /// Whether the DOF's motion is prescribed.
    pub fn is_kinematic(&self) -> bool {
        self.condition.is_kinematic()
    }

    /// Prescribed (q, v, a) at the step's end `t` over a step `h` (0 at the
    /// initial time) from the start state `(q0, v0, a0)` of the DOF; the step runs
    /// over the fractions `(s0, s1)` of the coupling step (a sub-step when the
    /// unit divides it), where coupled inputs are read.
    pub fn motion(
        &self,
        inputs: Inputs<'_>,
        (t, h): (f64, f64),
        (s0, s1): (f64, f64),
        start: [f64; 3],
    ) -> [f64; 3] {
        let [q0, v0, a0] = start;
        match (&self.condition, self.input) {
            (DofCondition::Held, _) => [0.0; 3],
            (DofCondition::Displacement(f), _) => match (f.eval(t), self.input) {
                (Some(v), _) => v,
                (None, Some(i)) if h > 0.0 => {
                    let rate = inputs.rate(i, h / (s1 - s0));
                    [inputs.at(i, s1), rate, (rate - v0) / h]
                }
                (None, Some(i)) => [inputs.at(i, s1), 0.0, 0.0],
                (None, None) => [q0, v0, a0],
            },
            // Trapezoidal rule on the velocity: consistent with Newmark (1/4, 1/2).
            (DofCondition::Velocity | DofCondition::VelocityFrom(_), Some(i)) => {
                let v1 = inputs.at(i, s1);
                if h > 0.0 {
                    [q0 + 0.5 * h * (v0 + v1), v1, 2.0 * (v1 - v0) / h - a0]
                } else if let DofCondition::VelocityFrom(start) = self.condition {
                    // At the start (statics, initial state): its given displacement.
                    [start, v1, a0]
                } else {
                    [q0, v1, a0]
                }
            }
            _ => [q0, v0, a0],
        }
    }

    /// Applied force or moment at `t`, a coupled one read at fraction `s` of the
    /// coupling step (0 for a kinematic condition).
    pub fn load(&self, inputs: Inputs<'_>, t: f64, s: f64) -> f64 {
        match (&self.condition, self.input) {
            (DofCondition::Force(f), input) => match (f.eval(t), input) {
                (Some([v, _, _]), _) => v,
                (None, Some(i)) => inputs.at(i, s),
                (None, None) => 0.0,
            },
            _ => 0.0,
        }
    }
}

/// Every end DOF that is not free, with the input ports of the coupled ones.
pub fn resolve(params: &NonlinearParams, nodes: usize) -> (Vec<Resolved>, Vec<Port>) {
    let mut resolved = Vec::new();
    let mut inputs = Vec::new();
    for (end, side) in SIDES.iter().enumerate() {
        let spec = if end == 0 {
            &params.ends.start
        } else {
            &params.ends.end
        };
        let node = if end == 0 { 0 } else { nodes - 1 };
        for (component, condition) in spec.conditions().into_iter().enumerate() {
            let name = DOF_NAMES[component];
            let rotation = component == 2;
            let port = match &condition {
                DofCondition::Free => continue,
                DofCondition::Held => None,
                DofCondition::Displacement(TimeFunction::Input(_)) => Some(if rotation {
                    Port::input(&format!("{side}_rotation"), PortKind::Rotation)
                } else {
                    Port::input(
                        &format!("{side}_displacement_{name}"),
                        PortKind::Displacement,
                    )
                }),
                DofCondition::Velocity | DofCondition::VelocityFrom(_) => Some(if rotation {
                    Port::input(&format!("{side}_angular_velocity"), PortKind::Generic)
                        .with_unit("rad/s")
                } else {
                    Port::input(&format!("{side}_velocity_{name}"), PortKind::Velocity)
                }),
                DofCondition::Force(TimeFunction::Input(_)) => Some(if rotation {
                    Port::input(&format!("{side}_moment"), PortKind::Moment)
                } else {
                    Port::input(&format!("{side}_force_{name}"), PortKind::Force)
                }),
                _ => None,
            };
            let input = port.map(|p| {
                inputs.push(p);
                inputs.len() - 1
            });
            resolved.push(Resolved {
                end,
                component,
                dof: 3 * node + component,
                condition,
                input,
            });
        }
    }
    for support in &params.supports {
        let Some(node) = params.node_at(support.at) else {
            continue;
        };
        for (component, held) in [support.x, support.z, support.rotation]
            .into_iter()
            .enumerate()
        {
            if held {
                resolved.push(Resolved {
                    end: INTERIOR,
                    component,
                    dof: 3 * node + component,
                    condition: DofCondition::Held,
                    input: None,
                });
            }
        }
    }
    (resolved, inputs)
}

/// Names of the outputs after the end quantities.
pub const EXTRA_OUTPUTS: [(&str, &str); 15] = [
    ("kinetic_energy", "J"),
    ("strain_energy", "J"),
    ("potential_energy", "J"),
    ("newton_iterations", ""),
    ("critical_step", "s"),
    ("touchdown", "m"),
    ("contact_length", "m"),
    ("max_moment", "N.m"),
    ("max_tension", "N"),
    ("sagbend_moment", "N.m"),
    ("overbend_moment", "N.m"),
    ("touchdown_arc", "m"),
    ("touchdown_x", "m"),
    ("external_work", "J"),
    ("energy_error", "J"),
];

/// Per end: position x, z, rotation, velocity x, z, angular velocity, and the force
/// x, z and moment the end exerts on what holds it (a component loaded by a
/// coupled input reports it: its one direct dependency); then the extras;
/// then each end's tension, the magnitude of its force (x, z); then tension,
/// moment, curvature, position x, z and the magnitude of the internal force
/// per station.
pub fn output_ports(resolved: &[Resolved], stations: usize) -> Vec<Port> {
    // A component loaded by a coupled input reports that input.
    let loads_of = |end: usize, components: &[usize]| -> Vec<usize> {
        resolved
            .iter()
            .filter(|r| r.end == end && components.contains(&r.component))
            .filter(|r| matches!(r.condition, DofCondition::Force(_)))
            .filter_map(|r| r.input)
            .collect()
    };
    let mut out = Vec::new();
    for (end, side) in SIDES.iter().enumerate() {
        let loads = |component: usize| loads_of(end, &[component]);
        out.push(Port::output(
            &format!("{side}_position_x"),
            PortKind::Displacement,
        ));
        out.push(Port::output(
            &format!("{side}_position_z"),
            PortKind::Displacement,
        ));
        out.push(Port::output(
            &format!("{side}_rotation"),
            PortKind::Rotation,
        ));
        out.push(Port::output(
            &format!("{side}_velocity_x"),
            PortKind::Velocity,
        ));
        out.push(Port::output(
            &format!("{side}_velocity_z"),
            PortKind::Velocity,
        ));
        out.push(
            Port::output(&format!("{side}_angular_velocity"), PortKind::Generic).with_unit("rad/s"),
        );
        out.push(
            Port::output(&format!("{side}_force_x"), PortKind::Force).with_feedthrough(&loads(0)),
        );
        out.push(
            Port::output(&format!("{side}_force_z"), PortKind::Force).with_feedthrough(&loads(1)),
        );
        out.push(
            Port::output(&format!("{side}_moment"), PortKind::Moment).with_feedthrough(&loads(2)),
        );
    }
    for (name, unit) in EXTRA_OUTPUTS {
        out.push(Port::output(name, PortKind::Generic).with_unit(unit));
    }
    for (end, side) in SIDES.iter().enumerate() {
        let tension = Port::output(&format!("{side}_tension"), PortKind::Force);
        out.push(tension.with_feedthrough(&loads_of(end, &[0, 1])));
    }
    for i in 1..=stations {
        out.push(Port::output(&format!("tension_{i}"), PortKind::Force));
        out.push(Port::output(&format!("moment_{i}"), PortKind::Moment));
        out.push(Port::output(&format!("curvature_{i}"), PortKind::Generic).with_unit("1/m"));
        out.push(Port::output(&format!("x_{i}"), PortKind::Displacement));
        out.push(Port::output(&format!("z_{i}"), PortKind::Displacement));
        out.push(Port::output(&format!("force_{i}"), PortKind::Force));
    }
    out
}

impl Ends {
    /// Checks every end's conditions: a prescribed motion's or load's values
    /// (finite, `fade_in` >= 0: an infinite one removed the motion, a NaN or
    /// negative one left it unfaded) and a starting displacement.
    pub(crate) fn validate(&self) -> Result<(), UnitError> {
        for (side, end) in [("start", &self.start), ("end", &self.end)] {
            for (dof, c) in ["x", "z", "rotation"].iter().zip(end.conditions()) {
                let key = format!("ends.{side}.{dof}");
                match c {
                    DofCondition::VelocityFrom(d) => {
                        require_finite(&format!("{key}.velocity_from"), d)?
                    }
                    DofCondition::Displacement(f) => f.validate(&format!("{key}.displacement"))?,
                    DofCondition::Force(f) => f.validate(&format!("{key}.force"))?,
                    _ => {}
                }
            }
        }
        Ok(())
    }
}
