//! A section as its linearised static response at its free end (scene kind
//! `static_section`): the end force and moment, and the reaction at the
//! section's held start, change with the end's motion through constant
//! stiffnesses found about an equilibrium; no mass, no damping. It is the
//! cheapest model of a laid pipe resting on the seabed below the touchdown
//! region (the structure generator's `static` fidelity finds its stiffnesses
//! from the nonlinear section's own static solves) and is valid while the
//! section keeps its contact state and its motion stays small.
//!
//! Inputs: the end's velocity (x, z, angular), integrated by the trapezoidal
//! rule; or, with `force_input`, the force and moment applied on the end, which
//! it follows through the inverse of its stiffness (the section then holds its
//! neighbour rather than following it). Outputs: the force and moment the end exerts on what holds it, the
//! reaction at the start, and the end's displacement from the equilibrium.

use crate::contract::{
    Capabilities, Inputs, Port, PortKind, StepReport, Time, Unit, UnitDescription, UnitError,
    require_finite,
};
use serde::{Deserialize, Serialize};

/// Parameters (SI units; rows are outputs, columns the end's x, z and rotation).
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct StaticSectionParams {
    /// d(end force x, z, moment) / d(end x, z, rotation) (N/m, N/rad, N m/m, N m/rad).
    pub stiffness: [[f64; 3]; 3],
    /// End force x, z (N) and moment (N m) in the equilibrium.
    pub force: [f64; 3],
    /// d(start reaction x, z) / d(end x, z, rotation).
    #[serde(default)]
    pub start_stiffness: [[f64; 3]; 2],
    /// Start reaction x, z (N) in the equilibrium.
    #[serde(default)]
    pub start_force: [f64; 2],
    /// The end takes the force x, z (N) and moment (N m) applied on it as
    /// inputs and moves by the compliance (the stiffness's inverse) instead of
    /// following velocity inputs.
    #[serde(default)]
    pub force_input: bool,
    /// Further outputs linear in the end's displacement (e.g. the touchdown
    /// point and the sag-bend moment of the section's static solves).
    #[serde(default)]
    pub quantities: Vec<Linearised>,
}

/// An output linear in the end's displacement u: value + gradient . u.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Linearised {
    /// The output's name.
    pub name: String,
    /// Its unit of measure ("m", "N.m", ...).
    #[serde(default)]
    pub unit: String,
    /// Its value in the equilibrium.
    pub value: f64,
    /// d(value) / d(end x, z, rotation).
    pub gradient: [f64; 3],
}

impl StaticSectionParams {
    fn validate(&self) -> Result<(), UnitError> {
        let values = self
            .stiffness
            .iter()
            .flatten()
            .chain(&self.force)
            .chain(self.start_stiffness.iter().flatten())
            .chain(&self.start_force)
            .chain(
                self.quantities
                    .iter()
                    .flat_map(|q| q.gradient.iter().chain([&q.value])),
            );
        for &v in values {
            require_finite("stiffness, force, start_stiffness, start_force", v)?;
        }
        Ok(())
    }
}

crate::state_struct! {
    /// The end's displacement from the equilibrium (m, m, rad).
    #[derive(Debug, serde::Serialize, serde::Deserialize)]
    struct StaticSectionState {
        displacement: [f64; 3],
    }
}

/// The unit.
pub struct StaticSection {
    params: StaticSectionParams,
    description: UnitDescription,
    state: StaticSectionState,
    /// The stiffness's inverse (m/N, rad/(N m), ...) when the end takes forces.
    compliance: Option<[[f64; 3]; 3]>,
    /// The length of the last step (s), for its Jacobian.
    last_step: f64,
}

const OUTPUTS: [(&str, PortKind); 8] = [
    ("end_force_x", PortKind::Force),
    ("end_force_z", PortKind::Force),
    ("end_moment", PortKind::Moment),
    ("start_force_x", PortKind::Force),
    ("start_force_z", PortKind::Force),
    ("end_displacement_x", PortKind::Displacement),
    ("end_displacement_z", PortKind::Displacement),
    ("end_rotation", PortKind::Rotation),
];

