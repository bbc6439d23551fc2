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
//! With `attachments` the static response to each loaded end DOF joins the
//! basis. Stepping: central differences in as many equal sub-steps of the
//! coupling step as keep each below 0.9 times the critical step (from the
//! reduced frequencies), or the trapezoidal rule in one step (a linear basis).
//! Outputs: each end's position, rotation, velocities and force (as the full
//! section names them) and each station's position. Rollback restores the
//! coordinates exactly; a step allocates nothing.

use super::build::{Implicit, Model, Stepper, build_model, refuse_what_is_not_reduced};
use super::jacobian::JacobianWork;
use super::polynomial::CubicSection;
use crate::contract::{
    Capabilities, HeldInputs, Inputs, Port, PortKind, StateSlot, StepReport, Time, Unit,
    UnitDescription, UnitError, require_finite_state,
};
use crate::integrators::hht::{NewtonSettings, SecondOrderSystem, StepLoads};
use crate::nonlinear::model::element_dofs;
use crate::nonlinear::{NonlinearParams, NonlinearSection};
use nalgebra::DVector;
use serde::{Deserialize, Serialize};

/// What the reduced section's motion is, for an error where it became
/// non-finite.
const MOTION: &str = "the reduced section's coordinates, velocities and accelerations";

/// How the modes' derivatives enter the basis.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
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
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ReducedParams {
    /// The full section: a `nonlinear` unit's parameters, seed 002's element.
    pub section: NonlinearParams,
    /// Linear modes in the basis, >= 1.
    pub modes: usize,
    /// How the modes' derivatives enter the basis.
    #[serde(default)]
    pub derivatives: Derivatives,
    /// How the coordinates are stepped.
    #[serde(default)]
    pub integrator: Stepping,
    /// Add the static response to a unit load at each loaded end DOF
    /// (attachment vectors, as further coordinates without derivatives): a
    /// section coupled by forces at its cuts needs their local flexibility,
    /// which its lowest modes miss.
    #[serde(default = "yes")]
    pub attachments: bool,
}

fn yes() -> bool {
    true
}

/// How a reduced unit steps its coordinates.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Stepping {
    /// Central differences in sub-steps below 0.9 times the critical step.
    #[default]
    CentralDifference,
    /// The trapezoidal rule (HHT-alpha with alpha = 0), Newton on the reduced
    /// tangent, one step per coupling step: for a linear basis whose
    /// derivatives' frequencies make the explicit step small.
    Trapezoidal,
}

/// Outputs per end (position, rotation, velocities, force and moment), and
/// where the critical step sits: after both ends, before the stations.
pub(super) const PER_END: usize = 9;
pub(super) const CRITICAL_STEP: usize = 2 * PER_END;

/// Newton's tolerance and bound for the trapezoidal rule (relative
/// correction of the coordinates; the reduced tensors carry EA, so round-off
/// floors the corrections near 1e-9).
const NEWTON: NewtonSettings = NewtonSettings {
    tolerance: 1e-8,
    max_iterations: 20,
};

crate::state_struct! {
    /// The coordinates, their rates and accelerations.
    #[derive(Debug, serde::Serialize, serde::Deserialize)]
    struct ReducedState {
        motion: Vec<f64>,
    }
}

/// The reduced unit.
pub struct ReducedUnit {
    pub(super) section: NonlinearSection,
    pub(super) cubic: CubicSection,
    pub(super) model: Model,
    critical: f64,
    description: UnitDescription,
    state: ReducedState,
    /// A sub-step's load on all DOFs, on the free DOFs, and projected.
    load: Vec<f64>,
    free_load: DVector<f64>,
    projected: DVector<f64>,
    /// Displacements, velocities and accelerations (free DOFs), the
    /// accelerations on all DOFs, and the outputs they give.
    pub(super) displacement: DVector<f64>,
    velocity: DVector<f64>,
    acceleration: DVector<f64>,
    full: Vec<f64>,
    residual: Vec<f64>,
    /// The coordinates and rates at a trapezoidal step's start.
    start: Vec<f64>,
    values: Vec<f64>,
    /// The end DOFs loaded by a force or moment (model DOFs).
    pub(super) loaded: Vec<usize>,
    /// Whether a single DOF holds x (z): its reaction is the balance sum.
    pub(super) held_once: [bool; 2],
    /// (input port, model DOF) of each coupled end load.
    pub(super) input_dofs: Vec<(usize, usize)>,
    pub(super) jacobian: JacobianWork,
}

