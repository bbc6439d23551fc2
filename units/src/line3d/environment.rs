//! What the surroundings do to each node of the 3D line: Morison drag on the
//! velocity relative to the water (current by depth plus Airy waves), the
//! waves' inertia force, and the seabed (penalty contact normal to its plane,
//! Coulomb friction along and across the line regularised by a stick
//! velocity). Each is skipped when the scene does not ask for it. Forces are
//! lumped at the nodes over their tributary length.

use super::bathymetry::Bathymetry;
use super::mechanics::{Tangent, add_block, add_node, node, normal_projector};
use super::params::{Line3dParams, Seabed};
use super::waves::{AiryWaves, Kinematics};
use crate::numerics::banded::SymmetricBand;
use nalgebra::{Matrix3, Vector3};
use rayon::prelude::*;

/// The fewest nodes whose wave kinematics one task of the sweep pool takes
/// (about 30 us of wave sums with 100 components: well above a task's cost).
const NODES_PER_TASK: usize = 4;

/// Penetration (m) over which the seabed's spring stiffens from 0 to its
/// stiffness.
pub const SMOOTHING: f64 = 1e-2;

/// The seabed (a plane or a bathymetry grid) and its laws.
#[derive(Clone, Debug)]
pub struct SeabedPlane {
    /// A point of the plane (m) and its upward unit normal.
    point: Vector3<f64>,
    normal: Vector3<f64>,
    /// The grid, in place of the plane.
    grid: Option<Bathymetry>,
    /// Per unit length of line: stiffness (N/m^2), damping (N s/m^2).
    stiffness: f64,
    damping: f64,
    friction: [f64; 2],
    stick_velocity: f64,
}

impl SeabedPlane {
    fn new(s: &Seabed) -> SeabedPlane {
        let normal = Vector3::new(-s.slope[0], -s.slope[1], 1.0).normalize();
        SeabedPlane {
            point: Vector3::new(0.0, 0.0, -s.depth.unwrap_or(0.0)),
            normal,
            grid: s.bathymetry.clone(),
            stiffness: s.stiffness,
            damping: s.damping,
            friction: [s.friction_axial, s.friction_lateral],
            stick_velocity: s.stick_velocity,
        }
    }

    /// Contact pressure per unit length (N/m) at penetration `d` (m) and
    /// its slope: the penalty spring with its first `SMOOTHING` metres
    /// quadratic (a force with a continuous derivative, so Newton does not
    /// cycle on a node at the surface), linear beyond.
    pub fn penalty(&self, d: f64) -> (f64, f64) {
        if d <= 0.0 {
            (0.0, 0.0)
        } else if d < SMOOTHING {
            (
                self.stiffness * d * d / (2.0 * SMOOTHING),
                self.stiffness * d / SMOOTHING,
            )
        } else {
            (self.stiffness * (d - 0.5 * SMOOTHING), self.stiffness)
        }
    }

    /// The spring's energy per unit length (J/m) at penetration `d` (m).
    pub fn penalty_energy(&self, d: f64) -> f64 {
        if d <= 0.0 {
            0.0
        } else if d < SMOOTHING {
            self.stiffness * d.powi(3) / (6.0 * SMOOTHING)
        } else {
            let d0 = SMOOTHING;
            self.stiffness * (d0 * d0 / 6.0 + 0.5 * (d - 0.5 * d0).powi(2) - d0 * d0 / 8.0)
        }
    }

    /// Signed height of `p` above the seabed (m; negative inside).
    pub fn height(&self, p: &Vector3<f64>) -> f64 {
        self.surface(p).0
    }

    /// Signed height of `p` above the seabed (m, along the normal) and the
    /// seabed's upward unit normal there: the plane's, or the grid's cell's
    /// (the vertical gap times the normal's z, which is the plane's distance
    /// where the grid is a plane).
    pub fn surface(&self, p: &Vector3<f64>) -> (f64, Vector3<f64>) {
        match &self.grid {
            None => (self.normal.dot(&(p - self.point)), self.normal),
            Some(grid) => {
                let (z, [sx, sy]) = grid.at(p.x, p.y);
                let normal = Vector3::new(-sx, -sy, 1.0).normalize();
                ((p.z - z) * normal.z, normal)
            }
        }
    }
}

