//! Beam unit (seed 004): an Euler-Bernoulli beam with Hermite cubic elements,
//! consistent mass, Rayleigh and viscous damping, a distributed load, two boundary
//! conditions per end (each a function of time or a coupled input), contact with a
//! surface, and HHT-alpha time integration with Newton iterations on the contact
//! terms. A static solver for the same model gives the equilibrium.
//!
//! Outputs are the four end quantities at both ends (a prescribed one as given,
//! the others from the state or, for moment and shear at a kinematically held end,
//! from the reaction), the energies and the contact region, so a beam can be one
//! section of a pipe coupled to its neighbours.

pub mod boundary;
pub mod elements;
pub mod params;
pub mod touchdown;

use crate::contact::surface::Surface;
use crate::contract::StateSlot;
use crate::contract::Time;
use crate::contract::{Capabilities, StepReport, Unit, UnitDescription, UnitError};
use crate::contract::{Inputs, Port, PortKind, require_finite_state};
use crate::integrators::hht::HhtAlpha;
use crate::numerics::banded::SymmetricBand;
use boundary::{Quantity, TimeFunction};
pub use params::{BeamParams, ContactIntegration, ContactParams, InitialShape};

/// Output names after the eight end quantities.
const EXTRA_OUTPUTS: [&str; 8] = [
    "kinetic_energy",
    "strain_energy",
    "contact_energy",
    "contact_start",
    "contact_end",
    "contact_length",
    "max_penetration",
    "newton_iterations",
];

/// A contact integration point.
#[derive(Clone, Debug)]
struct ContactPoint {
    element: usize,
    x: f64,
    weight: f64,
    shape: [f64; 4],
}

/// Contact evaluated at one state.
#[derive(Clone, Debug, Default)]
struct ContactValues {
    /// Nodal force vector (N) of the contact law and contact damping.
    force: Vec<f64>,
    energy: f64,
    start: f64,
    end: f64,
    length: f64,
    max_penetration: f64,
}

/// A condition resolved to a DOF.
#[derive(Clone, Debug)]
struct ResolvedCondition {
    end: usize,
    quantity: Quantity,
    dof: usize,
    value: TimeFunction,
    /// Input port index when coupled.
    input: Option<usize>,
}

crate::state_struct! {
    /// Everything that changes while stepping.
    #[derive(Debug, serde::Serialize, serde::Deserialize)]
    struct BeamState {
        t: f64,
        q: Vec<f64>,
        v: Vec<f64>,
        a: Vec<f64>,
        /// Lagrangian parameter per contact point.
        lambda: Vec<f64>,
        /// Gap per contact point at the current time (energy-conserving law).
        gap: Vec<f64>,
        /// Contact force vector at the current time (HHT weighting).
        contact_force: Vec<f64>,
        /// Residual at the current time (reactions at held DOFs).
        reaction: Vec<f64>,
        contact: [f64; 5],
        newton_iterations: u32,
    }
}

/// The beam unit.
pub struct Beam {
    params: BeamParams,
    description: UnitDescription,
    lengths: Vec<f64>,
    m: SymmetricBand,
    c: SymmetricBand,
    k: SymmetricBand,
    distributed: Vec<f64>,
    conditions: Vec<ResolvedCondition>,
    points: Vec<ContactPoint>,
    state: BeamState,
    // Scratch.
    /// The shared HHT-alpha integrator with its matrices and buffers.
    hht: HhtAlpha,
    /// Buffers of the time step.
    work: dynamics::StepWork,
    /// Contact evaluated in the step.
    step_contact: ContactValues,
    /// The step Jacobian's buffers.
    jacobian: jacobian::JacobianWork,
}

fn port_kind(q: Quantity) -> PortKind {
    match q {
        Quantity::Deflection => PortKind::Displacement,
        Quantity::Rotation => PortKind::Rotation,
        Quantity::Moment => PortKind::Moment,
        Quantity::Shear => PortKind::Force,
    }
}

