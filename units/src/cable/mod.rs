//! Cable unit (seed 000's fixedFreeCableSegment): a 2D chain of bar elements
//! (2 DOFs per node) with structural and added mass, effective weight, elastic and
//! geometric stiffness, Rayleigh damping and Morison drag in a current.
//!
//! The static equilibrium under the top force is found by Newton-Raphson; the
//! dynamics is linear about it (M, K and element directions from the static
//! state) with the drag on the velocity relative to the water computed exactly
//! (quadratic), integrated by Newmark average acceleration with drag iterations on
//! one factorisation per step size.
//!
//! Boundary conditions are fixed-free: the bottom node's velocity is prescribed
//! (input; zero for an anchor), the top node's force is prescribed (input). Outputs
//! are the top velocity and the force the cable exerts on its bottom support, so
//! two sections couple force-to-top / velocity-to-bottom at a truncation point.

pub mod current;
pub mod drag;
pub mod elements;
mod fields;
pub mod params;
pub mod statics;

mod dynamics;
mod jacobian;
use crate::integrators::newmark_iterated::LoadIteration;
use dynamics::{CableStep, Dynamics, mat2};

use crate::contract::Time;
use crate::contract::{
    Capabilities, Field, ModalAnalysis, Mode, StepReport, Unit, UnitDescription, UnitError,
};
use crate::contract::{Hold, Inputs, Port, PortKind, require_finite_state};
use crate::numerics::banded::SymmetricBand;
use drag::Drag;
use elements::ElementProperties;
pub use params::{CableParams, Effects, Section};
use statics::{StaticLoads, StaticState, straight_guess, trailing_block};

/// Input indices.
const TOP_FX: usize = 0;
const TOP_FZ: usize = 1;
const BOTTOM_VX: usize = 2;
const BOTTOM_VZ: usize = 3;

/// Output names, in order.
pub const OUTPUTS: [&str; 8] = [
    "top_velocity_x",
    "top_velocity_z",
    "bottom_force_x",
    "bottom_force_z",
    "top_displacement_x",
    "top_displacement_z",
    "top_tension",
    "bottom_tension",
];

crate::state_struct! {
    /// Everything that changes while stepping.
    #[derive(Debug, serde::Serialize, serde::Deserialize)]
    struct CableState {
        q: Vec<f64>,
        v: Vec<f64>,
        a: Vec<f64>,
        qb: [f64; 2],
        vb: [f64; 2],
        ab: [f64; 2],
        bottom_force: [f64; 2],
    }
}

/// The cable unit.
pub struct Cable {
    params: CableParams,
    effects: Effects,
    description: UnitDescription,
    props: ElementProperties,
    loads: StaticLoads,
    /// First guess of the section's static positions (bottom first; the bottom node
    /// stays fixed there).
    guess: Vec<[f64; 2]>,
    dynamics: Option<Dynamics>,
    state: CableState,
    /// The step Jacobian's buffers.
    jacobian: jacobian::JacobianWork,
}

impl Cable {
    /// Builds the unit; for a lower or upper section solves the whole line's static
    /// equilibrium to place the truncation point.
    pub fn new(params: CableParams, effects: Effects) -> Result<Cable, UnitError> {
        params.validate()?;
        let area = std::f64::consts::PI * params.diameter * params.diameter / 4.0;
        let (can, cat) = if effects.added_mass {
            (params.added_mass_normal, params.added_mass_tangential)
        } else {
            (0.0, 0.0)
        };
        let props = ElementProperties {
            length: params.length / params.elements as f64,
            axial_stiffness: params.axial_stiffness(),
            mass_per_length: params.mass_per_length,
            added_mass_normal: params.water_density * area * can,
            added_mass_tangential: params.water_density * area * cat,
        };
        let loads = StaticLoads {
            weight: if effects.weight {
                params.submerged_weight
            } else {
                0.0
            },
            current: (effects.drag && effects.current).then(|| {
                (
                    params.water_density,
                    params.diameter,
                    params.drag_normal,
                    params.drag_tangential,
                    params.current.clone(),
                    params.water_depth,
                )
            }),
        };
        let guess = section_guess(&params, &props, &loads)?;
        let nodes = guess.len();
        let free = 2 * (nodes - 1);
        Ok(Cable {
            jacobian: jacobian::JacobianWork::default(),
            description: describe(),
            state: CableState {
                q: vec![0.0; free],
                v: vec![0.0; free],
                a: vec![0.0; free],
                qb: [0.0; 2],
                vb: [0.0; 2],
                ab: [0.0; 2],
                bottom_force: [0.0; 2],
            },
            params,
            effects,
            props,
            loads,
            guess,
            dynamics: None,
        })
    }

