//! A rigid body in six degrees of freedom (scene kind `body`): a floating
//! platform, a vessel, the physical half of a truncated test. Finite
//! rotations on a unit quaternion; mass and inertia about the centre of
//! gravity, a constant added mass, linear hydrostatic restoring, linear and
//! quadratic damping, a mean load and an external load ([`dynamics`]),
//! stepped by the trapezoidal rule ([`step`]). Named attachment points
//! (fairleads) give their global position, velocity and acceleration as
//! outputs and take the force they receive as inputs, so 3D lines
//! (`line3d`, `catenary3d`) hang from them through the master.
//!
//! Instead of its dynamics a body may follow a prescribed motion (sines per
//! degree of freedom, a time table, a sea through motion RAOs): the fairleads
//! then move the lines as a vessel's motion would, whatever the lines pull.
//!
//! The step Jacobian (outputs after a step by the step's end inputs) comes
//! from the converged step by the implicit function theorem ([`jacobian`]).

pub mod dynamics;
mod jacobian;
pub mod mooring;
pub mod motion_table;
pub mod params;
mod ports;
mod step;
pub mod waves;

#[cfg(test)]
mod tests;
#[cfg(test)]
mod waves_tests;

use crate::contract::{
    Capabilities, HoldSupport, Inputs, StepReport, Time, Unit, UnitDescription, UnitError,
    require_step_jacobian_ready,
};
use crate::signal::series::SineSeries;
use crate::signal::sine::{faded_series, faded_sum};
use dynamics::{Model, Motion, rate_map, rate_map_derivative};
use motion_table::TableMotion;
use nalgebra::{UnitQuaternion, Vector3, Vector6};
pub use params::{BodyParams, Fairlead};
use step::{EndLoads, Kinematics, advance};

crate::state_struct! {
    /// Everything that changes while stepping.
    #[derive(Debug, serde::Serialize, serde::Deserialize)]
    struct BodyState {
        t: f64,
        /// Reference point (m), rotation quaternion (w, i, j, k), velocity
        /// and angular velocity, acceleration and angular acceleration.
        position: [f64; 3],
        rotation: [f64; 4],
        velocity: [f64; 6],
        acceleration: [f64; 6],
        /// Work done on the body by the loads that do work (J), and its
        /// energy at the start (J).
        work: f64,
        initial_energy: f64,
        /// The power of the loads that do work at the current time (W).
        power: f64,
        newton_iterations: u32,
    }
}

/// The unit.
pub struct Body {
    params: BodyParams,
    model: Model,
    description: UnitDescription,
    state: BodyState,
    /// The last step's start kinematics, start time and length (s), and its
    /// end inputs: what its Jacobian is taken from.
    last_start: Option<(Kinematics, f64, f64)>,
    end_inputs: Vec<f64>,
    /// Output buffers of the Jacobian's differences, and its factors
    /// `du1/df` (6 x inputs) and `dy/du1` (outputs x 6).
    plus: Vec<f64>,
    minus: Vec<f64>,
    velocity_by_input: nalgebra::DMatrix<f64>,
    output_by_velocity: nalgebra::DMatrix<f64>,
    /// `velocity_by_input` is of the last step (its Jacobian was taken).
    sensitivity_ready: bool,
    /// What the waves do to the body (made once).
    sea: Sea,
    /// The splines of a prescribed motion table.
    table: Option<TableMotion>,
}

/// The waves' excitation (N, N m) or motion (m, rad) per degree of freedom
/// as sines, faded in over `fade_in` (s).
#[derive(Default)]
struct Sea {
    excitation: Option<[SineSeries; 6]>,
    motion: Option<[SineSeries; 6]>,
    fade_in: f64,
}

impl Sea {
    fn of(p: &BodyParams) -> Sea {
        let Some(waves) = &p.waves else {
            return Sea::default();
        };
        let sines = |t: &Option<waves::RaoTable>| {
            (t.as_ref()).map(|t| t.sines(waves, p.reference).map(|s| SineSeries::new(&s)))
        };
        Sea {
            excitation: sines(&p.force_rao),
            motion: sines(&p.motion_rao),
            fade_in: waves.fade_in,
        }
    }

    /// The excitation at `t` (s): force and moment at the reference point.
    fn excitation(&self, t: f64) -> Vector6<f64> {
        match &self.excitation {
            Some(dofs) => Vector6::from_fn(|i, _| faded_series(0.0, &dofs[i], self.fade_in, t)[0]),
            None => Vector6::zeros(),
        }
    }
}