impl Beam {
    /// Builds the unit; fails with the first bad parameter.
    pub fn new(params: BeamParams) -> Result<Beam, UnitError> {
        params.validate()?;
        let lengths = params.lengths();
        let nodes = lengths.len() + 1;
        let n = 2 * nodes;
        let m = elements::mass(params.mass_per_length, &lengths);
        let mut k = elements::stiffness(params.flexural_rigidity, &lengths);
        elements::add_geometric_stiffness(&mut k, params.tension, &lengths);
        let mut c = SymmetricBand::zeros(n, elements::BAND);
        c.set_combination(&[
            (
                params.rayleigh_mass + params.damping_per_length / params.mass_per_length,
                &m,
            ),
            (params.rayleigh_stiffness, &k),
        ]);
        let mut distributed = vec![0.0; n];
        if !params.distributed_load.is_empty() {
            let coefficients = params.distributed_load.clone();
            elements::load(
                |x| params::polynomial(&coefficients, x).0,
                &lengths,
                &mut distributed,
            );
        }
        let (conditions, inputs) = resolve_conditions(&params, nodes);
        let outputs = output_ports(&conditions, params.stations.len());
        let points = contact_points(&params, &lengths);
        let lambda0 = params.contact.as_ref().map_or(0.0, |c| c.method.lambda0());
        let n_points = points.len();
        // The energy-conserving contact law steps a discrete gradient: no step
        // Jacobian from the Newton matrix then.
        let step_jacobian = !matches!(
            params.contact.as_ref().map(|c| &c.method),
            Some(crate::contact::Law::EnergyConserving { .. })
        );
        Ok(Beam {
            description: UnitDescription {
                kind: "beam".into(),
                inputs,
                outputs,
                capabilities: Capabilities {
                    step_jacobian,
                    ..Capabilities::default()
                },
            },
            state: BeamState {
                t: 0.0,
                q: vec![0.0; n],
                v: vec![0.0; n],
                a: vec![0.0; n],
                lambda: vec![lambda0; n_points],
                gap: vec![0.0; n_points],
                contact_force: vec![0.0; n],
                reaction: vec![0.0; n],
                contact: [0.0; 5],
                newton_iterations: 0,
            },
            hht: HhtAlpha::new(params.alpha, n, elements::BAND),
            work: dynamics::StepWork::default(),
            step_contact: ContactValues::default(),
            jacobian: jacobian::JacobianWork::default(),
            params,
            lengths,
            m,
            c,
            k,
            distributed,
            conditions,
            points,
        })
    }

    /// Node positions x (m).
    pub fn node_positions(&self) -> Vec<f64> {
        let mut x = vec![0.0];
        for l in &self.lengths {
            x.push(x.last().copied().unwrap_or(0.0) + l);
        }
        x
    }

    /// Nodal deflections (m) and rotations at the current time.
    pub fn deflections(&self) -> Vec<[f64; 2]> {
        self.state.q.chunks(2).map(|c| [c[0], c[1]]).collect()
    }

    /// Deflection (m) at x from the element's Hermite interpolation.
    pub fn deflection_at(&self, x: f64) -> f64 {
        let mut x0 = 0.0;
        for (e, &l) in self.lengths.iter().enumerate() {
            if x <= x0 + l || e + 1 == self.lengths.len() {
                let n = elements::shape(((x - x0) / l).clamp(0.0, 1.0), l);
                return (0..4).map(|i| n[i] * self.state.q[2 * e + i]).sum();
            }
            x0 += l;
        }
        0.0
    }

    /// Replaces the initial state (after `initialize`) by the shape `f(x) -> (y, y')`
    /// at rest, and recomputes the consistent initial acceleration.
    pub fn set_initial_shape(
        &mut self,
        inputs: Inputs<'_>,
        f: impl Fn(f64) -> (f64, f64),
    ) -> Result<(), UnitError> {
        self.place_at_rest(f);
        self.initial_acceleration(inputs)
    }