/// The forces on one node (N), by cause.
#[derive(Copy, Clone, Debug, Default)]
pub struct NodeForces {
    /// Drag and the waves' inertia force.
    pub hydrodynamic: Vector3<f64>,
    /// The seabed's spring (conservative) and its damper.
    pub seabed_spring: Vector3<f64>,
    /// The seabed's damper.
    pub seabed_damper: Vector3<f64>,
    /// Seabed friction.
    pub friction: Vector3<f64>,
}

/// The surroundings of a line.
#[derive(Clone, Debug)]
pub struct Environment {
    /// 1/2 rho D Cn and 1/2 rho pi D Ct (kg/m^2).
    drag: [f64; 2],
    /// rho A (1 + Ca_n) and rho A Ca_t (kg/m): the waves' inertia per length.
    inertia: [f64; 2],
    /// Depth (m) and current velocity (m/s), by depth.
    current: Vec<(f64, Vector3<f64>)>,
    waves: Option<AiryWaves>,
    /// The seabed, when the line can touch it.
    pub seabed: Option<SeabedPlane>,
    /// Tributary length per node (m).
    tributary: Vec<f64>,
    /// The waves' kinematics at each node for one time, taken once per step
    /// at the nodes' predicted positions ([`Environment::hold_waves`]).
    held: Option<HeldWaves>,
}

/// The water's motion at every node at time `t` (s); None above the surface;
/// and the positions (m) it was taken at.
#[derive(Clone, Debug)]
struct HeldWaves {
    t: f64,
    at_nodes: Vec<Option<Kinematics>>,
    positions: Vec<[u64; 3]>,
}

impl Environment {
    /// From the parameters (checked) and the mesh.
    pub fn new(p: &Line3dParams, tributary: Vec<f64>) -> Environment {
        let area = std::f64::consts::PI * p.diameter * p.diameter / 4.0;
        let rho = p.water_density;
        let current = p
            .current
            .iter()
            .map(|c| {
                let (s, co) = c.heading_deg.to_radians().sin_cos();
                (c.depth, Vector3::new(c.speed * co, c.speed * s, 0.0))
            })
            .collect();
        Environment {
            drag: [
                0.5 * rho * p.diameter * p.drag_normal,
                0.5 * rho * std::f64::consts::PI * p.diameter * p.drag_tangential,
            ],
            inertia: [
                rho * area * (1.0 + p.added_mass_normal),
                rho * area * p.added_mass_tangential,
            ],
            current,
            waves: p.waves.as_ref().map(AiryWaves::new),
            seabed: p.seabed.as_ref().map(SeabedPlane::new),
            tributary,
            held: None,
        }
    }

    /// Takes the waves' kinematics at `t` (s) once, at the node positions
    /// `q` (m: a step's predicted end), for every evaluation at `t` until the
    /// next call: Newton's iterations then cost no wave sums. The positions
    /// differ from the converged ones by the predictor's error, O(h^3).
    ///
    /// On a thread of the master's sweep pool (`[master] threads` > 1) the
    /// nodes are shared out with the pool's idle threads: the wave sums are
    /// most of a line's step, and three lines on two threads would otherwise
    /// leave one idle through the third. Each node's kinematics are computed
    /// alone, so the result is the same on any thread count. A step taken
    /// again (a coupling iteration, a rollback) predicts the same positions
    /// but at its driven ends: a node at the same time and position (bit for
    /// bit) keeps what it has.
    pub fn hold_waves(&mut self, q: &[f64], t: f64) {
        let Some(waves) = &self.waves else { return };
        let nodes = self.tributary.len();
        let mut held = self.held.take().unwrap_or(HeldWaves {
            t: f64::NAN,
            at_nodes: Vec::new(),
            positions: Vec::new(),
        });
        let same_time = held.t.to_bits() == t.to_bits() && held.positions.len() == nodes;
        held.t = t;
        held.at_nodes.resize(nodes, None);
        held.positions.resize(nodes, [0; 3]);
        let at_node = |(i, (kept, at)): (usize, (&mut Option<Kinematics>, &mut [u64; 3]))| {
            let p = node(q, i);
            let bits = [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()];
            if !(same_time && *at == bits) {
                *kept = waves.at(&p, t);
                *at = bits;
            }
        };
        let (at_nodes, positions) = (&mut held.at_nodes, &mut held.positions);
        if rayon::current_thread_index().is_some() {
            (at_nodes
                .par_iter_mut()
                .zip(positions.par_iter_mut())
                .enumerate())
            .with_min_len(NODES_PER_TASK)
            .for_each(at_node);
        } else {
            (at_nodes.iter_mut().zip(positions.iter_mut()).enumerate()).for_each(at_node);
        }
        self.held = Some(held);
    }

