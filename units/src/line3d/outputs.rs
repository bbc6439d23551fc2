//! The 3D line's ports and fields: per end its position, velocity and the
//! force it exerts on what holds it (x, y, z); then the top's tension, angle
//! from the vertical and azimuth, the touchdown point, the largest tension,
//! curvature and bending moment, the energies and the Newton iterations; and
//! along the line the node positions, the element tensions and the nodes'
//! curvature (FMI 3.0 array outputs).

use super::mechanics::{DOF, node};
use super::params::{EndCondition, Line3dParams};
use super::step::FRICTION;
use super::{Line3d, SIDES};
use crate::contract::{Field, Inputs, Port, PortKind, UnitError};

pub(super) const AXES: [&str; 3] = ["x", "y", "z"];

/// How many of [`EXTRA_OUTPUTS`] the catenary section has too (its first).
pub(super) const CATENARY_OUTPUTS: usize = 8;

/// The outputs after the ends' (name, unit of measure).
pub(super) const EXTRA_OUTPUTS: [(&str, &str); 17] = [
    ("end_tension", "N"),
    ("end_angle_from_vertical", "deg"),
    ("end_azimuth", "deg"),
    ("start_tension", "N"),
    ("touchdown_arc", "m"),
    ("touchdown_x", "m"),
    ("touchdown_y", "m"),
    ("largest_tension", "N"),
    ("largest_curvature", "1/m"),
    ("largest_moment", "N.m"),
    ("kinetic_energy", "J"),
    ("strain_energy", "J"),
    ("potential_energy", "J"),
    ("external_work", "J"),
    ("friction_work", "J"),
    ("energy_error", "J"),
    ("newton_iterations", ""),
];

/// Per end with coupled inputs: its three velocities or forces.
pub(super) fn input_ports(p: &Line3dParams) -> Vec<Port> {
    let mut out = Vec::new();
    for (side, end) in SIDES.iter().zip([&p.start, &p.end]) {
        let (what, kind) = match end.condition {
            EndCondition::Velocity => ("velocity", PortKind::Velocity),
            EndCondition::Force => ("force", PortKind::Force),
            _ => continue,
        };
        for axis in AXES {
            out.push(Port::input(&format!("{side}_{what}_{axis}"), kind));
        }
    }
    out
}

/// Per end: position, velocity and force x, y, z (a loaded end's force is its
/// input reversed: a direct dependency); then [`EXTRA_OUTPUTS`].
pub(super) fn output_ports(p: &Line3dParams, first_input: &[Option<usize>; 2]) -> Vec<Port> {
    let mut out = Vec::new();
    for (k, side) in SIDES.iter().enumerate() {
        let end = if k == 0 { &p.start } else { &p.end };
        for axis in AXES {
            out.push(Port::output(
                &format!("{side}_position_{axis}"),
                PortKind::Displacement,
            ));
        }
        for axis in AXES {
            out.push(Port::output(
                &format!("{side}_velocity_{axis}"),
                PortKind::Velocity,
            ));
        }
        for (c, axis) in AXES.iter().enumerate() {
            let port = Port::output(&format!("{side}_force_{axis}"), PortKind::Force);
            out.push(match (end.condition, first_input[k]) {
                (EndCondition::Force, Some(first)) => port.with_feedthrough(&[first + c]),
                _ => port,
            });
        }
    }
    for (name, unit) in EXTRA_OUTPUTS {
        let kind = match unit {
            "N" => PortKind::Force,
            "N.m" => PortKind::Moment,
            _ => PortKind::Generic,
        };
        let port = Port::output(name, kind);
        out.push(if kind == PortKind::Generic {
            port.with_unit(unit)
        } else {
            port
        });
    }
    out
}

impl Line3d {
    /// All outputs at the current time, in port order.
    pub(super) fn write_outputs(&self, _inputs: &Inputs<'_>, out: &mut [f64]) {
        let (q, v) = (&self.state.q, &self.state.v);
        let last = self.mechanics.nodes - 1;
        for (k, i) in [0, last].into_iter().enumerate() {
            let base = 9 * k;
            out[base..base + 3].copy_from_slice(&q[DOF * i..DOF * i + DOF]);
            out[base + 3..base + 6].copy_from_slice(&v[DOF * i..DOF * i + DOF]);
            out[base + 6..base + 9].copy_from_slice(&self.state.reaction[DOF * k..DOF * k + DOF]);
        }
        let top = nalgebra::Vector3::from_column_slice(&self.state.reaction[3..6]);
        let start = nalgebra::Vector3::from_column_slice(&self.state.reaction[..3]);
        let tension = top.norm();
        let (angle, azimuth) = if tension > 0.0 {
            (
                (-top.z / tension).clamp(-1.0, 1.0).acos().to_degrees(),
                top.y.atan2(top.x).to_degrees(),
            )
        } else {
            (0.0, 0.0)
        };
        let (arc, plan) = self.touchdown();
        let [largest_tension, largest_curvature] = self.largest();
        let [kinetic, strain, potential] = self.energies();
        let ledger = &self.state.ledger;
        let work: f64 = ledger.work.iter().sum();
        let extra = [
            tension,
            angle,
            azimuth,
            start.norm(),
            arc,
            plan[0],
            plan[1],
            largest_tension,
            largest_curvature,
            self.params.bending_stiffness * largest_curvature,
            kinetic,
            strain,
            potential,
            work,
            ledger.work[FRICTION],
            kinetic + strain + potential - ledger.initial - work,
            f64::from(self.state.newton_iterations),
        ];
        out[18..18 + extra.len()].copy_from_slice(&extra);
    }