    /// Number of elements of this section.
    pub fn element_count(&self) -> usize {
        self.guess.len() - 1
    }

    /// The static state found by `initialize`.
    pub fn static_state(&self) -> Option<&StaticState> {
        self.dynamics.as_ref().map(|d| &d.statics)
    }

    /// Static position of the bottom node (m): the anchor, or the truncation point.
    pub fn bottom_position(&self) -> [f64; 2] {
        self.guess[0]
    }

    /// The first `count` modes of the linearised cable about its static state
    /// (generalised eigenproblem K phi = w^2 M phi on the free DOFs), longest first.
    fn cable_modes(&self, count: usize) -> Result<Vec<Mode>, UnitError> {
        let d = self
            .dynamics
            .as_ref()
            .ok_or_else(|| UnitError::Unsupported("modal analysis before initialize".into()))?;
        let pairs = crate::numerics::modal::lowest_modes(
            &d.m_ff.to_dense(),
            &d.k_ff.to_dense(),
            count,
            "the cable has a zero-stiffness mode (geometric stiffness off?)",
        )?;
        let mut modes = Vec::new();
        for (w2, phi) in pairs {
            let scale = phi.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            let mut shape = vec![[0.0; 2]];
            for j in 0..phi.len() / 2 {
                shape.push([phi[2 * j] / scale, phi[2 * j + 1] / scale]);
            }
            modes.push(Mode {
                period: 2.0 * std::f64::consts::PI / w2.sqrt(),
                shape,
            });
        }
        Ok(modes)
    }
}

/// The bottom's displacement and acceleration at the step's end for the end
/// velocity `vb`: under a ramp the exact displacement and the ramp's slope (the
/// Newmark recursion a = 2 dv / h - a_n would never let a velocity jump, e.g. the
/// end of a signal loss, die out); under a zero-order hold a constant velocity.
fn bottom_motion(s: &CableState, vb: [f64; 2], hold: Hold, h: f64) -> ([f64; 2], [f64; 2]) {
    match hold {
        Hold::Ramp => (
            [
                s.qb[0] + 0.5 * h * (s.vb[0] + vb[0]),
                s.qb[1] + 0.5 * h * (s.vb[1] + vb[1]),
            ],
            [(vb[0] - s.vb[0]) / h, (vb[1] - s.vb[1]) / h],
        ),
        Hold::ZeroOrder => ([s.qb[0] + h * vb[0], s.qb[1] + h * vb[1]], [0.0; 2]),
    }
}

/// The force on the bottom support (N): the static pull minus the bottom node's
/// dynamic equation, plus its drag change (`node_drag` at the final velocities).
fn support_force(d: &Dynamics, s: &CableState) -> [f64; 2] {
    let (qb, vb, ab) = (s.qb, s.vb, s.ab);
    let (a1, v1, q1) = ([s.a[0], s.a[1]], [s.v[0], s.v[1]], [s.q[0], s.q[1]]);
    let t = |m: &[[f64; 2]; 2], x: [f64; 2]| {
        [
            m[0][0] * x[0] + m[1][0] * x[1],
            m[0][1] * x[0] + m[1][1] * x[1],
        ]
    };
    let inertia = [mat2(&d.m_bb, ab), t(&d.m_fb, a1)];
    let damping = [mat2(&d.c_bb, vb), t(&d.c_fb, v1)];
    let elastic = [mat2(&d.k_bb, qb), t(&d.k_fb, q1)];
    std::array::from_fn(|c| {
        let dyn_eq = inertia[0][c]
            + inertia[1][c]
            + damping[0][c]
            + damping[1][c]
            + elastic[0][c]
            + elastic[1][c];
        let drag = if d.drag.is_some() {
            d.node_drag[0][c]
        } else {
            0.0
        };
        d.static_support_force[c] - dyn_eq + drag
    })
}

