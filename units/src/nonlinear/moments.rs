//! Bending moments recovered from the element's own equilibrium.
//!
//! The co-rotational element carries its load (submerged weight, distributed
//! loads, drag, inertia, seabed contact) at its nodes. Its end moments from the
//! stiffness alone (`LocalForces::moments`) are then those of a beam loaded at
//! its nodes only, which a riser's sag bend overestimates by the fixed-end
//! moment `q l^2 / 12` of the load along each element: +3.2 % at 10 m elements
//! on the steel catenary riser, falling as l^2 (issue 48). Removing it, as a
//! beam code's element load does, leaves -0.07 % at 10 m (converged reference:
//! 3200 elements; table in docs/nonlinear-section.md).
//!
//! The load along an element is read at its nodes, so that every cause counts
//! without being named: a node's net load (N) is everything acting on it
//! besides its elements' elastic forces (load, inertia, damping, drag, contact:
//! the unit's elastic force less its residual, `g - (M a + C v + g_total - f)`),
//! divided by its tributary length. The element's normal load is the mean of
//! its two nodes' densities along its normal; a node where a reaction acts (a
//! section's end, a support) has no density, and its element takes the other
//! node's alone.

use super::contact::RollerLoad;
use super::element::{ElementState, Formulation, LocalForces};
use super::model::Model;

/// What the recovery reads of the loads: a node's net load (N, x and z;
/// `None` where a reaction acts) and, for an element whose two nodes are
/// held, the load along it that the unit knows (N/m, x and z).
pub trait Loads {
    /// Node `j`'s net load.
    fn net_load(&self, j: usize) -> Option<[f64; 2]>;
    /// The load along element `e`.
    fn element_load(&self, e: usize) -> [f64; 2];
    /// The point loads on the elements (rollers), left out of the nodes'
    /// net loads: each element takes its own fixed-end moments.
    fn point_loads(&self) -> &[RollerLoad] {
        &[]
    }
}

impl Model {
    /// Element `e`'s end moments (N m, counter-clockwise on the element as
    /// [`LocalForces::moments`]) from its `local` forces, the fixed-end
    /// moments of the load along it (read from `loads`) removed.
    /// Co-rotational only: seed 002's element takes its loads consistently
    /// already and is returned as it is.
    pub fn recovered_moments(&self, e: usize, local: &LocalForces, loads: &impl Loads) -> [f64; 2] {
        if self.formulation != Formulation::Corotational {
            return local.moments;
        }
        let last = self.elements.len();
        // The load density (N/m) along the normal at node `j`.
        let density = |j: usize| {
            if j == 0 || j == last {
                return None;
            }
            let f = loads.net_load(j)?;
            let tributary = 0.5 * (self.elements[j - 1].length + self.elements[j].length);
            Some(normal_part(f, local) / tributary)
        };
        let load = match (density(e), density(e + 1)) {
            (Some(a), Some(b)) => 0.5 * (a + b),
            (Some(a), None) | (None, Some(a)) => a,
            (None, None) => normal_part(loads.element_load(e), local),
        };
        let fixed = load * local.chord * local.chord / 12.0;
        let mut ends = [local.moments[0] - fixed, local.moments[1] + fixed];
        // A point load P at xi: fixed-end moments P l xi (1 - xi)^2 and
        // P l xi^2 (1 - xi).
        for p in loads.point_loads().iter().filter(|p| p.element == e) {
            let (pn, l, xi) = (normal_part(p.on_pipe(), local), local.chord, p.xi);
            ends[0] -= pn * l * xi * (1.0 - xi) * (1.0 - xi);
            ends[1] += pn * l * xi * xi * (1.0 - xi);
        }
        ends
    }

    /// The bending moment (N m, as a node's) under each point load, from
    /// its element's recovered end moments and the load's own peak
    /// `P l xi (1 - xi)`, with the element's x direction cosine.
    pub fn for_each_point_moment(
        &self,
        q: &[f64],
        loads: &impl Loads,
        mut visit: impl FnMut(f64, f64),
    ) {
        for p in loads.point_loads() {
            let local = self.local_forces(q, p.element);
            let ends = self.recovered_moments(p.element, &local, loads);
            let (pn, l, xi) = (normal_part(p.on_pipe(), &local), local.chord, p.xi);
            let moment = (1.0 - xi) * -ends[0] + xi * ends[1] - pn * l * xi * (1.0 - xi);
            visit(moment, local.direction[0]);
        }
    }

