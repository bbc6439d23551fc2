//! A single mass on a spring and damper to ground, coupled to a neighbour either
//! through a coupling spring-damper (inputs: the neighbour's displacement and
//! velocity) or through an interface force (input: the force).
//!
//! It is the building block of the coupling benchmarks B1-B3: two such units make
//! a two-mass chain cut at the coupling spring (displacement/displacement coupling)
//! or cut at a mass (force/displacement coupling). Integrated with Newmark average
//! acceleration, optionally with several sub-steps per synchronisation step.

use crate::contract::StateSlot;
use crate::contract::Time;
use crate::contract::{
    Capabilities, StepReport, Unit, UnitDescription, UnitError, require_finite,
    require_non_negative, require_positive,
};
use crate::contract::{Hold, Inputs, Port, PortKind, StateVector};
use crate::integrators::newmark::{LinearNewmark, NewmarkState};
use nalgebra::{DMatrix, DVector};
use serde::Deserialize;

/// How the oscillator is tied to its neighbour.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Coupling {
    /// Through a spring-damper (`coupling_stiffness`, `coupling_damping`) whose other
    /// end moves with the inputs `coupling_displacement` and `coupling_velocity`;
    /// output `coupling_force` is the force the spring exerts on the neighbour.
    #[default]
    Spring,
    /// Through the input `force` (N) acting on the mass.
    Force,
}

/// Parameters of an oscillator unit (scene kind `oscillator`).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OscillatorParams {
    /// Mass (kg), > 0.
    pub mass: f64,
    /// Stiffness of the spring to ground (N/m), default 0.
    #[serde(default)]
    pub stiffness: f64,
    /// Damping coefficient to ground (N s/m), default 0.
    #[serde(default)]
    pub damping: f64,
    /// `spring` (default) or `force`.
    #[serde(default)]
    pub coupling: Coupling,
    /// Coupling spring stiffness (N/m), `spring` coupling only, default 0.
    #[serde(default)]
    pub coupling_stiffness: f64,
    /// Coupling damper coefficient (N s/m), `spring` coupling only, default 0.
    #[serde(default)]
    pub coupling_damping: f64,
    /// Initial displacement (m), default 0.
    #[serde(default)]
    pub initial_displacement: f64,
    /// Initial velocity (m/s), default 0.
    #[serde(default)]
    pub initial_velocity: f64,
    /// Newmark sub-steps per synchronisation step, default 1.
    #[serde(default = "one")]
    pub substeps: u32,
}

fn one() -> u32 {
    1
}

impl OscillatorParams {
    /// Checks every parameter, naming the first bad one.
    pub fn validate(&self) -> Result<(), UnitError> {
        require_positive("mass", self.mass)?;
        require_non_negative("stiffness", self.stiffness)?;
        require_non_negative("damping", self.damping)?;
        require_non_negative("coupling_stiffness", self.coupling_stiffness)?;
        require_non_negative("coupling_damping", self.coupling_damping)?;
        require_finite("initial_displacement", self.initial_displacement)?;
        require_finite("initial_velocity", self.initial_velocity)?;
        if self.substeps == 0 {
            return Err(UnitError::parameter("substeps", 0, "expected at least 1"));
        }
        if self.coupling == Coupling::Force
            && (self.coupling_stiffness != 0.0 || self.coupling_damping != 0.0)
        {
            return Err(UnitError::parameter(
                "coupling_stiffness",
                self.coupling_stiffness,
                "coupling_stiffness and coupling_damping apply to `coupling = \"spring\"` only",
            ));
        }
        Ok(())
    }
}

crate::state_struct! {
    /// Everything that changes while stepping.
    #[derive(Debug, serde::Serialize, serde::Deserialize)]
    struct OscillatorState {
        motion: NewmarkState,
    }
}

/// The oscillator unit.
pub struct Oscillator {
    params: OscillatorParams,
    description: UnitDescription,
    integrator: LinearNewmark,
    state: OscillatorState,
    load: DVector<f64>,
    /// Scratch: the motion's derivative with respect to one end input.
    tangent: NewmarkState,
    /// The last step's local displacement error estimate (m).
    local_error: f64,
}

impl Oscillator {
    /// Builds the unit; fails with the first invalid parameter.
    pub fn new(params: OscillatorParams) -> Result<Oscillator, UnitError> {
        params.validate()?;
        // The spring-damper's force follows the other end's displacement, and
        // its velocity where the coupling damps.
        let spring_inputs: Vec<usize> = if params.coupling_damping != 0.0 {
            vec![0, 1]
        } else {
            vec![0]
        };
        let (inputs, outputs) = match params.coupling {
            Coupling::Spring => (
                vec![
                    Port::input("coupling_displacement", PortKind::Displacement),
                    Port::input("coupling_velocity", PortKind::Velocity),
                ],
                vec![
                    Port::output("displacement", PortKind::Displacement),
                    Port::output("velocity", PortKind::Velocity),
                    Port::output("coupling_force", PortKind::Force)
                        .with_feedthrough(&spring_inputs),
                ],
            ),
            Coupling::Force => (
                vec![Port::input("force", PortKind::Force)],
                vec![
                    Port::output("displacement", PortKind::Displacement),
                    Port::output("velocity", PortKind::Velocity),
                ],
            ),
        };
        let (kc, dc) = match params.coupling {
            Coupling::Spring => (params.coupling_stiffness, params.coupling_damping),
            Coupling::Force => (0.0, 0.0),
        };
        let scalar = |x: f64| DMatrix::from_element(1, 1, x);
        let integrator = LinearNewmark::new(
            scalar(params.mass),
            scalar(params.damping + dc),
            scalar(params.stiffness + kc),
            1.0,
        )?;
        let state = OscillatorState {
            motion: NewmarkState {
                u: StateVector(DVector::from_element(1, params.initial_displacement)),
                v: StateVector(DVector::from_element(1, params.initial_velocity)),
                a: StateVector(DVector::zeros(1)),
            },
        };
        Ok(Oscillator {
            description: UnitDescription {
                kind: "oscillator".into(),
                inputs,
                outputs,
                capabilities: Capabilities {
                    step_jacobian: true,
                    ..Capabilities::default()
                },
            },
            tangent: state.motion.clone(),
            local_error: 0.0,
            params,
            integrator,
            state,
            load: DVector::zeros(1),
        })
    }

