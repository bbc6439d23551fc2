//! A slender line in three dimensions (scene kind `line3d`): a mooring line,
//! a riser or a section of one, with large displacements, axial and bending
//! stiffness ([`mechanics`], rotation-free: nodes with three translations),
//! Morison drag and added mass with normal and tangential coefficients, a
//! current by depth with a heading per depth, Airy waves ([`waves`]), and a
//! sloped seabed with penalty contact and Coulomb friction along and across
//! the line ([`environment`]). Lumped mass; HHT-alpha with Newton on a banded
//! matrix (half-bandwidth 8), so it steps at the coupling step rather than at
//! an explicit scheme's critical step; its start is the static equilibrium by
//! Newton from the elastic catenary ([`catenary`], [`statics`]).
//!
//! Ends: fixed, moved by sines, moved by coupled velocities (the force on what
//! moves them is an output) or loaded by coupled forces (their motion is an
//! output). Torsion is not modelled: a scene that gives a torsional stiffness
//! is refused.

pub mod bathymetry;
pub mod catenary;
pub mod catenary_section;
pub mod environment;
pub mod mechanics;
pub mod params;
pub mod waves;

mod jacobian;
mod linear;
mod outputs;
mod statics;
mod step;

use crate::contract::{
    Capabilities, Field, Inputs, StepReport, Time, Unit, UnitDescription, UnitError,
};
use crate::integrators::hht::HhtAlpha;
use crate::numerics::banded::SymmetricBand;
use environment::{Environment, tangent_at};
use mechanics::{BAND, DOF, Mechanics, add_block, normal_projector};
pub use params::{EndCondition, Line3dParams};

crate::state_struct! {
    /// Everything that changes while stepping.
    #[derive(Debug, serde::Serialize, serde::Deserialize)]
    struct Line3dState {
        t: f64,
        /// Node positions (m), velocities (m/s), accelerations (m/s^2).
        q: Vec<f64>,
        v: Vec<f64>,
        a: Vec<f64>,
        /// The internal and surroundings' force g(q, v, t) at the current time (N).
        force: Vec<f64>,
        /// Force each end exerts on what holds it (N): start x, y, z, end x, y, z.
        reaction: [f64; 6],
        /// Energy ledger (J): the energy at the start of the dynamics, and the
        /// work done since by the ends, the water, friction, the seabed's
        /// damper and the axial damper.
        ledger: step::Ledger,
        newton_iterations: u32,
        /// The linear model's strain and seabed-spring energies (J).
        linear_energy: [f64; 2],
        /// Whether the start and the end have let go (`released_at`).
        released: [bool; 2],
    }
}

/// The unit.
pub struct Line3d {
    params: Line3dParams,
    description: UnitDescription,
    mechanics: Mechanics,
    environment: Environment,
    /// Lumped mass with the added mass of the static shape (kg).
    mass: SymmetricBand,
    /// Weight in water per DOF (N; z entries negative).
    weight: Vec<f64>,
    hht: HhtAlpha,
    state: Line3dState,
    work: step::Work,
    /// The first input of each end that takes coupled inputs.
    first_input: [Option<usize>; 2],
    jacobian: jacobian::JacobianWork,
    /// The linear model about the static state, with `linear = true`.
    linear: Option<linear::Linearised>,
}

/// The ends' names in ports: the start (anchor) and the end (fairlead).
pub const SIDES: [&str; 2] = ["start", "end"];

impl Line3d {
    /// Builds the unit from checked parameters.
    pub fn new(params: Line3dParams) -> Result<Line3d, UnitError> {
        params.validate()?;
        let nodes = params.elements + 1;
        let element_length = params.length / params.elements as f64;
        let mechanics = Mechanics {
            nodes,
            element_length,
            axial_stiffness: params.axial_stiffness,
            bending_stiffness: params.bending_stiffness,
            axial_damping: params.axial_damping,
        };
        let tributary: Vec<f64> = (0..nodes)
            .map(|i| if i == 0 || i + 1 == nodes { 0.5 } else { 1.0 } * element_length)
            .collect();
        let mut weight = vec![0.0; DOF * nodes];
        for (i, l) in tributary.iter().enumerate() {
            weight[DOF * i + 2] = -params.submerged_weight * l;
        }
        let environment = Environment::new(&params, tributary);
        let mut first_input = [None; 2];
        let mut next = 0;
        for (k, end) in [&params.start, &params.end].iter().enumerate() {
            if matches!(end.condition, EndCondition::Velocity | EndCondition::Force) {
                first_input[k] = Some(next);
                next += DOF;
            }
        }
        let coupled = first_input.iter().any(Option::is_some);
        let description = UnitDescription {
            kind: "line3d".into(),
            inputs: outputs::input_ports(&params),
            outputs: outputs::output_ports(&params, &first_input),
            capabilities: Capabilities {
                step_jacobian: coupled,
                step_correction: coupled,
                ..Capabilities::default()
            },
        };
        let n = DOF * nodes;
        let mut hht = HhtAlpha::new(params.alpha, n, BAND);
        hht.predict_start();
        if coupled {
            hht.keep_newton_matrix();
        }
        Ok(Line3d {
            hht,
            params,
            description,
            mechanics,
            environment,
            mass: SymmetricBand::zeros(n, BAND),
            weight,
            state: Line3dState {
                t: 0.0,
                q: vec![0.0; n],
                v: vec![0.0; n],
                a: vec![0.0; n],
                force: vec![0.0; n],
                reaction: [0.0; 6],
                released: [false; 2],
                ledger: step::Ledger::default(),
                newton_iterations: 0,
                linear_energy: [0.0; 2],
            },
            work: step::Work::default(),
            first_input,
            jacobian: jacobian::JacobianWork::default(),
            linear: None,
        })
    }