/// The first guess of a section's static positions (bottom first): a straight
/// line for the full line; for a section, the part below or above the node nearest
/// the truncation height of the full line's static shape.
fn section_guess(
    params: &CableParams,
    props: &ElementProperties,
    loads: &StaticLoads,
) -> Result<Vec<[f64; 2]>, UnitError> {
    match (params.section, params.static_top_force) {
        (Section::Full, f) => Ok(straight_guess(
            props,
            params.anchor,
            f.unwrap_or([0.0, 1.0]),
            params.elements,
        )),
        (Section::Lower { truncation_ratio }, Some(f))
        | (Section::Upper { truncation_ratio }, Some(f)) => {
            let full = statics::solve(
                props,
                loads,
                f,
                straight_guess(props, params.anchor, f, params.elements),
                params.static_tolerance,
            )?;
            statics::check_above_seabed(&full, params.anchor[1], f, params.length)?;
            let height = params.anchor[1] + truncation_ratio * params.water_depth;
            let top_z = full.positions[params.elements][1];
            let spacing = params.length / params.elements as f64;
            if top_z.is_nan()
                || top_z - params.anchor[1] <= truncation_ratio * params.water_depth + spacing
            {
                return Err(UnitError::parameter(
                    "section.truncation_ratio",
                    truncation_ratio,
                    &format!(
                        "the line's static top is at z = {top_z:.1} m: it does not reach the truncation height {height:.1} m by at least one element"
                    ),
                ));
            }
            let k = (1..params.elements)
                .min_by(|&a, &b| {
                    (full.positions[a][1] - height)
                        .abs()
                        .total_cmp(&(full.positions[b][1] - height).abs())
                })
                .ok_or_else(|| {
                    UnitError::parameter("elements", params.elements, "too few to split")
                })?;
            Ok(match params.section {
                Section::Lower { .. } => full.positions[..=k].to_vec(),
                _ => full.positions[k..].to_vec(),
            })
        }
        (_, None) => Err(UnitError::parameter(
            "static_top_force",
            "none",
            "a section needs the full line's static top force to place its cut",
        )),
    }
}

/// The cable's ports: forces in and velocities at the bottom in; top velocity and
/// displacement, bottom force and the end tensions out.
fn describe() -> UnitDescription {
    let inputs = vec![
        Port::input("top_force_x", PortKind::Force),
        Port::input("top_force_z", PortKind::Force),
        Port::input("bottom_velocity_x", PortKind::Velocity),
        Port::input("bottom_velocity_z", PortKind::Velocity),
    ];
    let kinds = [
        PortKind::Velocity,
        PortKind::Velocity,
        PortKind::Force,
        PortKind::Force,
        PortKind::Displacement,
        PortKind::Displacement,
        PortKind::Force,
        PortKind::Force,
    ];
    // No output follows an input at a communication point: the support force
    // holds the bottom node's inertia and damping over the step just taken, so
    // it changes with the bottom velocity through a step only.
    let outputs = OUTPUTS
        .iter()
        .zip(kinds)
        .map(|(name, kind)| Port::output(name, kind))
        .collect();
    UnitDescription {
        kind: "cable".into(),
        inputs,
        outputs,
        capabilities: Capabilities {
            step_jacobian: true,
            ..Capabilities::default()
        },
    }
}

impl Unit for Cable {
    fn description(&self) -> &UnitDescription {
        &self.description
    }

    fn fields(&self) -> Vec<Field> {
        self.field_list()
    }

    fn field_values(&self, index: usize, out: &mut [f64]) -> Result<(), UnitError> {
        self.write_field(index, out)
    }

    /// The top force: the statics are solved under it.
    fn static_inputs(&self) -> Vec<usize> {
        vec![TOP_FX, TOP_FZ]
    }

    fn initialize(&mut self, _t0: Time, inputs: Inputs<'_>) -> Result<(), UnitError> {
        self.jacobian.ready = false;
        let top = [inputs.at(TOP_FX, 1.0), inputs.at(TOP_FZ, 1.0)];
        let guess = match self.params.section {
            Section::Full if self.params.static_top_force.is_none() => {
                straight_guess(&self.props, self.params.anchor, top, self.params.elements)
            }
            _ => self.guess.clone(),
        };
        let statics = statics::solve(
            &self.props,
            &self.loads,
            top,
            guess,
            self.params.static_tolerance,
        )?;
        statics::check_above_seabed(&statics, self.params.anchor[1], top, self.params.length)?;
        let d = self.build_dynamics(statics, top)?;
        let s = &mut self.state;
        s.q.fill(0.0);
        s.v.fill(0.0);
        s.a.fill(0.0);
        s.qb = [0.0; 2];
        s.vb = [inputs.at(BOTTOM_VX, 1.0), inputs.at(BOTTOM_VZ, 1.0)];
        s.ab = [0.0; 2];
        s.bottom_force = d.static_support_force;
        self.dynamics = Some(d);
        Ok(())
    }