    /// Calls `visit` with every element's index, local forces and recovered
    /// end moments at `q` (see [`Model::recovered_moments`]), in order.
    pub fn for_each_recovered(
        &self,
        q: &[f64],
        loads: &impl Loads,
        mut visit: impl FnMut(usize, &LocalForces, [f64; 2]),
    ) {
        for e in 0..self.elements.len() {
            let local = self.local_forces(q, e);
            visit(e, &local, self.recovered_moments(e, &local, loads));
        }
    }

    /// [`Model::for_each_recovered`] from the elements' states already
    /// evaluated at the displacements (one per element, in order).
    pub fn for_each_recovered_from(
        &self,
        states: &[ElementState],
        loads: &impl Loads,
        mut visit: impl FnMut(usize, &LocalForces, [f64; 2]),
    ) {
        for (e, state) in states.iter().enumerate() {
            visit(
                e,
                &state.local,
                self.recovered_moments(e, &state.local, loads),
            );
        }
    }
}

/// The part of `load` (x and z) along the element's normal (its direction
/// turned counter-clockwise).
fn normal_part(load: [f64; 2], local: &LocalForces) -> f64 {
    let [c, s] = local.direction;
    -load[0] * s + load[1] * c
}

impl super::NonlinearSection {
    /// Marks the nodes where a reaction acts (no load density there) and the
    /// ends whose rotation takes the end element's load moment.
    pub(super) fn mark_held_ends(&mut self) {
        self.held_nodes = vec![false; self.model.reference.len()];
        for dof in self.held_dofs() {
            self.held_nodes[dof / 3] = true;
        }
        // A held rotation takes the end moments in its reaction, and a coupled
        // one is a cut: the neighbour's element balances them there.
        let last_rotation = 3 * self.model.elements.len() + 2;
        let fixed: Vec<usize> = (self.ends.iter())
            .filter(|r| r.is_kinematic() || r.input.is_some())
            .map(|r| r.dof)
            .collect();
        self.free_end_rotation = [!fixed.contains(&2), !fixed.contains(&last_rotation)];
    }

    /// Adds `scale` times the fixed-end moments of the load along the
    /// section's end elements at `q` and time `t` (s) to the nodal load `out`,
    /// at each end whose rotation is free or loaded by a given moment:
    /// interior nodes take the `+-q l^2 / 12` of the two elements meeting
    /// there, which cancel, but at a pinned or moment-loaded end the lumped
    /// load would leave them out and move the whole span (a slack beam's
    /// moments low by `q l^2 / 12` everywhere once recovered). A cut (its
    /// moment coupled) is an interior node of the structure: the other
    /// section's element balances it, so none is added there. They follow the end element's normal at
    /// `q`: the statics at each Newton iterate, a step at its start.
    pub(super) fn add_end_load_moments(&self, (q, t): (&[f64], f64), scale: f64, out: &mut [f64]) {
        if self.model.formulation != Formulation::Corotational {
            return;
        }
        let last = self.model.elements.len() - 1;
        for (end, e, node, sign) in [(0, 0, 0, 1.0), (1, last, last + 1, -1.0)] {
            if !self.free_end_rotation[end] {
                continue;
            }
            let local = self.model.local_forces(q, e);
            let q_n = normal_part(self.load_along(e, t), &local);
            let l = self.model.elements[e].length;
            out[3 * node + 2] += scale * sign * q_n * l * l / 12.0;
        }
    }

