//! Kind `reduced`: a seed 002 section reduced about its stress-free state, as a
//! unit. Its `section` table is a `nonlinear` unit's parameters; `modes` linear
//! modes make the basis, with their novel derivatives as further coordinates
//! (`derivatives = "linear"`, seed 002's LRBF), as coordinates following the
//! modes (`"taylor"`), or none. Loads (weight, distributed loads, loaded ends,
//! coupled ones included) are the section's own, projected; so its inputs are
//! the section's, and it takes the full section's place where the section is
//! loaded at its coupled ends. Held DOFs must stay at rest (a coupled or
//! prescribed motion needs constraint modes, not built).
//!
//! Stepping: central differences in as many equal sub-steps of the coupling
//! step as keep each below 0.9 times the critical step (from the reduced
//! frequencies). Outputs: each end's position, rotation, velocities (as the
//! full section names them) and each station's position. Rollback restores the
//! coordinates exactly; a step allocates nothing.

use super::basis::{Derivative, Normalisation, derivative_columns, linear_modes};
use super::polynomial::CubicSection;
use super::system::ReducedSection;
use super::taylor::TaylorSection;
use crate::contract::{
    Capabilities, HeldInputs, Inputs, Port, PortKind, StateSlot, StepReport, Time, Unit,
    UnitDescription, UnitError,
};
use crate::integrators::central_difference::CentralDifference;
use crate::integrators::hht::SecondOrderSystem;
use crate::nonlinear::{NonlinearParams, NonlinearSection};
use nalgebra::{DMatrix, DVector};
use serde::Deserialize;

/// How the modes' derivatives enter the basis.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Derivatives {
    /// Modes only.
    None,
    /// Modes and their novel derivatives as coordinates (LRBF).
    #[default]
    Linear,
    /// The derivatives follow the modal coordinates (Taylor basis).
    Taylor,
}

/// Parameters (scene kind `reduced`).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReducedParams {
    /// The full section: a `nonlinear` unit's parameters, seed 002's element.
    pub section: NonlinearParams,
    /// Linear modes in the basis, >= 1.
    pub modes: usize,
    #[serde(default)]
    pub derivatives: Derivatives,
}

enum Model {
    Linear(ReducedSection, CentralDifference),
    Taylor(TaylorSection),
}

crate::state_struct! {
    /// The coordinates, their rates and accelerations.
    #[derive(Debug, serde::Serialize, serde::Deserialize)]
    struct ReducedState {
        motion: Vec<f64>,
    }
}

/// The reduced unit.
pub struct ReducedUnit {
    section: NonlinearSection,
    cubic: CubicSection,
    model: Model,
    critical: f64,
    description: UnitDescription,
    state: ReducedState,
    /// A sub-step's load on all DOFs, on the free DOFs, and projected.
    load: Vec<f64>,
    free_load: DVector<f64>,
    projected: DVector<f64>,
    /// Displacements and velocities (free DOFs), and the outputs they give.
    displacement: DVector<f64>,
    velocity: DVector<f64>,
    values: Vec<f64>,
}

impl ReducedUnit {
    /// Builds the unit: the section, its modes and derivatives, the reduced model.
    pub fn new(params: ReducedParams) -> Result<ReducedUnit, UnitError> {
        let mut section = NonlinearSection::new(params.section)?;
        // The mass and the held DOFs are set up by `initialize` (at rest, zero
        // inputs: the stress-free state is the expansion point).
        let holds = section
            .description()
            .inputs
            .iter()
            .map(|p| p.hold)
            .collect();
        let zero = HeldInputs::new(holds);
        section.initialize(Time::ZERO, zero.view())?;
        if !section.held_at_rest() {
            return Err(UnitError::parameter(
                "section.ends",
                "prescribed or coupled motion",
                "expected held DOFs at rest: a reduced section takes loads at its ends, not motion",
            ));
        }
        let cubic = CubicSection::new(&section)?;
        let count = params.modes;
        if count == 0 || count >= cubic.size() {
            return Err(UnitError::parameter(
                "modes",
                count,
                &format!(
                    "expected 1 to {} (fewer than the free DOFs)",
                    cubic.size() - 1
                ),
            ));
        }
        let (model, critical) = build_model(&cubic, count, params.derivatives)?;
        let outputs = output_ports(section.station_count());
        let description = UnitDescription {
            kind: "reduced".into(),
            inputs: section.description().inputs.clone(),
            outputs,
            capabilities: Capabilities::default(),
        };
        let columns = match &model {
            Model::Linear(system, _) => system.size(),
            Model::Taylor(taylor) => taylor.basis_size(),
        };
        Ok(ReducedUnit {
            load: vec![0.0; section.model().dofs()],
            free_load: DVector::zeros(cubic.size()),
            projected: DVector::zeros(columns),
            displacement: DVector::zeros(cubic.size()),
            velocity: DVector::zeros(cubic.size()),
            values: vec![0.0; description.outputs.len()],
            state: ReducedState { motion: Vec::new() },
            section,
            cubic,
            model,
            critical,
            description,
        })
    }