impl StaticSection {
    /// Builds the unit; fails on a non-finite parameter.
    pub fn new(params: StaticSectionParams) -> Result<StaticSection, UnitError> {
        params.validate()?;
        let compliance = params
            .force_input
            .then(|| inverse(&params.stiffness))
            .transpose()?;
        let inputs = if params.force_input {
            vec![
                Port::input("end_force_x", PortKind::Force),
                Port::input("end_force_z", PortKind::Force),
                Port::input("end_moment", PortKind::Moment),
            ]
        } else {
            vec![
                Port::input("end_velocity_x", PortKind::Velocity),
                Port::input("end_velocity_z", PortKind::Velocity),
                Port::input("end_angular_velocity", PortKind::Generic).with_unit("rad/s"),
            ]
        };
        // Every output is linear in the end displacement (a row of it).
        let identity = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let rows = params.stiffness.iter().chain(&params.start_stiffness);
        let mut outputs: Vec<Port> = OUTPUTS
            .iter()
            .zip(rows.chain(&identity))
            .enumerate()
            .map(|(k, ((name, kind), row))| {
                let depends_on = match compliance {
                    // The end force is its input reversed (see `outputs`).
                    Some(_) if k < 3 => vec![k],
                    _ => direct(row, compliance.as_ref()),
                };
                Port::output(name, *kind).with_feedthrough(&depends_on)
            })
            .collect();
        for q in &params.quantities {
            outputs.push(
                Port::output(&q.name, PortKind::Generic)
                    .with_unit(&q.unit)
                    .with_feedthrough(&direct(&q.gradient, compliance.as_ref())),
            );
        }
        Ok(StaticSection {
            params,
            description: UnitDescription {
                kind: "static_section".into(),
                inputs,
                outputs,
                capabilities: Capabilities {
                    step_jacobian: true,
                    step_correction: true,
                    ..Capabilities::default()
                },
            },
            state: StaticSectionState {
                displacement: [0.0; 3],
            },
            compliance,
            last_step: 0.0,
        })
    }

    /// The end's displacement from the equilibrium under the force inputs (the
    /// end exerts what is applied on it, reversed), when it takes forces.
    /// d displacement_k / d end velocity k over the last step (s): the
    /// trapezoidal rule's share of the end value (all of it under a
    /// zero-order hold, which holds the end value over the step).
    fn velocity_share(&self, inputs: &Inputs<'_>, k: usize) -> f64 {
        let start = match inputs.hold(k) {
            crate::contract::Hold::ZeroOrder => 1.0,
            crate::contract::Hold::Ramp => 0.0,
        };
        0.5 * self.last_step * (start + 1.0)
    }

    fn yielded(&self, inputs: Inputs<'_>) -> Option<[f64; 3]> {
        let c = self.compliance.as_ref()?;
        let f = inputs.end();
        let excess: [f64; 3] = std::array::from_fn(|k| -f[k] - self.params.force[k]);
        Some(std::array::from_fn(|i| {
            (0..3).map(|j| c[i][j] * excess[j]).sum::<f64>()
        }))
    }
}

/// The inputs an output `row . u` follows at a communication point: none when
/// the end moves with velocities (the displacement changes through a step),
/// else those its row reaches through the compliance (`u = C (-f - f0)`),
/// round-off (below 1e-9 of the row's largest term) left out.
fn direct(row: &[f64; 3], compliance: Option<&[[f64; 3]; 3]>) -> Vec<usize> {
    let Some(c) = compliance else {
        return Vec::new();
    };
    let gain: [f64; 3] = std::array::from_fn(|j| (0..3).map(|i| row[i] * c[i][j]).sum());
    let largest = gain.iter().fold(0.0f64, |m, g| m.max(g.abs()));
    (0..3).filter(|&j| gain[j].abs() > 1e-9 * largest).collect()
}

