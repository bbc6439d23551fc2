//! The 3D line linearised about its static state (`linear = true`): the
//! cheap fidelity of a section whose motion stays small about its
//! equilibrium (a mooring line's lower part, a riser's top), as the planar
//! section's `linear`.
//!
//! At `initialize`, after the statics, the tangent stiffness K of the bars,
//! the bending and the seabed's springs (at the nodes in contact then) and the
//! damping C of the axial damper, the seabed's dampers and friction at rest
//! (mu N / stick_velocity: the sticking line) are formed once; the line's own
//! force is then g(q, v) = g_s + K (q - q_s) + C v, and HHT-alpha solves each
//! step with one back-substitution of a matrix factorised once per step size
//! (once per step where the line has drag). The water's force (drag on the
//! relative velocity and the waves' inertia) is evaluated at the step's start
//! position and velocity, with the water's motion at the step's start and
//! end, its drag linearised there: the drag's velocity tangent D_0 joins the
//! step's damping and the rest F_w(v_0) + D_0 v_0 is a load, so the step's
//! water force is F_w(v_0) - D_0 (v - v_0), implicit in the velocity. Held
//! over the step instead, it lagged by O(h) (2.9e-2 of the fairlead force's
//! change at 0.1 s) and blew up past h ~ 2 m / D_0 (issue 48 item 7). Outputs (tension,
//! curvature, touchdown) are the nonlinear line's at the linear state; the
//! energies are the linear model's.
//!
//! What it does not represent: large rotations, a touchdown point that moves
//! (a node off the seabed at the start never touches it, one on it is held by
//! a bilateral spring), sliding on the seabed (friction is the sticking
//! line's damping).

use super::Line3d;
use super::mechanics::{BAND, DOF, add_block, node};
use crate::numerics::banded::SymmetricBand;
use nalgebra::{Matrix3, Vector3};

/// A node on the seabed at the start: the spring's stiffness and force there,
/// and the damper's and the friction's damping at rest.
#[derive(Clone, Debug)]
struct SeabedNode {
    node: usize,
    stiffness: Matrix3<f64>,
    /// Minus the spring's force at the start (N; as g holds it).
    force: Vector3<f64>,
    damper: Matrix3<f64>,
    friction: Matrix3<f64>,
}

/// The line's linear model about its start state.
#[derive(Clone, Debug)]
pub(super) struct Linearised {
    /// K: bars, bending and the seabed's springs at the start (N/m).
    pub stiffness: SymmetricBand,
    /// C: the axial damper, the seabed's dampers and friction at rest (N s/m).
    pub damping: SymmetricBand,
    /// The axial damper's part of C.
    axial: SymmetricBand,
    /// Whether the line has drag (else the step's damping is C throughout).
    pub has_drag: bool,
    /// The drag's velocity tangent D_0 at the step's start (N s/m).
    pub water_tangent: SymmetricBand,
    /// The step's damping: C + D_0 (N s/m).
    pub step_damping: SymmetricBand,
    /// g_s - K q_s: the line's force is K q + C v + offset (N).
    offset: Vec<f64>,
    /// g_s: the bars', bending's and seabed springs' force at the start (N).
    start_force: Vec<f64>,
    /// The start state q_s (m) and the bars' and bending's force there (N).
    start: Vec<f64>,
    elastic_start: Vec<f64>,
    /// Strain energy and the seabed spring's energy at the start (J).
    energy_start: [f64; 2],
    seabed: Vec<SeabedNode>,
    /// Scratch: q - q_s and K (q - q_s).
    dq: Vec<f64>,
    kdq: Vec<f64>,
}

impl Line3d {
    /// Forms the linear model about the static state `q` (no-op unless
    /// `linear = true`).
    pub(super) fn linearise(&mut self, q: &[f64]) {
        self.linear = None;
        if !self.params.linear {
            return;
        }
        let n = q.len();
        let rest = vec![0.0; n];
        let mut stiffness = SymmetricBand::zeros(n, BAND);
        let mut axial = SymmetricBand::zeros(n, BAND);
        let mut elastic_start = vec![0.0; n];
        let tangent = Some((&mut stiffness, 1.0, 0.0));
        self.mechanics
            .add_force(q, &rest, 1.0, tangent, &mut elastic_start);
        let mut scratch = vec![0.0; n];
        let tangent = Some((&mut axial, 0.0, 1.0));
        self.mechanics
            .add_force(q, &rest, 0.0, tangent, &mut scratch);
        let mut damping = axial.clone();
        let mut seabed = Vec::new();
        let mut offset = elastic_start.clone();
        for i in 0..self.mechanics.nodes {
            let Some((forces, t)) = self.environment.seabed_at_rest(q, i) else {
                continue;
            };
            add_block(&mut stiffness, i, i, &t.stiffness, 1.0);
            add_block(&mut damping, i, i, &(t.damper + t.friction), 1.0);
            for c in 0..DOF {
                offset[DOF * i + c] -= forces.seabed_spring[c];
            }
            seabed.push(SeabedNode {
                node: i,
                stiffness: t.stiffness,
                force: -forces.seabed_spring,
                damper: t.damper,
                friction: t.friction,
            });
        }
        let start_force = offset.clone();
        stiffness.mul_add(-1.0, q, &mut offset);
        let seabed_energy = self
            .environment
            .seabed
            .as_ref()
            .map_or(0.0, |s| self.environment.seabed_energy(s, q));
        self.linear = Some(Linearised {
            stiffness,
            has_drag: self.environment.has_drag(),
            water_tangent: SymmetricBand::zeros(n, BAND),
            step_damping: damping.clone(),
            damping,
            axial,
            offset,
            start_force,
            start: q.to_vec(),
            elastic_start,
            energy_start: [self.mechanics.strain_energy(q), seabed_energy],
            seabed,
            dq: vec![0.0; n],
            kdq: vec![0.0; n],
        });
    }
}