impl Body {
    /// Builds the body, refusing parameters it cannot use (the error names the key).
    pub fn new(params: BodyParams) -> Result<Body, UnitError> {
        params.validate()?;
        let model = Model::new(&params);
        let description = UnitDescription {
            kind: "body".into(),
            inputs: ports::inputs(&params),
            outputs: ports::outputs(&params),
            capabilities: Capabilities {
                step_jacobian: true,
                step_correction: true,
                // The trapezoidal rule reads the loads at the step's ends
                // only: its start's are the last step's end.
                hold: HoldSupport::Fixed,
                ..Capabilities::default()
            },
        };
        let outputs = description.outputs.len();
        let inputs = description.inputs.len();
        let state = BodyState {
            t: 0.0,
            position: params.reference,
            rotation: [1.0, 0.0, 0.0, 0.0],
            velocity: [0.0; 6],
            acceleration: [0.0; 6],
            work: 0.0,
            initial_energy: 0.0,
            power: 0.0,
            newton_iterations: 0,
        };
        let sea = Sea::of(&params);
        let table = params.motion_table.as_ref().map(|t| t.splines());
        Ok(Body {
            params,
            model,
            description,
            state,
            last_start: None,
            end_inputs: Vec::new(),
            plus: vec![0.0; outputs],
            minus: vec![0.0; outputs],
            velocity_by_input: nalgebra::DMatrix::zeros(6, inputs),
            sensitivity_ready: false,
            output_by_velocity: nalgebra::DMatrix::zeros(outputs, 6),
            sea,
            table,
        })
    }

    /// The body's parameters.
    pub fn params(&self) -> &BodyParams {
        &self.params
    }

    fn kinematics(&self) -> Kinematics {
        let s = &self.state;
        let [w, i, j, k] = s.rotation;
        Kinematics {
            motion: Motion {
                position: Vector3::from(s.position),
                rotation: UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(w, i, j, k)),
                velocity: Vector6::from(s.velocity),
            },
            acceleration: Vector6::from(s.acceleration),
        }
    }

    fn set_kinematics(&mut self, k: &Kinematics) {
        let q = k.motion.rotation.quaternion();
        self.state.position = k.motion.position.into();
        self.state.rotation = [q.w, q.i, q.j, q.k];
        self.state.velocity = k.motion.velocity.into();
        self.state.acceleration = k.acceleration.into();
    }

    /// Whether the body follows a prescribed motion (sines, a table or a
    /// motion RAO).
    fn is_prescribed(&self) -> bool {
        self.params.motion.is_some() || self.sea.motion.is_some() || self.table.is_some()
    }

    /// The prescribed motion at `t` (s): the initial offset, the sines faded
    /// in over `fade_in`, the table's motion, the waves' motion faded in over
    /// theirs.
    fn prescribed(&self, t: f64) -> Kinematics {
        let p = &self.params;
        let mut dof = [[0.0; 3]; 6];
        let add = |d: &mut [f64; 3], more: [f64; 3]| {
            for (x, w) in d.iter_mut().zip(more) {
                *x += w;
            }
        };
        let table = self.table.as_ref().map(|m| m.eval(t));
        for (i, d) in dof.iter_mut().enumerate() {
            let sines = p.motion.as_ref().map_or(&[][..], |m| &m[i]);
            *d = faded_sum(p.initial_offset[i], sines, p.fade_in, t);
            if let Some(sea) = &self.sea.motion {
                add(d, faded_series(0.0, &sea[i], self.sea.fade_in, t));
            }
            if let Some(table) = &table {
                add(d, table[i]);
            }
        }
        let column = |k: usize| Vector3::new(dof[3][k], dof[4][k], dof[5][k]);
        let (angles, rates, second) = (column(0), column(1), column(2));
        let map = rate_map(angles.y, angles.z);
        let spin = map * rates;
        let spin_rate = map * second + rate_map_derivative(angles.y, angles.z, &rates) * rates;
        let mut velocity = Vector6::zeros();
        let mut acceleration = Vector6::zeros();
        for k in 0..3 {
            velocity[k] = dof[k][1];
            velocity[3 + k] = spin[k];
            acceleration[k] = dof[k][2];
            acceleration[3 + k] = spin_rate[k];
        }
        Kinematics {
            motion: Motion {
                position: self.model.reference + Vector3::new(dof[0][0], dof[1][0], dof[2][0]),
                rotation: UnitQuaternion::from_euler_angles(angles.x, angles.y, angles.z),
                velocity,
            },
            acceleration,
        }
    }

    /// The fairleads' forces among `values` (the inputs in port order) and
    /// the external load: the inputs' and the waves' at `t` (s).
    fn end_loads<'a>(&self, values: &'a [f64], t: f64) -> EndLoads<'a> {
        let n = 3 * self.model.fairleads.len();
        EndLoads {
            forces: &values[..n],
            external: Vector6::from_column_slice(&values[n..n + 6]) + self.sea.excitation(t),
        }
    }

    /// The power (W) of the loads that do work at kinematics `k` under `loads`.
    fn power(&self, k: &Kinematics, loads: &EndLoads<'_>) -> f64 {
        self.model
            .applied(&k.motion, loads.forces, &loads.external)
            .dot(&k.motion.velocity)
    }

    fn energy(&self, k: &Kinematics) -> f64 {
        let [kinetic, potential] = self.model.energies(&k.motion);
        kinetic + potential
    }
}