    /// Arc (m, unstretched, from the start) and plan position (m) of the
    /// touchdown point: the last node in contact with the seabed counted from
    /// the start; 0 and the start's plan position with nothing in contact.
    pub(super) fn touchdown(&self) -> (f64, [f64; 2]) {
        let q = &self.state.q;
        let in_contact = |i: usize| {
            self.environment
                .seabed
                .as_ref()
                .is_some_and(|s| s.height(&node(q, i)) < 0.0)
        };
        let last = (0..self.mechanics.nodes)
            .rev()
            .find(|&i| in_contact(i))
            .unwrap_or(0);
        let arc = if in_contact(last) {
            last as f64 * self.mechanics.element_length
        } else {
            0.0
        };
        (arc, [q[DOF * last], q[DOF * last + 1]])
    }

    /// Largest tension (N) over the elements and curvature (1/m) over the nodes.
    fn largest(&self) -> [f64; 2] {
        let (q, v) = (&self.state.q, &self.state.v);
        let nodes = self.mechanics.nodes;
        let tension = (0..nodes - 1)
            .map(|e| self.mechanics.tension(q, v, e))
            .fold(f64::MIN, f64::max);
        let curvature = (1..nodes - 1)
            .map(|i| self.mechanics.curvature(q, i))
            .fold(0.0, f64::max);
        [tension, curvature]
    }

    /// x, y, z per node, tension per element, curvature per node.
    pub(super) fn field_list(&self) -> Vec<Field> {
        let nodes = self.mechanics.nodes;
        let mut fields: Vec<Field> = AXES
            .iter()
            .map(|a| Field::per_node(a, "m", "position of each node, start first", nodes))
            .collect();
        fields.push(Field::per_element(
            "tension",
            "N",
            "axial force of each element (tension positive), start first",
            nodes - 1,
        ));
        fields.push(Field::per_node(
            "curvature",
            "1/m",
            "curvature at each node (0 at the ends), start first",
            nodes,
        ));
        fields.push(Field::per_node(
            "moment",
            "N.m",
            "bending moment at each node, EI times the curvature (0 at the ends), start first",
            nodes,
        ));
        fields
    }

    /// The current values of field `index` into `out`.
    pub(super) fn write_field(&self, index: usize, out: &mut [f64]) -> Result<(), UnitError> {
        let nodes = self.mechanics.nodes;
        let lengths = [nodes, nodes, nodes, nodes - 1, nodes, nodes];
        let names = ["x", "y", "z", "tension", "curvature", "moment"];
        check_field_request(
            ("a 3D line", "the line"),
            &names,
            &lengths,
            index,
            out.len(),
        )?;
        let len = lengths[index];
        let (q, v) = (&self.state.q, &self.state.v);
        for (k, o) in out.iter_mut().enumerate() {
            *o = match index {
                0..=2 => q[DOF * k + index],
                3 => self.mechanics.tension(q, v, k),
                _ if k == 0 || k + 1 == len => 0.0,
                4 => self.mechanics.curvature(q, k),
                _ => self.params.bending_stiffness * self.mechanics.curvature(q, k),
            };
        }
        Ok(())
    }
}

/// Checks a request for field `index` (of `names`, each `lengths` long) into
/// `room` values, without building the unit's field list (a run's envelopes
/// read the fields every step); `(of, owner)` name the unit in the errors
/// ("a 3D line", "the line").
pub(super) fn check_field_request(
    (of, owner): (&str, &str),
    names: &[&str],
    lengths: &[usize],
    index: usize,
    room: usize,
) -> Result<(), UnitError> {
    let (Some(name), Some(&len)) = (names.get(index), lengths.get(index)) else {
        return Err(UnitError::Unsupported(format!(
            "field {index} of {of} (it has {})",
            names.len()
        )));
    };
    if room != len {
        return Err(UnitError::Numerical(format!(
            "field {name}: {room} values asked for, {owner} has {len}"
        )));
    }
    Ok(())
}