    /// The critical step of central differences (s) about the stress-free state.
    pub fn critical_step(&self) -> f64 {
        self.critical
    }

    /// Copies the motion into the state (its buffer reused).
    fn store_motion(&mut self) {
        let [q, v, a] = match &self.model {
            Model::Linear(system, _) => system.motion(),
            Model::Taylor(taylor) => taylor.motion(),
        };
        let m = &mut self.state.motion;
        m.clear();
        m.extend_from_slice(q);
        m.extend_from_slice(v);
        m.extend_from_slice(a);
    }

    /// Recomputes the outputs from the current motion (after a step, an
    /// initialisation or a restore), allocating nothing.
    fn refresh_outputs(&mut self) {
        let (d, v) = (&mut self.displacement, &mut self.velocity);
        match &mut self.model {
            Model::Linear(system, _) => system.displacements_and_velocities_into(d, v),
            Model::Taylor(taylor) => taylor.displacements_and_velocities_into(d, v),
        }
        let free = self.cubic.free_dofs();
        let at = |x: &DVector<f64>, dof: usize| free.binary_search(&dof).map_or(0.0, |k| x[k]);
        let model = self.section.model();
        let last = model.reference.len() - 1;
        let out = &mut self.values;
        for (k, node) in [0, last].into_iter().enumerate() {
            let [x, z] = model.reference[node];
            let base = 6 * k;
            out[base] = x + at(d, 3 * node);
            out[base + 1] = z + at(d, 3 * node + 1);
            out[base + 2] = at(d, 3 * node + 2);
            out[base + 3] = at(v, 3 * node);
            out[base + 4] = at(v, 3 * node + 1);
            out[base + 5] = at(v, 3 * node + 2);
        }
        for (i, &s) in self.section.stations().iter().enumerate() {
            let (e, xi) = model.locate(s);
            for c in 0..2 {
                let (a, b) = (at(d, 3 * e + c), at(d, 3 * (e + 1) + c));
                let reference = (1.0 - xi) * model.reference[e][c] + xi * model.reference[e + 1][c];
                out[12 + 2 * i + c] = reference + (1.0 - xi) * a + xi * b;
            }
        }
    }
}

/// The reduced model of `cubic` on `count` modes and its critical step (s).
fn build_model(
    cubic: &CubicSection,
    count: usize,
    derivatives: Derivatives,
) -> Result<(Model, f64), UnitError> {
    let modes = linear_modes(cubic, count, Normalisation::Mass)?;
    let phi = DMatrix::from_columns(&modes.shapes);
    Ok(match derivatives {
        Derivatives::Taylor => {
            let mds = derivative_columns(cubic, &modes, Derivative::Novel, count)?;
            let taylor = TaylorSection::new(cubic, &phi, &DMatrix::from_columns(&mds))?;
            // Linearised at rest only the modes remain: 2 / omega_N.
            let critical = modes.omegas.last().map_or(f64::INFINITY, |w| 2.0 / w);
            (Model::Taylor(taylor), critical)
        }
        kind => {
            let mut columns = modes.shapes.clone();
            if kind == Derivatives::Linear {
                columns.extend(derivative_columns(cubic, &modes, Derivative::Novel, count)?);
            }
            let system = ReducedSection::new(cubic, DMatrix::from_columns(&columns));
            let critical = CentralDifference::critical_step(&system.matrices(), 400)?;
            (Model::Linear(system, CentralDifference::new()), critical)
        }
    })
}