impl ReducedUnit {
    /// Builds the unit: the section, its modes and derivatives, the reduced model.
    pub fn new(params: ReducedParams) -> Result<ReducedUnit, UnitError> {
        let section = section_at_rest(params.section)?;
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
        let loaded_ends = section.loaded_end_dofs();
        // Attachment vectors at the loaded end DOFs (as free-DOF indices).
        let free = cubic.free_dofs();
        let loaded: Vec<usize> = (loaded_ends.iter())
            .filter(|_| params.attachments)
            .filter_map(|d| free.binary_search(d).ok())
            .collect();
        let (model, critical) = build_model(
            &cubic,
            (count, params.derivatives),
            &loaded,
            params.integrator,
        )?;
        let outputs = output_ports(section.station_count());
        let description = UnitDescription {
            kind: "reduced".into(),
            inputs: section.description().inputs.clone(),
            outputs,
            capabilities: Capabilities {
                step_jacobian: ReducedUnit::offers_jacobian(&model),
                ..Capabilities::default()
            },
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
            acceleration: DVector::zeros(cubic.size()),
            full: vec![0.0; section.model().dofs()],
            residual: vec![0.0; section.model().dofs()],
            start: vec![0.0; 2 * columns],
            values: {
                // The critical step never changes; finite as every output.
                let mut values = vec![0.0; description.outputs.len()];
                values[CRITICAL_STEP] = if critical.is_finite() { critical } else { 0.0 };
                values
            },
            loaded: loaded_ends,
            held_once: [0, 1].map(|c| {
                let dofs = section.model().dofs();
                (c..dofs)
                    .step_by(3)
                    .filter(|d| free.binary_search(d).is_err())
                    .count()
                    == 1
            }),
            state: ReducedState { motion: Vec::new() },
            input_dofs: section.input_load_dofs(),
            jacobian: JacobianWork::default(),
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

    /// One trapezoidal step from `t0` over `h` (s): the projected loads at both
    /// ends, the nonlinear force at the start, Newton on the reduced tangent;
    /// returns the Newton iterations.
    fn implicit_step(&mut self, t0: f64, h: f64, inputs: Inputs<'_>) -> Result<u32, UnitError> {
        let Model::Linear(system, Stepper::Implicit(implicit)) = &mut self.model else {
            return Ok(0);
        };
        let Implicit { hht, f0, g0 } = &mut **implicit;
        for (s, out) in [(0.0, &mut *f0), (1.0, &mut self.projected)] {
            self.section.load_at(inputs, t0 + s * h, s, &mut self.load);
            gather(&self.load, self.cubic.free_dofs(), &mut self.free_load);
            system.project_into(&self.free_load, out);
        }
        let n = system.size();
        self.start[..n].copy_from_slice(system.motion()[0]);
        self.start[n..].copy_from_slice(system.motion()[1]);
        let (q0, v0) = self.start.split_at(n);
        system.nonlinear_force(q0, v0, t0, None, g0);
        let loads = StepLoads {
            t0,
            t1: t0 + h,
            h,
            f0: f0.as_slice(),
            f1: self.projected.as_slice(),
            g0: Some(g0),
            held: &[],
        };
        hht.step(system, &loads, NEWTON)
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
        let (d, v, a) = (
            &mut self.displacement,
            &mut self.velocity,
            &mut self.acceleration,
        );
        match &mut self.model {
            Model::Linear(system, _) => {
                system.displacements_and_velocities_into(d, v);
                system.accelerations_into(a);
            }
            Model::Taylor(taylor) => {
                taylor.displacements_and_velocities_into(d, v);
                taylor.accelerations_into(a);
            }
        }
        let mut values = std::mem::take(&mut self.values);
        let mut put = |row: usize, value: f64| values[row] = value;
        self.kinematic_rows(&self.displacement, &self.velocity, true, &mut put);
        self.values = values;
        self.end_forces();
    }

    /// Each end's position, rotation and velocities and each station's
    /// position from displacements `d` and velocities `v` on the free DOFs,
    /// as `put(output row, value)`; the positions from the reference
    /// (stress-free) shape with `reference`, their changes without.
    pub(super) fn kinematic_rows(
        &self,
        d: &DVector<f64>,
        v: &DVector<f64>,
        reference: bool,
        put: &mut impl FnMut(usize, f64),
    ) {
        let free = self.cubic.free_dofs();
        let at = |x: &DVector<f64>, dof: usize| free.binary_search(&dof).map_or(0.0, |k| x[k]);
        let model = self.section.model();
        let origin = |node: usize, c: usize| match reference {
            true => model.reference[node][c],
            false => 0.0,
        };
        let last = model.reference.len() - 1;
        for (k, node) in [0, last].into_iter().enumerate() {
            let base = PER_END * k;
            for c in 0..3 {
                let position = if c < 2 { origin(node, c) } else { 0.0 };
                put(base + c, position + at(d, 3 * node + c));
                put(base + 3 + c, at(v, 3 * node + c));
            }
        }
        for (i, &s) in self.section.stations().iter().enumerate() {
            let (e, xi) = model.locate(s);
            for c in 0..2 {
                let (a, b) = (at(d, 3 * e + c), at(d, 3 * (e + 1) + c));
                let position = (1.0 - xi) * origin(e, c) + xi * origin(e + 1, c);
                put(
                    CRITICAL_STEP + 1 + 2 * i + c,
                    position + (1.0 - xi) * a + xi * b,
                );
            }
        }
    }

    /// The central-difference sub-steps of a coupling step of `h` seconds.
    pub(super) fn substeps(&self, h: f64) -> usize {
        (h / (0.9 * self.critical)).ceil().max(1.0) as usize
    }

    /// Each end's force on what holds or loads it (N, N m), as the full
    /// section gives it: minus the reaction M a + g(V) - f at a held DOF,
    /// minus the load at a loaded one, zero at a free one. The element forces
    /// sum to zero in x and in z, so where one DOF holds a direction its
    /// reaction is the section's balance sum (f - M a); the stiff axial
    /// strain a few modes get wrong does not enter. Elsewhere (a rotation,
    /// or a direction held twice) the end element's force gives it.
    fn end_forces(&mut self) {
        let free = self.cubic.free_dofs();
        self.full.fill(0.0);
        for (k, &dof) in free.iter().enumerate() {
            self.full[dof] = self.displacement[k];
        }
        let model = self.section.model();
        let last = model.reference.len() - 1;
        let mut element_force = [[0.0; 6]; 2];
        for (side, e) in [0, last - 1].into_iter().enumerate() {
            let p = element_dofs(&self.full, e);
            element_force[side] = model.elements[e].force(model.formulation, &p, false).0;
        }
        self.full.fill(0.0);
        for (k, &dof) in free.iter().enumerate() {
            self.full[dof] = self.acceleration[k];
        }
        // The residual f - M a on all DOFs (held ones do not accelerate).
        let residual = &mut self.residual;
        residual.copy_from_slice(&self.load);
        self.section
            .mass_matrix()
            .mul_add(-1.0, &self.full, residual);
        for (side, node) in [0, last].into_iter().enumerate() {
            for c in 0..3 {
                let dof = 3 * node + c;
                let residual = &self.residual;
                let value = match self.end_force_rule(side, c, dof) {
                    EndForce::BalanceSum => residual.iter().skip(c).step_by(3).sum(),
                    EndForce::Element(local) => residual[dof] - element_force[side][local],
                    EndForce::Load => -self.load[dof],
                    EndForce::Zero => 0.0,
                };
                self.values[PER_END * side + 6 + c] = value;
            }
        }
    }

    /// How end DOF `dof` (component `c` at end `side`) reports its force;
    /// the step Jacobian differentiates the same rule.
    pub(super) fn end_force_rule(&self, side: usize, c: usize, dof: usize) -> EndForce {
        if self.cubic.free_dofs().binary_search(&dof).is_err() {
            match c < 2 && self.held_once[c] {
                true => EndForce::BalanceSum,
                false => EndForce::Element(if side == 0 { c } else { 3 + c }),
            }
        } else if self.loaded.binary_search(&dof).is_ok() {
            EndForce::Load
        } else {
            EndForce::Zero
        }
    }
}

/// How an end's reported force is formed (`ReducedUnit::end_forces`).
pub(super) enum EndForce {
    /// A direction one held DOF holds: the section's balance sum f - M a.
    BalanceSum,
    /// Another held DOF: the residual less the end element's force (its
    /// local index).
    Element(usize),
    /// A loaded DOF: minus the load.
    Load,
    /// A free DOF: nothing holds it.
    Zero,
}

/// The entries of `full` (all DOFs) at the `free` DOFs into `out`.
fn gather(full: &[f64], free: &[usize], out: &mut DVector<f64>) {
    for (o, &d) in out.iter_mut().zip(free) {
        *o = full[d];
    }
}

/// The full section, initialised at rest in its stress-free state (which sets
/// up its mass and held DOFs); refused where it has what a reduced section does
/// not carry or where a held DOF moves.
fn section_at_rest(params: NonlinearParams) -> Result<NonlinearSection, UnitError> {
    refuse_what_is_not_reduced(&params)?;
    let mut section = NonlinearSection::new(params)?;
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
    Ok(section)
}

/// Each end's position, rotation, velocities and force, the critical step of
/// central differences (s; 0 when stepped implicitly), then each station's
/// position.
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
        outputs.push(Port::output(&format!("{side}_force_x"), PortKind::Force));
        outputs.push(Port::output(&format!("{side}_force_z"), PortKind::Force));
        outputs.push(Port::output(&format!("{side}_moment"), PortKind::Moment));
    }
    outputs.push(Port::output("critical_step", PortKind::Generic).with_unit("s"));
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
        gather(&self.load, self.cubic.free_dofs(), &mut self.free_load);
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
        self.jacobian.ready = false;
        Ok(())
    }

    fn do_step(&mut self, t: Time, h: Time, inputs: Inputs<'_>) -> Result<StepReport, UnitError> {
        let (t0, h) = (t.as_secs(), h.as_secs());
        let w = &mut self.jacobian;
        w.ready = false;
        (w.t0, w.h) = (t0, h);
        if let Model::Linear(_, Stepper::Implicit(_)) = self.model {
            let iterations = self.implicit_step(t0, h, inputs)?;
            self.store_motion();
            require_finite_state(MOTION, &self.state.motion)?;
            self.refresh_outputs();
            self.jacobian.ready = true;
            return Ok(StepReport {
                solver_iterations: iterations,
            });
        }
        let substeps = self.substeps(h);
        let hk = h / substeps as f64;
        for k in 1..=substeps {
            let s = k as f64 / substeps as f64;
            self.section.load_at(inputs, t0 + s * h, s, &mut self.load);
            gather(&self.load, self.cubic.free_dofs(), &mut self.free_load);
            match &mut self.model {
                Model::Linear(system, Stepper::Explicit(cd)) => {
                    system.project_into(&self.free_load, &mut self.projected);
                    cd.step(system, t0 + s * h, hk, self.projected.as_slice(), &[])?;
                }
                Model::Linear(_, Stepper::Implicit(_)) => {}
                Model::Taylor(taylor) => {
                    taylor.project_into(&self.free_load, &mut self.projected);
                    taylor.step(hk, &self.projected)?;
                }
            }
        }
        self.store_motion();
        require_finite_state(MOTION, &self.state.motion)?;
        self.refresh_outputs();
        self.jacobian.ready = true;
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
        self.jacobian.ready = false;
        Ok(())
    }

    fn step_jacobian(&mut self, inputs: Inputs<'_>, jacobian: &mut [f64]) -> Result<(), UnitError> {
        self.interface_jacobian(inputs, jacobian)
    }
}
