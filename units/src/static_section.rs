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
//! rule. Outputs: the force and moment the end exerts on what holds it, the
//! reaction at the start, and the end's displacement from the equilibrium.

use crate::contract::{
    Capabilities, Inputs, Port, PortKind, StateSlot, StepReport, Time, Unit, UnitDescription,
    UnitError, require_finite,
};
use serde::Deserialize;

/// Parameters (SI units; rows are outputs, columns the end's x, z and rotation).
#[derive(Clone, Debug, Deserialize)]
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
}

impl StaticSectionParams {
    fn validate(&self) -> Result<(), UnitError> {
        let values = self
            .stiffness
            .iter()
            .flatten()
            .chain(&self.force)
            .chain(self.start_stiffness.iter().flatten())
            .chain(&self.start_force);
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
        let inputs = vec![
            Port::input("end_velocity_x", PortKind::Velocity),
            Port::input("end_velocity_z", PortKind::Velocity),
            Port::input("end_angular_velocity", PortKind::Generic).with_unit("rad/s"),
        ];
        let outputs = OUTPUTS
            .iter()
            .map(|(name, kind)| Port::output(name, *kind))
            .collect();
        Ok(StaticSection {
            params,
            description: UnitDescription {
                kind: "static_section".into(),
                inputs,
                outputs,
                capabilities: Capabilities::default(),
            },
            state: StaticSectionState {
                displacement: [0.0; 3],
            },
        })
    }
}

impl Unit for StaticSection {
    fn description(&self) -> &UnitDescription {
        &self.description
    }

    fn initialize(&mut self, _t0: Time, _inputs: Inputs<'_>) -> Result<(), UnitError> {
        self.state.displacement = [0.0; 3];
        Ok(())
    }

    fn do_step(&mut self, _t: Time, h: Time, inputs: Inputs<'_>) -> Result<StepReport, UnitError> {
        let h = h.as_secs();
        for (k, u) in self.state.displacement.iter_mut().enumerate() {
            *u += 0.5 * h * (inputs.at(k, 0.0) + inputs.at(k, 1.0));
        }
        Ok(StepReport::default())
    }

    fn outputs(&self, _inputs: Inputs<'_>, out: &mut [f64]) {
        let u = &self.state.displacement;
        let dot = |row: &[f64; 3]| row.iter().zip(u).map(|(k, u)| k * u).sum::<f64>();
        let p = &self.params;
        let rows = p.stiffness.iter().chain(&p.start_stiffness);
        let at_rest = p.force.iter().chain(&p.start_force);
        for ((o, row), f0) in out[..5].iter_mut().zip(rows).zip(at_rest) {
            *o = f0 + dot(row);
        }
        out[5..8].copy_from_slice(u);
    }

    fn save_state(&self, slot: &mut StateSlot) -> Result<(), UnitError> {
        slot.store(&self.state);
        Ok(())
    }

    fn restore_state(&mut self, slot: &StateSlot) -> Result<(), UnitError> {
        self.state.clone_from(&*slot.load::<StaticSectionState>()?);
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
}