    /// Nodal deflections and slopes from `f(x) -> (y, y')`, velocities zero.
    fn place_at_rest(&mut self, f: impl Fn(f64) -> (f64, f64)) {
        for (j, x) in self.node_positions().into_iter().enumerate() {
            let (y, slope) = f(x);
            self.state.q[2 * j] = y;
            self.state.q[2 * j + 1] = slope;
        }
        self.state.v.fill(0.0);
    }

    /// Newton iterations of the last step or static solve.
    pub fn last_newton_iterations(&self) -> u32 {
        self.state.newton_iterations
    }

    /// The prescribed value, rate and acceleration of condition `c` at time t (for
    /// inputs: end value, ramp slope, change of slope over h).
    fn prescribed(&self, inputs: Inputs<'_>, c: &ResolvedCondition, t: f64, h: f64) -> [f64; 3] {
        match (c.value.eval(t), c.input) {
            (Some(v), _) => v,
            (None, Some(i)) => {
                let value = inputs.at(i, 1.0);
                if h > 0.0 {
                    let rate = inputs.rate(i, h);
                    [value, rate, (rate - self.state.v[c.dof]) / h]
                } else {
                    [value, 0.0, 0.0]
                }
            }
            (None, None) => [0.0; 3],
        }
    }

    /// External load vector at time t (distributed load and prescribed moment and
    /// shear), into `out`.
    fn external_load(&self, inputs: Inputs<'_>, t: f64, h: f64, out: &mut [f64]) {
        out.copy_from_slice(&self.distributed);
        for c in self
            .conditions
            .iter()
            .filter(|c| !c.quantity.is_kinematic())
        {
            let value = self.prescribed(inputs, c, t, h)[0];
            // Boundary terms of the weak form: moment EI y'' enters theta with +
            // at x = L and - at x = 0; shear EI y''' enters y with - at L, + at 0.
            let sign = match (c.quantity, c.end) {
                (Quantity::Moment, 1) | (Quantity::Shear, 0) => 1.0,
                _ => -1.0,
            };
            out[c.dof] += sign * value;
        }
    }

    /// Sets the kinematic conditions at time t into q, v, a.
    fn apply_kinematics(&mut self, inputs: Inputs<'_>, t: f64, h: f64) {
        for i in 0..self.conditions.len() {
            let c = &self.conditions[i];
            if c.quantity.is_kinematic() {
                let [y, v, a] = self.prescribed(inputs, c, t, h);
                let dof = c.dof;
                self.state.q[dof] = y;
                self.state.v[dof] = v;
                self.state.a[dof] = a;
            }
        }
    }

    fn held_dofs(&self) -> impl Iterator<Item = usize> + '_ {
        self.conditions
            .iter()
            .filter(|c| c.quantity.is_kinematic())
            .map(|c| c.dof)
    }

    /// Total mechanical energy (J): kinetic, strain and contact.
    pub fn energies(&self) -> [f64; 3] {
        [
            0.5 * self.m.quadratic_form(&self.state.v),
            0.5 * self.k.quadratic_form(&self.state.q),
            self.state.contact[0],
        ]
    }
}

mod contact;
mod dynamics;
mod jacobian;
mod statics;

impl Unit for Beam {
    fn description(&self) -> &UnitDescription {
        &self.description
    }

    /// With a static start, the end loads its statics are solved under.
    fn static_inputs(&self) -> Vec<usize> {
        self.description
            .static_load_inputs(self.params.static_start)
    }

