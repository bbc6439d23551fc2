//! Geometrically nonlinear section unit (scene kind `nonlinear`): a planar chain
//! of 2D beam-column elements (axial EA, bending EI) in one of two formulations
//! (co-rotational, seed 002's cubic element; [`element`]), with weight, distributed
//! loads, Morison drag on the velocity relative to a current, added mass, Rayleigh
//! damping and nodal contact with a surface; ends fixed, pinned, free, moved in
//! time, coupled in velocity or displacement, or loaded (time functions or coupled
//! forces and moments). A static Newton with load continuation finds the
//! equilibrium ([`statics`]); HHT-alpha with Newton or explicit central
//! differences step the dynamics ([`dynamics`]). This is the reference model of a
//! section: the cheaper units are measured against it.

pub mod contact;
mod correction;
mod deferred_end;
pub mod element;
pub mod ends;
pub mod environment;
pub mod model;
pub mod params;
pub mod seed002;

mod dynamics;
mod energy;
mod fields;
mod jacobian;
mod linear;
mod modes;
mod moments;
mod reduced;
mod start_shape;
mod statics;
mod step_work;
mod validation;

use crate::contract::{
    Capabilities, Field, Inputs, Port, PortKind, StepReport, Time, Unit, UnitDescription, UnitError,
};
use crate::integrators::central_difference::CentralDifference;
use crate::integrators::hht::HhtAlpha;
use crate::numerics::banded::SymmetricBand;
use contact::ContactSummary;
use ends::Resolved;
use environment::Environment;
use model::{BAND, Model};
use params::Integrator;

/// Outputs per station: tension, moment, curvature, x, z, internal force.
const STATION_OUTPUTS: usize = 6;
pub use moments::Loads;
pub use params::NonlinearParams;
/// How a section reduced about its start samples its forces (`reduced_sampling`).
pub use reduced::Sampling;

crate::state_struct! {
    /// Everything that changes while stepping.
    #[derive(Debug, serde::Serialize, serde::Deserialize)]
    struct SectionState {
        t: f64,
        q: Vec<f64>,
        v: Vec<f64>,
        a: Vec<f64>,
        /// Internal, drag and contact force at the current time (N, N m).
        force: Vec<f64>,
        /// Its elastic part as the integrator used it (with the energy-conserving
        /// integrator, 2 g_bar - g0 of the last step).
        elastic: Vec<f64>,
        /// Support reactions at the held DOFs: M a + C v + g - f (N, N m).
        reaction: Vec<f64>,
        /// Force of the contact laws stepped by their discrete gradient as the
        /// integrator used it (2 F_bar - F0 of the last step).
        stepped_contact: Vec<f64>,
        /// Lagrangian parameters of the contacts, per surface and node.
        lambda: Vec<f64>,
        contact: ContactSummary,
        /// The rollers' loads at the current state (the moment recovery's
        /// point loads).
        rollers: Vec<contact::RollerLoad>,
        /// Largest sag-bend and overbend moments (N m) at the current time and
        /// over the last step (its start and end).
        bend_now: [f64; 2],
        bend_step: [f64; 2],
        /// Largest |moment| (N m) and tension (N) at the current time.
        largest: [f64; 2],
        /// The elements' strain energy (J) when the last force evaluation
        /// gave it (a nonlinear, not energy-conserving section).
        strain_energy: Option<f64>,
        newton_iterations: u32,
        /// A reduced section's coordinates, velocities and accelerations
        /// (empty otherwise).
        reduced: Vec<f64>,
        /// The forces from outside the section's energy at the current time
        /// (N, N m; `energy::outside_force`) and the energy balance.
        outside: Vec<f64>,
        ledger: energy::EnergyLedger,
    }
}

impl SectionState {
    /// At rest at the stress-free shape (`n` DOFs), nothing in contact.
    fn at_rest(n: usize, lambda: Vec<f64>) -> SectionState {
        let zeros = vec![0.0; n];
        SectionState {
            t: 0.0,
            q: zeros.clone(),
            v: zeros.clone(),
            a: zeros.clone(),
            force: zeros.clone(),
            elastic: zeros.clone(),
            reaction: zeros.clone(),
            stepped_contact: zeros,
            lambda,
            contact: ContactSummary {
                crossing: [f64::NAN; 2],
                ..ContactSummary::default()
            },
            rollers: Vec::new(),
            bend_now: [0.0; 2],
            bend_step: [0.0; 2],
            largest: [0.0; 2],
            strain_energy: None,
            newton_iterations: 0,
            reduced: Vec::new(),
            outside: Vec::new(),
            ledger: energy::EnergyLedger::default(),
        }
    }
}