    /// Tributary length of node `i` (m).
    pub fn tributary(&self, i: usize) -> f64 {
        self.tributary[i]
    }

    /// Energy stored in the seabed's spring (J): 1/2 k l d^2 per node
    /// inside the plane.
    pub fn seabed_energy(&self, seabed: &SeabedPlane, q: &[f64]) -> f64 {
        (0..self.tributary.len())
            .map(|i| seabed.penalty_energy(-seabed.height(&node(q, i))) * self.tributary[i])
            .sum()
    }

    /// The same surroundings without waves (for the statics).
    pub fn without_waves(&self) -> Environment {
        Environment {
            waves: None,
            held: None,
            ..self.clone()
        }
    }

    /// The current's velocity at height z (m/s): linear in depth between the
    /// table's rows, the end rows' values beyond them.
    pub fn current_at(&self, z: f64) -> Vector3<f64> {
        let depth = -z;
        let c = &self.current;
        match c.iter().position(|(d, _)| *d >= depth) {
            None => c.last().map_or(Vector3::zeros(), |r| r.1),
            Some(0) => c[0].1,
            Some(i) => {
                let ((d0, u0), (d1, u1)) = (c[i - 1], c[i]);
                let s = (depth - d0) / (d1 - d0);
                u0 + (u1 - u0) * s
            }
        }
    }

    /// Whether waves move the water (else it changes with depth only).
    pub fn has_waves(&self) -> bool {
        self.waves.is_some()
    }

    /// Whether the water moves or drags (else drag is skipped).
    /// Whether the line has Morison drag (normal or tangential).
    pub fn has_drag(&self) -> bool {
        self.drag[0] + self.drag[1] > 0.0
    }

    fn hydrodynamic(&self) -> bool {
        self.drag[0] + self.drag[1] > 0.0 || self.waves.is_some()
    }

    /// Adds `scale` times minus the surroundings' forces to `force` (they
    /// enter as `M a + g = f`, g holding minus the forces), and their tangent
    /// (position derivatives of the contact spring; velocity derivatives of
    /// drag, seabed damping and friction) to the band.
    pub fn add_force(
        &self,
        q: &[f64],
        v: &[f64],
        t: f64,
        scale: f64,
        mut tangent: Tangent<'_>,
        force: &mut [f64],
    ) {
        if !self.hydrodynamic() && self.seabed.is_none() {
            return;
        }
        for i in 0..self.tributary.len() {
            let band = tangent.as_mut().map(|(b, k, c)| (&mut **b, *k, *c));
            let f = self.node_forces(q, v, t, i, band);
            let total = f.hydrodynamic + f.seabed_spring + f.seabed_damper + f.friction;
            add_node(force, i, &total, -scale);
        }
    }

    /// As [`Environment::add_force`] at scale 1 without a tangent, and the
    /// powers (W) of the water, friction and the seabed's damper on the
    /// nodes' velocities, in the same pass.
    pub fn add_force_and_powers(
        &self,
        q: &[f64],
        v: &[f64],
        t: f64,
        force: &mut [f64],
    ) -> [f64; 3] {
        let mut powers = [0.0; 3];
        if !self.hydrodynamic() && self.seabed.is_none() {
            return powers;
        }
        for i in 0..self.tributary.len() {
            let f = self.node_forces(q, v, t, i, None);
            let total = f.hydrodynamic + f.seabed_spring + f.seabed_damper + f.friction;
            add_node(force, i, &total, -1.0);
            let velocity = node(v, i);
            powers[0] += f.hydrodynamic.dot(&velocity);
            powers[1] += f.friction.dot(&velocity);
            powers[2] += f.seabed_damper.dot(&velocity);
        }
        powers
    }

    /// The forces on node `i`, and with `tangent` minus their derivatives
    /// added to the band (scaled by its factors).
    pub fn node_forces(
        &self,
        q: &[f64],
        v: &[f64],
        t: f64,
        i: usize,
        mut tangent: Tangent<'_>,
    ) -> NodeForces {
        let at = self.at(q, node(v, i), t, i);
        let mut out = NodeForces::default();
        if self.hydrodynamic() {
            let band = tangent.as_mut().map(|(b, _, c)| (&mut **b, *c));
            out.hydrodynamic = self.hydrodynamics(&at, band);
        }
        if let Some(seabed) = &self.seabed {
            seabed_forces(seabed, &at, tangent, &mut out);
        }
        out
    }