    /// The external load on the mass (N) at fraction `s` of the step.
    fn load_at(&self, inputs: Inputs<'_>, s: f64) -> f64 {
        match self.params.coupling {
            Coupling::Spring => {
                self.params.coupling_stiffness * inputs.at(0, s)
                    + self.params.coupling_damping * inputs.at(1, s)
            }
            Coupling::Force => inputs.at(0, s),
        }
    }

    /// d load / d (end value of input `port`) at fraction `s` of the step.
    fn load_derivative(&self, inputs: Inputs<'_>, port: usize, s: f64) -> f64 {
        let weight = match inputs.hold(port) {
            Hold::ZeroOrder => 1.0,
            Hold::Ramp => s,
        };
        weight
            * match (self.params.coupling, port) {
                (Coupling::Spring, 0) => self.params.coupling_stiffness,
                (Coupling::Spring, _) => self.params.coupling_damping,
                (Coupling::Force, _) => 1.0,
            }
    }
}

impl Unit for Oscillator {
    fn description(&self) -> &UnitDescription {
        &self.description
    }

    fn initialize(&mut self, _t0: Time, inputs: Inputs<'_>) -> Result<(), UnitError> {
        let f = DVector::from_element(1, self.load_at(inputs, 1.0));
        self.state.motion = self.integrator.initial_state(
            DVector::from_element(1, self.params.initial_displacement),
            DVector::from_element(1, self.params.initial_velocity),
            &f,
        )?;
        Ok(())
    }

    fn do_step(&mut self, _t: Time, h: Time, inputs: Inputs<'_>) -> Result<StepReport, UnitError> {
        let n = self.params.substeps;
        let h_sub = h.as_secs() / f64::from(n);
        self.integrator.set_step_size(h_sub)?;
        self.local_error = 0.0;
        for i in 1..=n {
            self.load[0] = self.load_at(inputs, f64::from(i) / f64::from(n));
            let a0 = self.state.motion.a[0];
            self.integrator.step(&mut self.state.motion, &self.load);
            // Zienkiewicz-Xie, beta = 1/4: h^2 (beta - 1/6) |a1 - a0| per
            // sub-step, summed over the step.
            self.local_error += h_sub * h_sub / 12.0 * (self.state.motion.a[0] - a0).abs();
        }
        Ok(StepReport::default())
    }

    fn outputs(&self, inputs: Inputs<'_>, out: &mut [f64]) {
        let (u, v) = (self.state.motion.u[0], self.state.motion.v[0]);
        out[0] = u;
        out[1] = v;
        if self.params.coupling == Coupling::Spring {
            let inputs = inputs.end();
            out[2] = self.params.coupling_stiffness * (u - inputs[0])
                + self.params.coupling_damping * (v - inputs[1]);
        }
    }

    fn save_state(&self, slot: &mut StateSlot) -> Result<(), UnitError> {
        slot.store(&self.state);
        Ok(())
    }

    fn local_error(&self) -> Option<f64> {
        Some(self.local_error)
    }

    /// Exact: the Newmark step is linear in the state and the load, so the
    /// derivative of the motion follows the same sub-steps from zero with the
    /// load's derivative.
    fn step_jacobian(&mut self, inputs: Inputs<'_>, jacobian: &mut [f64]) -> Result<(), UnitError> {
        let n = self.params.substeps;
        let n_in = inputs.len();
        for j in 0..n_in {
            for x in [
                &mut self.tangent.u,
                &mut self.tangent.v,
                &mut self.tangent.a,
            ] {
                x.fill(0.0);
            }
            for i in 1..=n {
                self.load[0] = self.load_derivative(inputs, j, f64::from(i) / f64::from(n));
                self.integrator.step(&mut self.tangent, &self.load);
            }
            let (du, dv) = (self.tangent.u[0], self.tangent.v[0]);
            jacobian[j] = du;
            jacobian[n_in + j] = dv;
            if self.params.coupling == Coupling::Spring {
                let (kc, dc) = (self.params.coupling_stiffness, self.params.coupling_damping);
                let direct = if j == 0 { kc } else { dc };
                jacobian[2 * n_in + j] = kc * du + dc * dv - direct;
            }
        }
        Ok(())
    }

    fn restore_state(&mut self, slot: &StateSlot) -> Result<(), UnitError> {
        self.state.clone_from(&*slot.load::<OscillatorState>()?);
        Ok(())
    }
}