/// The nonlinear section unit.
pub struct NonlinearSection {
    params: NonlinearParams,
    description: UnitDescription,
    model: Model,
    environment: Environment,
    ends: Vec<Resolved>,
    m: SymmetricBand,
    c: Option<SymmetricBand>,
    /// Nodal loads of a unit x and z distributed load per `params.loads` entry.
    patterns: Vec<[Vec<f64>; 2]>,
    /// Weight and buoyancy (N).
    weight: Vec<f64>,
    /// Critical step 2 / omega_max of the tangent at the start of the dynamics (s).
    critical_step: f64,
    /// Whether a node has a held DOF (a reaction acts there): its net load is
    /// no distributed load (see `moments.rs`).
    held_nodes: Vec<bool>,
    /// Whether the first and the last node's rotation is free or loaded by a
    /// given moment (not held, not coupled): where the end elements'
    /// fixed-end moments load (`moments.rs`).
    free_end_rotation: [bool; 2],
    /// The drag (N, N m per DOF) at the state of the last `refresh_forces`
    /// (zero without drag), for the energy balance.
    drag_at_state: Vec<f64>,
    /// Each element's state at the last `refresh_forces` (local forces,
    /// strain energy), read by the extremes right after it.
    element_states: Vec<element::ElementState>,
    state: SectionState,
    // Scratch.
    hht: HhtAlpha,
    explicit: CentralDifference,
    work: dynamics::StepWork,
    jacobian_work: jacobian::JacobianWork,
    /// The linear model about the start (`linear = true`), after `initialize`.
    linear: Option<linear::Linearised>,
    /// The basis about the start (`reduced_modes`), formed at the first step
    /// after `initialize` (`reduced::ensure_reduced`): the master's initial
    /// iterates initialise a unit many times (15 on the riser), and the basis
    /// (a dense eigen-solve and second differences) is only needed to step.
    reduction: Option<Box<reduced::Reduction>>,
    /// The start's right-hand side f - C v - g (held DOFs: their
    /// accelerations) from `initialize`, from which the reduced start is set.
    reduced_start_rhs: Vec<f64>,
    /// The state at the end of `initialize`, about which the basis is formed
    /// (a reduced section only).
    reduced_origin: Option<Box<SectionState>>,
}

impl NonlinearSection {
    /// Builds the unit; fails with the first bad parameter.
    pub fn new(params: NonlinearParams) -> Result<NonlinearSection, UnitError> {
        params.validate()?;
        linear::validate(&params)?;
        reduced::validate(&params)?;
        let model = Model::new(&params);
        let n = model.dofs();
        let (ends, inputs) = ends::resolve(&params, model.reference.len());
        let mut outputs = ends::output_ports(&ends, params.stations.len());
        if params.reduced_sampling.is_some() {
            // How many terms the sample holds: what a sampled section costs.
            outputs.push(Port::output("sampled_terms", PortKind::Generic).with_unit("1"));
        }
        let mut weight = vec![0.0; n];
        for (i, s) in params.segments.iter().enumerate() {
            let range = segment_range(&model, i);
            model.add_distributed([0.0, -s.submerged_weight], range, &mut weight);
        }
        let patterns = params
            .loads
            .iter()
            .map(|l| {
                let mut px = vec![0.0; n];
                let mut pz = vec![0.0; n];
                model.add_distributed([1.0, 0.0], (l.from, l.to), &mut px);
                model.add_distributed([0.0, 1.0], (l.from, l.to), &mut pz);
                [px, pz]
            })
            .collect();
        let alpha = match params.integrator {
            Integrator::Hht { alpha, .. } => alpha,
            Integrator::EnergyConserving { .. } | Integrator::CentralDifference => 0.0,
        };
        let environment = Environment::new(&params, &model);
        // Formed about the start state by `initialize`.
        let m = SymmetricBand::zeros(n, BAND);
        let mut section = NonlinearSection {
            description: UnitDescription {
                kind: "nonlinear".into(),
                inputs,
                outputs,
                capabilities: Capabilities::default(),
            },
            state: SectionState::at_rest(n, environment.contacts.initial_lambda()),
            environment,
            hht: HhtAlpha::new(alpha, n, BAND),
            explicit: CentralDifference::new(),
            work: dynamics::StepWork::default(),
            jacobian_work: jacobian::JacobianWork::default(),
            linear: None,
            reduction: None,
            reduced_start_rhs: Vec::new(),
            reduced_origin: None,
            c: None,
            m,
            critical_step: f64::NAN,
            held_nodes: Vec::new(),
            free_end_rotation: [true; 2],
            drag_at_state: vec![0.0; n],
            element_states: Vec::new(),
            patterns,
            weight,
            ends,
            model,
            params,
        };
        section.check_reduced_size()?;
        section.mark_held_ends();
        section.description.capabilities.step_jacobian = section.offers_jacobian();
        section.description.capabilities.step_correction = section.offers_correction();
        if section.offers_jacobian() {
            section.hht.keep_newton_matrix();
        }
        section.hht.predict_start();
        Ok(section)
    }