    fn initialize(&mut self, t0: Time, inputs: Inputs<'_>) -> Result<(), UnitError> {
        self.jacobian.ready = false;
        self.state.t = t0.as_secs();
        let x = self.node_positions();
        for (j, &xj) in x.iter().enumerate() {
            let (y, dy) = params::polynomial(&self.params.initial_deflection, xj);
            let (v, dv) = params::polynomial(&self.params.initial_velocity, xj);
            self.state.q[2 * j] = y;
            self.state.q[2 * j + 1] = dy;
            self.state.v[2 * j] = v;
            self.state.v[2 * j + 1] = dv;
        }
        let lambda0 = self
            .params
            .contact
            .as_ref()
            .map_or(0.0, |c| c.method.lambda0());
        self.state.lambda.fill(lambda0);
        if let Some(shape) = self.params.initial_shape.clone() {
            self.place_at_rest(|x| shape.at(x));
        }
        if self.params.static_start {
            self.solve_static(inputs)?;
        } else {
            self.initial_acceleration(inputs)?;
            // A penalty-type law would fire the pipe off a surface it starts deep in.
            let depth = self.state.contact[4];
            if depth > 0.01 * self.params.length {
                return Err(UnitError::Numerical(format!(
                    "the initial state penetrates the contact surface by {depth:.3} m (more than 1 % of the length): start above it or use static_start"
                )));
            }
        }
        Ok(())
    }

    fn do_step(&mut self, t: Time, h: Time, inputs: Inputs<'_>) -> Result<StepReport, UnitError> {
        self.jacobian.ready = false;
        let iterations = self.hht_step(inputs, t.as_secs(), (t + h).as_secs(), h.as_secs())?;
        require_finite_state("the beam's nodal displacements", &self.state.q)?;
        require_finite_state("the beam's nodal velocities", &self.state.v)?;
        self.jacobian.ready = self.description.capabilities.step_jacobian;
        self.jacobian.h = h.as_secs();
        Ok(StepReport {
            solver_iterations: iterations,
        })
    }

    fn outputs(&self, inputs: Inputs<'_>, out: &mut [f64]) {
        let nodes = self.state.q.len() / 2;
        for end in 0..2 {
            let node = if end == 0 { 0 } else { nodes - 1 };
            let (y, th) = (self.state.q[2 * node], self.state.q[2 * node + 1]);
            let (ry, rth) = (
                self.state.reaction[2 * node],
                self.state.reaction[2 * node + 1],
            );
            // Reaction R = support force on the beam = the boundary load it replaces.
            let (moment, shear) = if end == 0 { (-rth, ry) } else { (rth, -ry) };
            let base = 4 * end;
            out[base] = y;
            out[base + 1] = th;
            out[base + 2] = moment;
            out[base + 3] = shear;
            for c in self
                .conditions
                .iter()
                .filter(|c| c.end == end && !c.quantity.is_kinematic())
            {
                let value = self.prescribed(inputs, c, self.state.t, 0.0)[0];
                out[base + if c.quantity == Quantity::Moment { 2 } else { 3 }] = value;
            }
        }
        let e = self.energies();
        out[8] = e[0];
        out[9] = e[1];
        out[10] = e[2];
        out[11] = self.state.contact[1];
        out[12] = self.state.contact[2];
        out[13] = self.state.contact[3];
        out[14] = self.state.contact[4];
        out[15] = f64::from(self.state.newton_iterations);
        for (i, &x) in self.params.stations.iter().enumerate() {
            out[16 + i] = self.deflection_at(x);
        }
    }

    fn save_state(&self, slot: &mut StateSlot) -> Result<(), UnitError> {
        slot.store(&self.state);
        Ok(())
    }

    fn step_jacobian(&mut self, inputs: Inputs<'_>, jacobian: &mut [f64]) -> Result<(), UnitError> {
        self.interface_jacobian(inputs, jacobian)
    }

    fn restore_state(&mut self, slot: &StateSlot) -> Result<(), UnitError> {
        self.jacobian.ready = false;
        self.state.clone_from(&*slot.load::<BeamState>()?);
        Ok(())
    }

    /// Over the nodes' deflections (DOFs 2j).
    fn local_error(&self) -> Option<f64> {
        Some(self.hht.local_error(|d| d % 2 == 0))
    }

    fn modes(&self, count: usize) -> Result<crate::contract::ModalAnalysis, UnitError> {
        dynamics::modes(self, count)
    }
}