    /// The DOFs whose motion is prescribed (fixed, moved or velocity ends
    /// that have not let go).
    fn held_dofs(&self) -> Vec<usize> {
        let last = self.mechanics.nodes - 1;
        [(&self.params.start, 0), (&self.params.end, last)]
            .iter()
            .zip(self.state.released)
            .filter(|((e, _), released)| e.condition != EndCondition::Force && !released)
            .flat_map(|((_, i), _)| DOF * i..DOF * i + DOF)
            .collect()
    }

    /// Lumped mass: m l + rho A l (Ca_n P + Ca_t t t^T) with the tangent `t`
    /// of the shape `q` (the static one: added mass follows the start shape).
    fn form_mass(&mut self, q: &[f64]) {
        let p = &self.params;
        let area = std::f64::consts::PI * p.diameter * p.diameter / 4.0;
        let water = p.water_density * area;
        self.mass.fill_zero();
        for i in 0..self.mechanics.nodes {
            let l = self.environment.tributary(i);
            let t = tangent_at(q, i, self.mechanics.nodes);
            let m = nalgebra::Matrix3::identity() * (p.mass_per_length * l)
                + (normal_projector(&t) * p.added_mass_normal
                    + t * t.transpose() * p.added_mass_tangential)
                    * (water * l);
            add_block(&mut self.mass, i, i, &m, 1.0);
        }
    }

    /// The loads (N) the coupled force inputs put on the ends at fraction `s`
    /// of the step, per DOF.
    fn end_loads(&self, inputs: &Inputs<'_>, s: f64, out: &mut [f64]) {
        out.fill(0.0);
        let last = self.mechanics.nodes - 1;
        for (k, (end, node)) in [(&self.params.start, 0), (&self.params.end, last)]
            .iter()
            .enumerate()
        {
            if let (EndCondition::Force, Some(first)) = (end.condition, self.first_input[k]) {
                for c in 0..DOF {
                    out[DOF * node + c] = inputs.at(first + c, s);
                }
            }
        }
    }
}

impl Unit for Line3d {
    fn description(&self) -> &UnitDescription {
        &self.description
    }

    fn initialize(&mut self, t0: Time, inputs: Inputs<'_>) -> Result<(), UnitError> {
        let t0 = t0.as_secs();
        let mut q = self.first_shape();
        for (k, end) in [&self.params.start, &self.params.end].iter().enumerate() {
            let node = if k == 0 { 0 } else { self.mechanics.nodes - 1 };
            let [p, _, _] = step::end_motion(end, t0);
            q[DOF * node..DOF * node + DOF].copy_from_slice(&p);
        }
        let mut loads = vec![0.0; q.len()];
        self.end_loads(&inputs, 1.0, &mut loads);
        self.solve_statics(&mut q, &loads, t0)?;
        self.form_mass(&q);
        self.linearise(&q);
        self.hht.forget_matrices();
        self.start_dynamics(q, &inputs, t0);
        self.jacobian.ready = false;
        Ok(())
    }

    fn do_step(&mut self, t: Time, h: Time, inputs: Inputs<'_>) -> Result<StepReport, UnitError> {
        let iterations = self.step_coupling(t.as_secs(), h.as_secs(), &inputs)?;
        Ok(StepReport {
            solver_iterations: iterations,
        })
    }

    fn outputs(&self, inputs: Inputs<'_>, out: &mut [f64]) {
        self.write_outputs(&inputs, out);
    }

    slender_contract::state_in_field!(state: Line3dState, |unit| {
        unit.jacobian.ready = false;
    });

    fn step_jacobian(&mut self, inputs: Inputs<'_>, jacobian: &mut [f64]) -> Result<(), UnitError> {
        self.interface_jacobian(inputs, jacobian)
    }

    fn warm_repeat(&mut self) {
        self.jacobian.warm.warm = true;
    }

    fn correct_step(&mut self, inputs: Inputs<'_>, change: &[f64]) -> Result<(), UnitError> {
        self.correct_last_step(&inputs, change)
    }

    fn fields(&self) -> Vec<Field> {
        self.field_list()
    }

    fn field_values(&self, index: usize, out: &mut [f64]) -> Result<(), UnitError> {
        self.write_field(index, out)
    }

    /// Every degree of freedom of a rotation-free line is a translation.
    fn local_error(&self) -> Option<f64> {
        Some(self.hht.local_error(|_| true))
    }
}

#[cfg(test)]
mod catenary_section_tests;
#[cfg(test)]
mod coupling_tests;
#[cfg(test)]
mod linear_tests;
#[cfg(test)]
mod planar_tests;
#[cfg(test)]
mod release_tests;
#[cfg(test)]
mod seabed_tests;
#[cfg(test)]
mod statics_tests;
#[cfg(test)]
mod tests;