    /// The mesh.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// Displacements (m, rad) at the current time, three per node.
    pub fn displacements(&self) -> &[f64] {
        &self.state.q
    }

    /// Velocities at the current time.
    pub fn velocities(&self) -> &[f64] {
        &self.state.v
    }

    /// Node positions (m) at the current time.
    pub fn positions(&self) -> Vec<[f64; 2]> {
        self.model.positions(&self.state.q)
    }

    /// The Newton matrix of the last implicit iteration (for solver comparisons).
    pub fn newton_matrix(&self) -> &SymmetricBand {
        self.hht.newton_matrix()
    }

    /// The critical step of central differences (s), after `initialize`.
    pub fn critical_step(&self) -> f64 {
        self.critical_step
    }

    /// The mass matrix of the dynamics (kg, kg m^2), banded.
    pub fn mass_matrix(&self) -> &SymmetricBand {
        &self.m
    }

    /// The end DOFs loaded by a concentrated force or moment (given or coupled),
    /// in increasing order: where a reduced basis needs the static response.
    pub fn loaded_end_dofs(&self) -> Vec<usize> {
        let mut loaded: Vec<usize> = self
            .ends
            .iter()
            .filter(|r| matches!(r.condition, params::DofCondition::Force(_)))
            .map(|r| r.dof)
            .collect();
        loaded.sort_unstable();
        loaded.dedup();
        loaded
    }

    /// The DOF each coupled end load's input adds to, one-for-one (N or N m
    /// per unit input): (input port, model DOF).
    pub fn input_load_dofs(&self) -> Vec<(usize, usize)> {
        (self.ends.iter())
            .filter(|r| matches!(r.condition, params::DofCondition::Force(_)))
            .filter_map(|r| Some((r.input?, r.dof)))
            .collect()
    }

    /// The DOFs held by kinematic end and support conditions (prescribed or
    /// coupled motion), in increasing order.
    pub fn held_dofs(&self) -> Vec<usize> {
        let mut held: Vec<usize> = self.held().map(|r| r.dof).collect();
        held.sort_unstable();
        held.dedup();
        held
    }

    /// The support reactions (N, N m) at the held DOFs (zero elsewhere).
    pub fn reactions(&self) -> &[f64] {
        &self.state.reaction
    }

    /// Newton iterations of the last step or static solve.
    pub fn last_newton_iterations(&self) -> u32 {
        self.state.newton_iterations
    }

    /// The external load at time `t` (weight, distributed loads, end loads;
    /// coupled ones read from `inputs` at fraction `s` of the coupling step)
    /// into `out` (N, N m; all DOFs): what a reduced model of the section
    /// projects.
    pub fn load_at(&self, inputs: Inputs<'_>, t: f64, s: f64, out: &mut [f64]) {
        self.external_load(inputs, (t, s), out);
    }

    /// Number of stations (`stations`).
    pub fn station_count(&self) -> usize {
        self.params.stations.len()
    }

    /// The stations' arc lengths (m).
    pub fn stations(&self) -> &[f64] {
        &self.params.stations
    }