/// Each end's position, rotation and velocities, then each station's position.
fn output_ports(stations: usize) -> Vec<Port> {
    let mut outputs = Vec::new();
    for side in ["start", "end"] {
        for (name, kind) in [
            ("position_x", PortKind::Displacement),
            ("position_z", PortKind::Displacement),
            ("rotation", PortKind::Rotation),
            ("velocity_x", PortKind::Velocity),
            ("velocity_z", PortKind::Velocity),
        ] {
            outputs.push(Port::output(&format!("{side}_{name}"), kind));
        }
        outputs.push(
            Port::output(&format!("{side}_angular_velocity"), PortKind::Generic).with_unit("rad/s"),
        );
    }
    for i in 1..=stations {
        outputs.push(Port::output(&format!("x_{i}"), PortKind::Displacement));
        outputs.push(Port::output(&format!("z_{i}"), PortKind::Displacement));
    }
    outputs
}

impl Unit for ReducedUnit {
    fn description(&self) -> &UnitDescription {
        &self.description
    }

    fn initialize(&mut self, t0: Time, inputs: Inputs<'_>) -> Result<(), UnitError> {
        // At rest in the stress-free state, accelerated by the load at t0.
        let count = match &self.model {
            Model::Linear(system, _) => system.size(),
            Model::Taylor(taylor) => taylor.size(),
        };
        let zero = vec![0.0; count];
        self.section
            .load_at(inputs, t0.as_secs(), 1.0, &mut self.load);
        for (f, &d) in self.free_load.iter_mut().zip(self.cubic.free_dofs()) {
            *f = self.load[d];
        }
        match &mut self.model {
            Model::Linear(system, _) => {
                system.set_motion(&zero, &zero, &zero);
                system.project_into(&self.free_load, &mut self.projected);
                system.set_initial_acceleration(&self.projected)?;
            }
            Model::Taylor(taylor) => {
                taylor.set_motion(&zero, &zero, &zero);
                taylor.project_into(&self.free_load, &mut self.projected);
                taylor.set_initial_acceleration(&self.projected)?;
            }
        }
        self.store_motion();
        self.refresh_outputs();
        Ok(())
    }

    fn do_step(&mut self, t: Time, h: Time, inputs: Inputs<'_>) -> Result<StepReport, UnitError> {
        let (t0, h) = (t.as_secs(), h.as_secs());
        let substeps = (h / (0.9 * self.critical)).ceil().max(1.0) as usize;
        let hk = h / substeps as f64;
        for k in 1..=substeps {
            let s = k as f64 / substeps as f64;
            self.section.load_at(inputs, t0 + s * h, s, &mut self.load);
            for (f, &d) in self.free_load.iter_mut().zip(self.cubic.free_dofs()) {
                *f = self.load[d];
            }
            match &mut self.model {
                Model::Linear(system, cd) => {
                    system.project_into(&self.free_load, &mut self.projected);
                    cd.step(system, t0 + s * h, hk, self.projected.as_slice(), &[])?;
                }
                Model::Taylor(taylor) => {
                    taylor.project_into(&self.free_load, &mut self.projected);
                    taylor.step(hk, &self.projected)?;
                }
            }
        }
        self.store_motion();
        self.refresh_outputs();
        Ok(StepReport::default())
    }

    fn outputs(&self, _inputs: Inputs<'_>, out: &mut [f64]) {
        out.copy_from_slice(&self.values);
    }

    fn save_state(&self, slot: &mut StateSlot) -> Result<(), UnitError> {
        slot.store(&self.state);
        Ok(())
    }

    fn restore_state(&mut self, slot: &StateSlot) -> Result<(), UnitError> {
        self.state.clone_from(&*slot.load::<ReducedState>()?);
        let n = self.state.motion.len() / 3;
        let m = &self.state.motion;
        match &mut self.model {
            Model::Linear(system, _) => system.set_motion(&m[..n], &m[n..2 * n], &m[2 * n..]),
            Model::Taylor(taylor) => taylor.set_motion(&m[..n], &m[n..2 * n], &m[2 * n..]),
        }
        self.refresh_outputs();
        Ok(())
    }
}