/// The inverse of a 3x3 matrix by cofactors; an error when it is singular.
fn inverse(k: &[[f64; 3]; 3]) -> Result<[[f64; 3]; 3], UnitError> {
    let cof = |i: usize, j: usize| {
        let (r0, r1) = ((i + 1) % 3, (i + 2) % 3);
        let (c0, c1) = ((j + 1) % 3, (j + 2) % 3);
        k[r0][c0] * k[r1][c1] - k[r0][c1] * k[r1][c0]
    };
    let det: f64 = (0..3).map(|j| k[0][j] * cof(0, j)).sum();
    let scale = k.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    if det.abs() <= 1e-12 * scale.powi(3) || !det.is_finite() {
        return Err(UnitError::parameter(
            "stiffness",
            det,
            "a nonsingular stiffness when the end takes forces (force_input)",
        ));
    }
    Ok(std::array::from_fn(|i| {
        std::array::from_fn(|j| cof(j, i) / det)
    }))
}

impl Unit for StaticSection {
    fn description(&self) -> &UnitDescription {
        &self.description
    }

    fn initialize(&mut self, _t0: Time, inputs: Inputs<'_>) -> Result<(), UnitError> {
        self.state.displacement = self.yielded(inputs).unwrap_or([0.0; 3]);
        Ok(())
    }

    fn do_step(&mut self, _t: Time, h: Time, inputs: Inputs<'_>) -> Result<StepReport, UnitError> {
        if let Some(d) = self.yielded(inputs) {
            self.state.displacement = d;
            return Ok(StepReport::default());
        }
        let h = h.as_secs();
        self.last_step = h;
        for (k, u) in self.state.displacement.iter_mut().enumerate() {
            *u += 0.5 * h * (inputs.at(k, 0.0) + inputs.at(k, 1.0));
        }
        Ok(StepReport::default())
    }

    fn outputs(&self, inputs: Inputs<'_>, out: &mut [f64]) {
        let yielded = self.yielded(inputs);
        let u = yielded.as_ref().unwrap_or(&self.state.displacement);
        let dot = |row: &[f64; 3]| row.iter().zip(u).map(|(k, u)| k * u).sum::<f64>();
        let p = &self.params;
        // Under force inputs the end exerts what is applied on it, reversed
        // (f0 + K C (-f - f0) = -f): exactly, not through K C's round-off.
        let given = if yielded.is_some() {
            for (o, f) in out[..3].iter_mut().zip(inputs.end()) {
                *o = -f;
            }
            3
        } else {
            0
        };
        let rows = p.stiffness.iter().chain(&p.start_stiffness);
        let at_rest = p.force.iter().chain(&p.start_force);
        for ((o, row), f0) in out[..5].iter_mut().zip(rows).zip(at_rest).skip(given) {
            *o = f0 + dot(row);
        }
        out[5..8].copy_from_slice(u);
        for (o, q) in out[8..].iter_mut().zip(&p.quantities) {
            *o = q.value + dot(&q.gradient);
        }
    }

    slender_contract::state_in_field!(state: StaticSectionState);

    /// Exact, as its Jacobian: under force inputs the displacement is the
    /// compliance's (taken from the moved inputs), under velocities it moves
    /// by the trapezoidal rule's share of the end velocity's change.
    fn correct_step(&mut self, inputs: Inputs<'_>, change: &[f64]) -> Result<(), UnitError> {
        if let Some(d) = self.yielded(inputs) {
            self.state.displacement = d;
            return Ok(());
        }
        let shares: [f64; 3] = std::array::from_fn(|k| self.velocity_share(&inputs, k));
        for ((u, share), du) in self.state.displacement.iter_mut().zip(shares).zip(change) {
            *u += share * du;
        }
        Ok(())
    }