    /// Whether every held DOF stays at its stress-free value (no prescribed or
    /// coupled motion): the condition for a reduced model about the
    /// stress-free state.
    pub fn held_at_rest(&self) -> bool {
        self.held()
            .all(|r| matches!(r.condition, params::DofCondition::Held))
    }

    /// External load at time t (weight, distributed loads, end loads; coupled ones
    /// read at fraction `s` of the coupling step) into `out`, with the end
    /// elements' load moments at the state (`moments.rs`).
    fn external_load(&self, inputs: Inputs<'_>, (t, s): (f64, f64), out: &mut [f64]) {
        self.applied_load(inputs, (t, s), out);
        self.add_end_load_moments((&self.state.q, t), 1.0, out);
    }

    /// [`Self::external_load`] without the end elements' load moments (the
    /// statics add them at each iterate).
    fn applied_load(&self, inputs: Inputs<'_>, (t, s): (f64, f64), out: &mut [f64]) {
        out.copy_from_slice(&self.weight);
        for (l, [px, pz]) in self.params.loads.iter().zip(&self.patterns) {
            let fx = l.x.eval(t).map_or(0.0, |v| v[0]);
            let fz = l.z.eval(t).map_or(0.0, |v| v[0]);
            for i in 0..out.len() {
                out[i] += fx * px[i] + fz * pz[i];
            }
        }
        for r in &self.ends {
            out[r.dof] += r.load(inputs, t, s);
        }
    }

    fn held(&self) -> impl Iterator<Item = &Resolved> + '_ {
        self.ends.iter().filter(|r| r.is_kinematic())
    }

    /// The touchdown point (m of arc) as a continuous function of the state:
    /// where the seabed gap crosses zero, linear between the nodes; None
    /// without seabed contact.
    pub fn seabed_crossing(&self) -> Option<f64> {
        self.environment
            .contacts
            .seabed_crossing(&self.model, (&self.state.q, self.state.t))
    }

    /// Position (m) at arc length `s`, linear between the nodes.
    pub fn position_at(&self, s: f64) -> [f64; 2] {
        self.model.position_at(&self.state.q, s)
    }

    /// The tangent's angle (rad, from +x, along increasing arc length) at
    /// node `node`: its element's stress-free angle turned by the node's
    /// rotation.
    pub fn tangent_angle_at_node(&self, node: usize) -> f64 {
        let e = node.min(self.model.elements.len() - 1);
        let element = &self.model.elements[e];
        element.sin0.atan2(element.cos0) + self.state.q[3 * node + 2]
    }
}

/// The arc-length range of segment `i`.
fn segment_range(model: &Model, i: usize) -> (f64, f64) {
    let first = model.segment_of.iter().position(|&s| s == i).unwrap_or(0);
    let last = model.segment_of.iter().rposition(|&s| s == i).unwrap_or(0);
    (model.arc[first], model.arc[last + 1])
}

impl Unit for NonlinearSection {
    fn description(&self) -> &UnitDescription {
        &self.description
    }

    /// With a static start, the end loads its statics are solved under.
    fn static_inputs(&self) -> Vec<usize> {
        self.description
            .static_load_inputs(self.params.static_start)
    }

    fn initialize(&mut self, t0: Time, inputs: Inputs<'_>) -> Result<(), UnitError> {
        self.jacobian_work.ready = false;
        self.state.t = t0.as_secs();
        self.state.q.fill(0.0);
        self.state.v.fill(0.0);
        self.state.lambda = self.environment.contacts.initial_lambda();
        self.state.reduced.clear();
        if self.params.static_start {
            self.solve_static(inputs)?;
        }
        self.prepare_dynamics()?;
        self.linearise()?;
        self.reduction = None;
        self.initial_acceleration(inputs)?;
        if self.params.reduced_modes.is_some() {
            match self.reduced_origin.as_mut() {
                Some(origin) => (**origin).clone_from(&self.state),
                None => self.reduced_origin = Some(Box::new(self.state.clone())),
            }
        }
        Ok(())
    }

    fn fields(&self) -> Vec<Field> {
        self.field_list()
    }

    fn field_values(&self, index: usize, out: &mut [f64]) -> Result<(), UnitError> {
        self.write_field(index, out)
    }

    fn local_error(&self) -> Option<f64> {
        self.local_displacement_error()
    }