    /// In one pass over the elements: the largest |moment| (N m), the largest
    /// tension (N), and the largest sag-bend and overbend moments (N m): the
    /// bending moment where the section is concave upwards (d2z/dx2 > 0, the sag
    /// bend above the touchdown point) and convex (the overbend on a stinger).
    /// The moments are the nodes' (the `moment` field): the mean of the
    /// recovered moments (`moments.rs`) of the elements meeting there, whose
    /// ends differ in dynamics by the element's own inertia (their larger one
    /// overstates the sag bend of the riser's 10 m mesh by 0.4 %, the mean by
    /// 0.05 %).
    /// With `kept`, from the elements' states the force evaluation kept.
    pub(super) fn extremes(&self, kept: bool) -> ([f64; 2], [f64; 2]) {
        let (mut moment, mut tension, mut bend) = (0.0f64, f64::NEG_INFINITY, [0.0f64; 2]);
        let element = |l: &LocalForces| tension = tension.max(l.axial);
        let mut node = |m: f64, forward: f64| {
            moment = moment.max(m.abs());
            // Positive m turns the tangent counter-clockwise along the arc.
            let concave = m * forward;
            if concave > 0.0 {
                bend[0] = bend[0].max(m.abs());
            } else if concave < 0.0 {
                bend[1] = bend[1].max(m.abs());
            }
        };
        self.for_each_node_moment(kept, element, |_, m, forward| node(m, forward));
        // The peaks under the rollers, between the nodes.
        (self.model).for_each_point_moment(&self.state.q, self, &mut node);
        ([moment, tension], bend)
    }

    /// Calls `element` with each element's local forces and `node` with each
    /// node's index, bending moment (N m: the mean of the recovered moments of
    /// the elements meeting there, one at each end of the section; positive
    /// turning the tangent counter-clockwise along the arc) and the mean x
    /// direction cosine of those elements, in order; with `kept`, from the
    /// elements' states the force evaluation kept at the current state.
    pub(super) fn for_each_node_moment(
        &self,
        kept: bool,
        mut element: impl FnMut(&LocalForces),
        mut node: impl FnMut(usize, f64, f64),
    ) {
        // The previous element's end moment (as the node's) and direction.
        let mut previous: Option<(f64, f64)> = None;
        let last = self.model.elements.len() - 1;
        let visit = |e, l: &LocalForces, moments: [f64; 2]| {
            element(l);
            let forward = l.direction[0];
            match previous {
                Some((m, f)) => node(e, 0.5 * (m - moments[0]), 0.5 * (f + forward)),
                None => node(e, -moments[0], forward),
            }
            if e == last {
                node(e + 1, moments[1], forward);
            }
            previous = Some((moments[1], forward));
        };
        if kept {
            (self.model).for_each_recovered_from(&self.element_states, self, visit);
        } else {
            (self.model).for_each_recovered(&self.state.q, self, visit);
        }
    }

    /// The load per length (N/m, x and z) along element `e` at time `t`: its
    /// segment's submerged weight and the distributed loads over its midpoint
    /// (a coupled distributed load is left out: it has no value here).
    fn load_along(&self, e: usize, t: f64) -> [f64; 2] {
        let segment = &self.params.segments[self.model.segment_of[e]];
        let mut load = [0.0, -segment.submerged_weight];
        let mid = 0.5 * (self.model.arc[e] + self.model.arc[e + 1]);
        for l in (self.params.loads.iter()).filter(|l| l.from <= mid && mid <= l.to) {
            load[0] += l.x.eval(t).map_or(0.0, |v| v[0]);
            load[1] += l.z.eval(t).map_or(0.0, |v| v[0]);
        }
        load
    }
}

impl Loads for super::NonlinearSection {
    /// Node `j`'s net load (N, x and z): everything acting on it besides its
    /// elements' elastic forces (load, inertia, damping, drag, contact), the
    /// elastic force less the residual the last `finish` left; `None` where a
    /// support or an end condition holds it (a reaction acts there).
    fn net_load(&self, j: usize) -> Option<[f64; 2]> {
        if self.held_nodes.get(j).copied().unwrap_or(true) {
            return None;
        }
        let (g, r) = (&self.state.elastic, &self.state.reaction);
        // A roller's share is its element's point load, not the node's.
        let roller = |dof: usize| self.state.rollers.iter().map(|p| p.at(dof)).sum::<f64>();
        Some([
            g[3 * j] - r[3 * j] + roller(3 * j),
            g[3 * j + 1] - r[3 * j + 1] + roller(3 * j + 1),
        ])
    }

    fn point_loads(&self) -> &[RollerLoad] {
        &self.state.rollers
    }

    /// The weight and distributed loads along element `e` at the state's time.
    fn element_load(&self, e: usize) -> [f64; 2] {
        self.load_along(e, self.state.t)
    }
}