    /// The seabed's force on node `i` at rest at `q` (N) and its
    /// derivatives there; `None` off the seabed or without one.
    pub fn seabed_at_rest(&self, q: &[f64], i: usize) -> Option<(NodeForces, SeabedTangent)> {
        let seabed = self.seabed.as_ref()?;
        let at = self.at(q, Vector3::zeros(), 0.0, i);
        let mut out = NodeForces::default();
        let tangent = seabed_node(seabed, &at, &mut out)?;
        Some((out, tangent))
    }

    /// The true velocity derivative of friction on node `i` at (q, v, t)
    /// less the slope Newton takes (N s/m); `None` where they agree (off
    /// the seabed, sticking, or no friction).
    pub fn friction_correction(
        &self,
        q: &[f64],
        v: &[f64],
        t: f64,
        i: usize,
    ) -> Option<Matrix3<f64>> {
        let seabed = self.seabed.as_ref()?;
        let at = self.at(q, node(v, i), t, i);
        let tangent = seabed_node(seabed, &at, &mut NodeForces::default())?;
        let correction = tangent.friction_exact - tangent.friction;
        (correction.abs().max() > 0.0).then_some(correction)
    }

    /// Adds the water's force (drag on the velocity relative to the water
    /// and the waves' inertia, N) at (q, v, t) to `force`; returns whether
    /// there is any.
    pub fn add_hydrodynamic_force(&self, q: &[f64], v: &[f64], t: f64, force: &mut [f64]) -> bool {
        self.add_hydrodynamic_force_with_tangent(q, v, t, force, None)
    }

    /// As [`Environment::add_hydrodynamic_force`], with minus the drag's
    /// velocity derivative (N s/m) added to `tangent` when given.
    pub fn add_hydrodynamic_force_with_tangent(
        &self,
        q: &[f64],
        v: &[f64],
        t: f64,
        force: &mut [f64],
        mut tangent: Option<&mut SymmetricBand>,
    ) -> bool {
        if !self.hydrodynamic() {
            return false;
        }
        for i in 0..self.tributary.len() {
            let at = self.at(q, node(v, i), t, i);
            let band = tangent.as_deref_mut().map(|b| (b, 1.0));
            add_node(force, i, &self.hydrodynamics(&at, band), 1.0);
        }
        true
    }

    /// Node `i` of the shape `q` moving at `velocity` (m/s) at `t` (s).
    fn at(&self, q: &[f64], velocity: Vector3<f64>, t: f64, i: usize) -> At {
        At {
            x: node(q, i),
            velocity,
            axis: tangent_at(q, i, self.tributary.len()),
            t,
            length: self.tributary[i],
            node: i,
        }
    }

    /// Drag on the velocity relative to the water and the waves' inertia
    /// (none on a node above the surface); with `band`, the drag's velocity
    /// derivative times the damping factor.
    fn hydrodynamics(&self, at: &At, band: Option<(&mut SymmetricBand, f64)>) -> Vector3<f64> {
        let mut water = self.current_at(at.x.z);
        let mut inertia = Vector3::zeros();
        match &self.waves {
            Some(waves) => {
                let kinematics = match &self.held {
                    Some(held) if held.t == at.t => held.at_nodes[at.node],
                    _ => waves.at(&at.x, at.t),
                };
                let Some(k) = kinematics else {
                    return Vector3::zeros();
                };
                water += k.velocity;
                let (along, normal) = split(&k.acceleration, &at.axis);
                inertia =
                    (normal * self.inertia[0] + at.axis * (along * self.inertia[1])) * at.length;
            }
            None if at.x.z > 0.0 => return Vector3::zeros(),
            None => {}
        }
        let (along, normal) = split(&(water - at.velocity), &at.axis);
        let normal_speed = normal.norm();
        let [kn, kt] = self.drag.map(|k| k * at.length);
        let drag = normal * (kn * normal_speed) + at.axis * (kt * along.abs() * along);
        if let Some((band, c)) = band {
            let mut m = at.axis * at.axis.transpose() * (2.0 * kt * along.abs());
            if normal_speed > 0.0 {
                m += (normal_projector(&at.axis) * normal_speed
                    + normal * normal.transpose() / normal_speed)
                    * kn;
            }
            add_block(band, at.node, at.node, &m, c);
        }
        drag + inertia
    }
}

/// A node's position (m), velocity (m/s), unit tangent, the time (s), its
/// tributary length (m) and index.
struct At {
    x: Vector3<f64>,
    velocity: Vector3<f64>,
    axis: Vector3<f64>,
    t: f64,
    length: f64,
    node: usize,
}