    fn do_step(&mut self, t: Time, h: Time, inputs: Inputs<'_>) -> Result<StepReport, UnitError> {
        self.ensure_reduced()?;
        let iterations = self.step(inputs, t.as_secs(), (t + h).as_secs(), h.as_secs())?;
        Ok(StepReport {
            solver_iterations: iterations,
        })
    }

    fn outputs(&self, inputs: Inputs<'_>, out: &mut [f64]) {
        let nodes = self.model.reference.len();
        for end in 0..2 {
            let node = if end == 0 { 0 } else { nodes - 1 };
            let d = 3 * node;
            let r = self.model.reference[node];
            let base = 9 * end;
            out[base] = r[0] + self.state.q[d];
            out[base + 1] = r[1] + self.state.q[d + 1];
            out[base + 2] = self.state.q[d + 2];
            out[base + 3..base + 6].copy_from_slice(&self.state.v[d..d + 3]);
            // The force on what holds the end: minus the support reaction.
            for k in 0..3 {
                out[base + 6 + k] = -self.state.reaction[d + k];
            }
            for c in self
                .ends
                .iter()
                .filter(|c| c.end == end && !c.is_kinematic())
            {
                out[base + 6 + c.component] = -c.load(inputs, self.state.t, 1.0);
            }
        }
        if self.work.end_pending {
            // The rest is the step's end's, taken with it (`deferred_end.rs`).
            return;
        }
        let energies = self.energies();
        let [kinetic, strain, potential] = energies;
        let [max_moment, max_tension] = self.state.largest;
        let extra = [
            kinetic,
            strain,
            potential,
            f64::from(self.state.newton_iterations),
            // Outputs stay finite: 0 for "not computed" and "nothing in contact".
            if self.critical_step.is_finite() {
                self.critical_step
            } else {
                0.0
            },
            // `touchdown` is `touchdown_arc`: one definition (issue 49 #4).
            finite_or_zero(self.state.contact.crossing[0]),
            self.state.contact.length,
            max_moment,
            max_tension,
            self.state.bend_step[0],
            self.state.bend_step[1],
            finite_or_zero(self.state.contact.crossing[0]),
            finite_or_zero(self.state.contact.crossing[1]),
            self.external_work(),
            self.energy_error(energies),
            // The magnitude of each end's force (x, z): a riser's top tension.
            out[6].hypot(out[7]),
            out[15].hypot(out[16]),
        ];
        let stations = 18 + extra.len();
        out[18..stations].copy_from_slice(&extra);
        for (i, &s) in self.params.stations.iter().enumerate() {
            let base = stations + STATION_OUTPUTS * i;
            out[base..base + 3].copy_from_slice(&self.section_forces(s));
            out[base + 3..base + 5].copy_from_slice(&self.position_at(s));
            out[base + 5] = self.internal_force(s);
        }
        if self.params.reduced_sampling.is_some() {
            // 0 until the training window ends.
            let picked = self.sample_size().map_or(0, |(picked, _)| picked);
            out[stations + STATION_OUTPUTS * self.params.stations.len()] = picked as f64;
        }
    }

    slender_contract::state_in_field!(state: SectionState, |unit| {
        unit.jacobian_work.ready = false;
        unit.work.end_pending = false;
    });

    fn step_jacobian(&mut self, inputs: Inputs<'_>, jacobian: &mut [f64]) -> Result<(), UnitError> {
        self.interface_jacobian(inputs, jacobian)
    }

    fn correct_step(&mut self, inputs: Inputs<'_>, change: &[f64]) -> Result<(), UnitError> {
        self.correct_last_step(inputs, change)
    }

    fn warm_repeat(&mut self) {
        self.jacobian_work.warm.warm = true;
    }

    fn defer_step_end(&mut self, coupled: &[usize]) {
        self.work.defer_next = self.can_defer_end(coupled);
    }

    fn complete_step(&mut self) -> Result<bool, UnitError> {
        self.complete_pending_end()
    }

    fn modes(&self, count: usize) -> Result<crate::contract::ModalAnalysis, UnitError> {
        modes::modes(self, count)
    }
}

/// Outputs stay finite: 0 stands for "nothing in contact".
fn finite_or_zero(x: f64) -> f64 {
    if x.is_finite() { x } else { 0.0 }
}

#[cfg(test)]
mod tests;