impl Linearised {
    /// The line's force at (q, v) into `force`: g_s + K (q - q_s) + (C +
    /// D_0) v (the displacement first, so the force keeps its digits), less
    /// the water's force's remainder `water` (N) the step took: with the
    /// step's D_0 v, the water's force the step used.
    pub(super) fn force(&mut self, q: &[f64], v: &[f64], water: &[f64], force: &mut [f64]) {
        for ((d, x), s) in self.dq.iter_mut().zip(q).zip(&self.start) {
            *d = x - s;
        }
        force.copy_from_slice(&self.start_force);
        self.stiffness.mul_add(1.0, &self.dq, force);
        self.step_damping.mul_add(1.0, v, force);
        for (f, w) in force.iter_mut().zip(water) {
            *f -= w;
        }
    }

    /// Takes the drag's tangent D_0 (in `water_tangent`, from the water's
    /// force at the step's start) into the step's damping C + D_0, and
    /// D_0 v_0 into the water's forces `water` at the step's start and end
    /// (N): each then the remainder F_w - D_0 v_0, so that the step's water
    /// force is F_w(v_0) - D_0 (v - v_0), implicit in the velocity.
    pub(super) fn linearise_water(&mut self, v0: &[f64], water: [&mut [f64]; 2]) {
        if !self.has_drag {
            return;
        }
        self.step_damping
            .set_combination(&[(1.0, &self.damping), (1.0, &self.water_tangent)]);
        for w in water {
            self.water_tangent.mul_add(1.0, v0, w);
        }
    }

    /// The power (W) of the water's force the step used at velocity `v`,
    /// from its remainder `water` (N): (water - D_0 v) . v.
    pub(super) fn water_power(&self, water: &[f64], v: &[f64]) -> f64 {
        let held: f64 = water.iter().zip(v).map(|(f, u)| f * u).sum();
        let drag = if self.has_drag {
            self.water_tangent.quadratic_form(v)
        } else {
            0.0
        };
        held - drag
    }

    /// A step's loads for the linear model: `f` + `water` - offset (N).
    pub(super) fn step_loads(&self, f: &[f64], water: &[f64], out: &mut Vec<f64>) {
        out.clear();
        let shifted = f.iter().zip(water).zip(&self.offset);
        out.extend(shifted.map(|((f, w), o)| f + w - o));
    }

    /// The powers (W) of friction and the seabed's dampers at velocity `v`.
    pub(super) fn seabed_dissipation(&self, v: &[f64]) -> [f64; 2] {
        let mut out = [0.0; 2];
        for s in &self.seabed {
            let u = node(v, s.node);
            out[0] -= u.dot(&(s.friction * u));
            out[1] -= u.dot(&(s.damper * u));
        }
        out
    }

    /// The axial damper's power (W) at velocity `v`.
    pub(super) fn axial_dissipation(&self, v: &[f64]) -> f64 {
        -self.axial.quadratic_form(v)
    }

    /// Strain energy and the seabed spring's energy (J) of the linear model
    /// at `q`: each the start's plus its force's work and the quadratic term.
    pub(super) fn energies(&mut self, q: &[f64]) -> [f64; 2] {
        for ((d, x), s) in self.dq.iter_mut().zip(q).zip(&self.start) {
            *d = x - s;
        }
        self.kdq.fill(0.0);
        self.stiffness.mul_add(1.0, &self.dq, &mut self.kdq);
        let mut seabed = self.energy_start[1];
        let mut seabed_quadratic = 0.0;
        for s in &self.seabed {
            let d = node(&self.dq, s.node);
            seabed += s.force.dot(&d);
            seabed_quadratic += 0.5 * d.dot(&(s.stiffness * d));
        }
        let quadratic: f64 = 0.5
            * self
                .dq
                .iter()
                .zip(&self.kdq)
                .map(|(a, b)| a * b)
                .sum::<f64>();
        let work: f64 = self
            .elastic_start
            .iter()
            .zip(&self.dq)
            .map(|(g, d)| g * d)
            .sum();
        [
            self.energy_start[0] + work + quadratic - seabed_quadratic,
            seabed + seabed_quadratic,
        ]
    }
}