impl Unit for Body {
    fn description(&self) -> &UnitDescription {
        &self.description
    }

    fn initialize(&mut self, t0: Time, inputs: Inputs<'_>) -> Result<(), UnitError> {
        let t0 = t0.as_secs();
        let p = &self.params;
        let loads = self.end_loads(inputs.end(), t0);
        let start = if self.is_prescribed() {
            if let Some(table) = &self.table {
                table.require_within(t0, "the start")?;
            }
            self.prescribed(t0)
        } else {
            let o = &p.initial_offset;
            let motion = Motion {
                position: self.model.reference + Vector3::new(o[0], o[1], o[2]),
                rotation: UnitQuaternion::from_euler_angles(o[3], o[4], o[5]),
                velocity: Vector6::from(p.initial_velocity),
            };
            let acceleration = self
                .model
                .acceleration(&motion, loads.forces, &loads.external)?;
            Kinematics {
                motion,
                acceleration,
            }
        };
        self.state.power = self.power(&start, &loads);
        self.set_kinematics(&start);
        self.state.t = t0;
        self.state.work = 0.0;
        self.state.initial_energy = self.energy(&start);
        self.state.newton_iterations = 0;
        self.last_start = None;
        Ok(())
    }

    fn do_step(&mut self, t: Time, h: Time, inputs: Inputs<'_>) -> Result<StepReport, UnitError> {
        let (t0, h) = (t.as_secs(), h.as_secs());
        let start = self.kinematics();
        // The loads at the step's end (the waves' excitation summed once).
        let loads = self.end_loads(inputs.end(), t0 + h);
        let (end, iterations) = if self.is_prescribed() {
            if let Some(table) = &self.table {
                table.require_within(t0 + h, "the step's end")?;
            }
            (self.prescribed(t0 + h), 0)
        } else {
            advance(&self.model, &start, h, &loads, self.params.max_iterations)?
        };
        let power = self.power(&end, &loads);
        self.state.work += 0.5 * h * (self.state.power + power);
        self.state.power = power;
        self.set_kinematics(&end);
        self.state.t = t0 + h;
        self.state.newton_iterations = iterations;
        self.last_start = Some((start, t0, h));
        self.sensitivity_ready = false;
        self.end_inputs.clear();
        self.end_inputs.extend_from_slice(inputs.end());
        Ok(StepReport {
            solver_iterations: iterations,
        })
    }

    fn outputs(&self, _inputs: Inputs<'_>, out: &mut [f64]) {
        ports::write_outputs(self, &self.kinematics(), out);
    }

    slender_contract::state_in_field!(state: BodyState, |unit| {
        unit.last_start = None;
        unit.sensitivity_ready = false;
    });

    fn step_jacobian(&mut self, inputs: Inputs<'_>, jacobian: &mut [f64]) -> Result<(), UnitError> {
        let Some((start, t0, h)) = self.last_start else {
            return require_step_jacobian_ready(false, "a body");
        };
        let _ = inputs;
        jacobian.fill(0.0);
        if self.is_prescribed() {
            return Ok(());
        }
        self.implicit_jacobian(&start, (t0, h), jacobian)
    }

    fn correct_step(&mut self, inputs: Inputs<'_>, change: &[f64]) -> Result<(), UnitError> {
        self.correct_last_step(inputs.end(), change)
    }
}