/// Each boundary condition with its DOF, and the input ports of the coupled ones.
fn resolve_conditions(params: &BeamParams, nodes: usize) -> (Vec<ResolvedCondition>, Vec<Port>) {
    let mut inputs = Vec::new();
    let mut conditions = Vec::new();
    for (end, cond) in params.boundary.all() {
        let node = if end == 0 { 0 } else { nodes - 1 };
        let side = if end == 0 { "left" } else { "right" };
        let input = matches!(cond.value, TimeFunction::Input(_)).then(|| {
            inputs.push(Port::input(
                &format!("{side}_{}", cond.quantity.name()),
                port_kind(cond.quantity),
            ));
            inputs.len() - 1
        });
        conditions.push(ResolvedCondition {
            end,
            quantity: cond.quantity,
            dof: 2 * node + cond.quantity.dof(),
            value: cond.value.clone(),
            input,
        });
    }
    (conditions, inputs)
}

/// The four end quantities at both ends (a moment or shear prescribed by a
/// coupled input is that input: it depends on it directly), the energies and
/// contact region, and the deflection at each of `stations`.
fn output_ports(conditions: &[ResolvedCondition], stations: usize) -> Vec<Port> {
    let mut outputs = Vec::new();
    for (end, side) in ["left", "right"].iter().enumerate() {
        for q in [
            Quantity::Deflection,
            Quantity::Rotation,
            Quantity::Moment,
            Quantity::Shear,
        ] {
            let held: Vec<usize> = conditions
                .iter()
                .filter(|c| c.end == end && c.quantity == q && !q.is_kinematic())
                .filter_map(|c| c.input)
                .collect();
            let p = Port::output(&format!("{side}_{}", q.name()), port_kind(q));
            outputs.push(p.with_feedthrough(&held));
        }
    }
    for name in EXTRA_OUTPUTS {
        let unit = match name {
            n if n.ends_with("energy") => "J",
            "newton_iterations" => "",
            _ => "m",
        };
        outputs.push(Port::output(name, PortKind::Generic).with_unit(unit));
    }
    for i in 0..stations {
        outputs.push(Port::output(
            &format!("deflection_{}", i + 1),
            PortKind::Displacement,
        ));
    }
    outputs
}

/// The contact integration points (Gauss or trapezoid per element), none without
/// contact.
fn contact_points(params: &BeamParams, lengths: &[f64]) -> Vec<ContactPoint> {
    let mut points = Vec::new();
    if let Some(contact) = &params.contact {
        let mut x0 = 0.0;
        for (e, &l) in lengths.iter().enumerate() {
            let rule: &[(f64, f64)] = match contact.integration {
                ContactIntegration::Gauss => &elements::GAUSS,
                ContactIntegration::Trapezoid => &[(0.0, 0.5), (1.0, 0.5)],
            };
            for &(xi, w) in rule {
                points.push(ContactPoint {
                    element: e,
                    x: x0 + xi * l,
                    weight: w * l,
                    shape: elements::shape(xi, l),
                });
            }
            x0 += l;
        }
    }
    points
}

/// Beam changes that depend on the inputs, through the driver that holds them
/// (a trait: the driver is the contract crate's type).
pub trait BeamDriver {
    /// [`Beam::set_initial_shape`] with the driver's inputs (after `initialize`).
    fn set_initial_shape(&mut self, f: impl Fn(f64) -> (f64, f64)) -> Result<(), UnitError>;
}

impl BeamDriver for crate::contract::Driver<Beam> {
    fn set_initial_shape(&mut self, f: impl Fn(f64) -> (f64, f64)) -> Result<(), UnitError> {
        let (beam, inputs) = self.unit_mut_with_inputs();
        beam.set_initial_shape(inputs, f)
    }
}

/// The contact surface, for plots and tests.
impl Beam {
    /// The contact surface, when the beam has contact (for plots and tests).
    pub fn surface(&self) -> Option<&Surface> {
        self.params.contact.as_ref().map(|c| &c.surface)
    }
}