    /// Exact: the displacement is linear in the end inputs (the compliance, or
    /// the trapezoidal rule over the last step), every output linear in it.
    fn step_jacobian(&mut self, inputs: Inputs<'_>, jacobian: &mut [f64]) -> Result<(), UnitError> {
        // d displacement_i / d end input j.
        let mut du = [[0.0; 3]; 3];
        match &self.compliance {
            Some(c) => du = c.map(|row| row.map(|v| -v)),
            None => {
                for (k, row) in du.iter_mut().enumerate() {
                    row[k] = self.velocity_share(&inputs, k);
                }
            }
        }
        let p = &self.params;
        let gradients = p
            .stiffness
            .iter()
            .chain(&p.start_stiffness)
            .chain([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]].iter())
            .chain(p.quantities.iter().map(|q| &q.gradient));
        for (row, g) in jacobian.chunks_exact_mut(3).zip(gradients) {
            for (j, d) in row.iter_mut().enumerate() {
                *d = (0..3).map(|i| g[i] * du[i][j]).sum();
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contract::Driver;

    #[test]
    fn the_end_force_follows_the_integrated_motion_through_the_stiffness() {
        let params = StaticSectionParams {
            stiffness: [[2.0, 0.0, 0.0], [0.0, 3.0, 1.0], [0.0, 1.0, 5.0]],
            force: [10.0, 20.0, 30.0],
            start_stiffness: [[-2.0, 0.0, 0.0], [0.0, -3.0, 0.0]],
            start_force: [-10.0, 5.0],
            force_input: false,
            quantities: vec![],
        };
        let mut unit = Driver::new(StaticSection::new(params).unwrap());
        // 0.5 m/s in x and 0.1 rad/s from the start, for 2 s.
        unit.set_inputs(&[0.5, 0.0, 0.1]).unwrap();
        unit.initialize(Time::ZERO).unwrap();
        let mut out = [0.0; 8];
        unit.outputs(&mut out).unwrap();
        assert_eq!(&out[..5], &[10.0, 20.0, 30.0, -10.0, 5.0]);
        let h = Time::from_secs(0.5).unwrap();
        for k in 0..4 {
            let t = Time::from_secs(0.5 * k as f64).unwrap();
            unit.do_step(t, h).unwrap();
        }
        unit.outputs(&mut out).unwrap();
        let expect = [12.0, 20.2, 31.0, -12.0, 5.0, 1.0, 0.0, 0.2];
        for (o, e) in out.iter().zip(expect) {
            assert!((o - e).abs() < 1e-12, "{out:?}");
        }
    }

    #[test]
    fn a_loaded_end_moves_by_the_compliance_and_exerts_what_it_carries() {
        let params = StaticSectionParams {
            stiffness: [[2.0, 0.5, 0.0], [0.5, 3.0, 1.0], [0.0, 1.0, 5.0]],
            force: [10.0, 20.0, 30.0],
            start_stiffness: [[-2.0, 0.0, 0.0], [0.0, -3.0, 0.0]],
            start_force: [-10.0, 5.0],
            force_input: true,
            quantities: vec![],
        };
        let mut unit = Driver::new(StaticSection::new(params).unwrap());
        // Applied: the equilibrium's force reversed, plus (1, -2, 0.5).
        let applied = [-10.0 + 1.0, -20.0 - 2.0, -30.0 + 0.5];
        unit.set_inputs(&applied).unwrap();
        unit.initialize(Time::ZERO).unwrap();
        let mut out = [0.0; 8];
        unit.outputs(&mut out).unwrap();
        for k in 0..3 {
            assert!((out[k] + applied[k]).abs() < 1e-12, "{out:?}");
        }
        // K u = -(1, -2, 0.5).
        let u = &out[5..8];
        let k = [[2.0, 0.5, 0.0], [0.5, 3.0, 1.0], [0.0, 1.0, 5.0]];
        let target = [-1.0, 2.0, -0.5];
        for i in 0..3 {
            let ku: f64 = (0..3).map(|j| k[i][j] * u[j]).sum();
            assert!((ku - target[i]).abs() < 1e-12, "{u:?}");
        }
        assert!((out[3] - (-10.0 - 2.0 * u[0])).abs() < 1e-12);
        let singular = StaticSectionParams {
            stiffness: [[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 0.0, 1.0]],
            force: [0.0; 3],
            start_stiffness: [[0.0; 3]; 2],
            start_force: [0.0; 2],
            force_input: true,
            quantities: vec![],
        };
        let e = StaticSection::new(singular).err().unwrap().to_string();
        assert!(e.contains("force_input"), "{e}");
    }
}