/// Unit tangent at node `i` of `nodes`: along the chord of its neighbours.
pub fn tangent_at(q: &[f64], i: usize, nodes: usize) -> Vector3<f64> {
    let (a, b) = match i {
        0 => (0, 1),
        i if i + 1 == nodes => (i - 1, i),
        i => (i - 1, i + 1),
    };
    (node(q, b) - node(q, a)).normalize()
}

/// Split of `u` into its parts along the unit `axis` and normal to it.
fn split(u: &Vector3<f64>, axis: &Vector3<f64>) -> (f64, Vector3<f64>) {
    let along = u.dot(axis);
    (along, u - axis * along)
}

/// The seabed's derivatives at a node in contact: the spring's stiffness
/// (N/m), the damper's and the friction's velocity slopes (N s/m), as Newton
/// takes them (friction's secant while sliding).
#[derive(Copy, Clone, Debug)]
pub struct SeabedTangent {
    /// Of the seabed's spring (N/m).
    pub stiffness: Matrix3<f64>,
    /// Of the seabed's damper (N s/m).
    pub damper: Matrix3<f64>,
    /// Of friction (N s/m while sliding: its secant).
    pub friction: Matrix3<f64>,
    /// Friction's true velocity derivative (the tangent of the tanh also
    /// while sliding), for the step's sensitivity.
    pub friction_exact: Matrix3<f64>,
}

/// The seabed's spring, damper and friction on a node (zero off the seabed),
/// with their tangent added to the band.
fn seabed_forces(s: &SeabedPlane, at: &At, tangent: Tangent<'_>, out: &mut NodeForces) {
    let Some(d) = seabed_node(s, at, out) else {
        return;
    };
    if let Some((band, k, c)) = tangent {
        let m = d.stiffness * k + (d.damper + d.friction) * c;
        add_block(band, at.node, at.node, &m, 1.0);
    }
}

/// The seabed's forces on a node into `out`, and their derivatives; `None`
/// off the seabed.
fn seabed_node(s: &SeabedPlane, at: &At, out: &mut NodeForces) -> Option<SeabedTangent> {
    let (vel, axis, length) = (&at.velocity, &at.axis, at.length);
    let (height, n) = s.surface(&at.x);
    if height >= 0.0 {
        return None;
    }
    let (pressure, slope) = s.penalty(-height);
    let normal_force = pressure * length;
    out.seabed_spring = n * normal_force;
    // The damper engages with the spring, so no force jumps at the surface.
    let damping_rate = s.damping * length * (-height / SMOOTHING).min(1.0);
    out.seabed_damper = -n * (damping_rate * vel.dot(&n));
    // Sliding directions: the line's axis in the plane, and across it.
    let along = (axis - n * axis.dot(&n))
        .try_normalize(1e-12)
        .unwrap_or_else(|| any_normal(&n));
    let across = n.cross(&along);
    let mut friction = Matrix3::zeros();
    let mut friction_exact = Matrix3::zeros();
    for (dir, mu) in [(along, s.friction[0]), (across, s.friction[1])] {
        if mu == 0.0 {
            continue;
        }
        // mu N tanh(v / v_stick): smooth, so Newton does not cycle at the
        // stick velocity; its slope at rest is mu N / v_stick.
        let limit = mu * normal_force;
        let slip = vel.dot(&dir) / s.stick_velocity;
        let ratio = slip.tanh();
        out.friction -= dir * (limit * ratio);
        // Newton's slope: the tangent while sticking, the secant (force over
        // velocity) while sliding, where the tangent vanishes and Newton would
        // overshoot into the other regime and cycle.
        let slope = if slip.abs() < 1e-3 {
            1.0
        } else {
            (1.0 - ratio * ratio).max(ratio / slip)
        };
        friction += dir * dir.transpose() * (limit * slope / s.stick_velocity);
        friction_exact +=
            dir * dir.transpose() * (limit * (1.0 - ratio * ratio) / s.stick_velocity);
    }
    let nn = n * n.transpose();
    Some(SeabedTangent {
        stiffness: nn * (slope * length),
        damper: nn * damping_rate,
        friction,
        friction_exact,
    })
}

/// Some unit vector normal to `n`.
fn any_normal(n: &Vector3<f64>) -> Vector3<f64> {
    let trial = if n.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    normal_projector(n) * trial / (normal_projector(n) * trial).norm()
}