    fn do_step(&mut self, t: Time, h: Time, inputs: Inputs<'_>) -> Result<StepReport, UnitError> {
        let d = self
            .dynamics
            .as_mut()
            .ok_or_else(|| UnitError::Unsupported("do_step before initialize".into()))?;
        let t1 = (t + h).as_secs();
        let h = h.as_secs();
        let s = &mut self.state;
        let n = s.q.len();
        // Prescribed bottom motion at the step's end.
        let vb = [inputs.at(BOTTOM_VX, 1.0), inputs.at(BOTTOM_VZ, 1.0)];
        let (qb, ab) = bottom_motion(s, vb, inputs.hold(BOTTOM_VX), h);
        // The load at the step's end: the top force's change and the bottom
        // motion through the coupling blocks.
        let top = [
            inputs.at(TOP_FX, 1.0) - d.static_top_force[0],
            inputs.at(TOP_FZ, 1.0) - d.static_top_force[1],
        ];
        let coupling = {
            let (mfb, cfb, kfb) = (mat2(&d.m_fb, ab), mat2(&d.c_fb, vb), mat2(&d.k_fb, qb));
            [mfb[0] + cfb[0] + kfb[0], mfb[1] + cfb[1] + kfb[1]]
        };
        let end_load = |rhs: &mut [f64]| {
            rhs[n - 2] += top[0];
            rhs[n - 1] += top[1];
            rhs[0] -= coupling[0];
            rhs[1] -= coupling[1];
        };
        let iteration = LoadIteration {
            tolerance: self.params.drag_tolerance,
            max_iterations: 100,
        };
        let mut newmark = std::mem::take(&mut d.newmark);
        let mut step = CableStep {
            dynamics: d,
            state: s,
            vb,
        };
        let outcome = newmark.step(&mut step, t1, h, end_load, iteration);
        d.newmark = newmark;
        self.jacobian.ready = false;
        let iterations = outcome?;
        require_finite_state("the cable's nodal displacements", &s.q)?;
        require_finite_state("the cable's nodal velocities", &s.v)?;
        s.qb = qb;
        s.vb = vb;
        s.ab = ab;
        // Force on the support: static pull minus the bottom node's dynamic
        // equation, plus its drag change at the final velocities.
        if d.drag.is_some() {
            d.drag_change(&s.v, vb);
        }
        s.bottom_force = support_force(d, s);
        self.jacobian.ready = true;
        self.jacobian.h = h;
        Ok(StepReport {
            solver_iterations: iterations,
        })
    }

    fn outputs(&self, _inputs: Inputs<'_>, out: &mut [f64]) {
        let s = &self.state;
        let n = s.q.len();
        out[0] = s.v[n - 2];
        out[1] = s.v[n - 1];
        out[2] = s.bottom_force[0];
        out[3] = s.bottom_force[1];
        out[4] = s.q[n - 2];
        out[5] = s.q[n - 1];
        let (top, bottom) = match &self.dynamics {
            Some(d) => {
                let x = &d.statics.positions;
                let m = x.len() - 1;
                let ea = self.props.axial_stiffness / self.props.length;
                let (et, _, tt) = elements::element_state(&self.props, x[m - 1], x[m]);
                let (eb, _, tb) = elements::element_state(&self.props, x[0], x[1]);
                let below_top = if m >= 2 {
                    [s.q[n - 4], s.q[n - 3]]
                } else {
                    s.qb
                };
                let dt = [s.q[n - 2] - below_top[0], s.q[n - 1] - below_top[1]];
                let db = [s.q[0] - s.qb[0], s.q[1] - s.qb[1]];
                (
                    tt + ea * (et[0] * dt[0] + et[1] * dt[1]),
                    tb + ea * (eb[0] * db[0] + eb[1] * db[1]),
                )
            }
            None => (0.0, 0.0),
        };
        out[6] = top;
        out[7] = bottom;
    }

    slender_contract::state_in_field!(state: CableState, |unit| {
        unit.jacobian.ready = false;
    });

    fn step_jacobian(&mut self, inputs: Inputs<'_>, jacobian: &mut [f64]) -> Result<(), UnitError> {
        self.interface_jacobian(inputs, jacobian)
    }

    fn modes(&self, count: usize) -> Result<ModalAnalysis, UnitError> {
        let modes = self.cable_modes(count)?;
        let positions = self
            .static_state()
            .map(|s| s.positions.clone())
            .unwrap_or_default();
        Ok(ModalAnalysis { positions, modes })
    }
}
