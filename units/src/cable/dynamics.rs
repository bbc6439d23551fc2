//! The cable's linear dynamics about its static state: the matrices, the drag's
//! nonlinear remainder, and the cable as a [`SecondOrderSystem`] stepped by the
//! shared [`IteratedNewmark`] (the drag iterated on the fixed factorisation).

use super::*;
use crate::integrators::hht::{Matrices, SecondOrderSystem, TangentScales, motion_fields};
use crate::integrators::newmark_iterated::IteratedNewmark;

/// Matrices and scratch of the linear dynamics about the static state.
pub(super) struct Dynamics {
    pub(super) statics: StaticState,
    pub(super) m_ff: SymmetricBand,
    pub(super) c_ff: SymmetricBand,
    /// Whether any damping (structural or linearised drag) exists: without it the
    /// damping products are skipped.
    pub(super) damped: bool,
    pub(super) k_ff: SymmetricBand,
    /// Couplings of the bottom node (rows: node 1 x, z; columns: bottom x, z).
    pub(super) m_fb: [[f64; 2]; 2],
    pub(super) c_fb: [[f64; 2]; 2],
    pub(super) k_fb: [[f64; 2]; 2],
    pub(super) m_bb: [[f64; 2]; 2],
    pub(super) c_bb: [[f64; 2]; 2],
    pub(super) k_bb: [[f64; 2]; 2],
    pub(super) drag: Option<Drag>,
    pub(super) static_top_force: [f64; 2],
    /// Force the cable exerts on its bottom support at rest (N).
    pub(super) static_support_force: [f64; 2],
    /// The shared integrator with the factorised effective stiffness.
    pub(super) newmark: IteratedNewmark,
    // Scratch, sized once.
    pub(super) node_velocity: Vec<[f64; 2]>,
    pub(super) node_drag: Vec<[f64; 2]>,
}

impl Cable {
    pub(super) fn build_dynamics(
        &self,
        statics: StaticState,
        top_force: [f64; 2],
    ) -> Result<Dynamics, UnitError> {
        let p = &self.props;
        let x = &statics.positions;
        let nodes = x.len();
        let full_m = elements::mass(p, x);
        let full_k = elements::stiffness(p, x, self.effects.geometric_stiffness);
        let (a1, a2) = if self.effects.structural_damping {
            (self.params.rayleigh_mass, self.params.rayleigh_stiffness)
        } else {
            (0.0, 0.0)
        };
        let mut full_c = SymmetricBand::zeros(full_m.size(), full_m.half_bandwidth());
        full_c.set_combination(&[(a1, &full_m), (a2, &full_k)]);
        let structural_c = full_c.clone();
        let block = |m: &SymmetricBand, r0: usize, c0: usize| {
            [
                [m.get(r0, c0), m.get(r0, c0 + 1)],
                [m.get(r0 + 1, c0), m.get(r0 + 1, c0 + 1)],
            ]
        };
        let drag = self.effects.drag.then(|| self.drag_about(x));
        let mut static_drag = vec![[0.0; 2]; nodes];
        if let Some(d) = &drag {
            d.add_forces(&vec![[0.0; 2]; nodes], &mut static_drag);
            // The drag's linearisation joins the damping the integrator factorises.
            full_c.set_combination(&[(1.0, &structural_c), (1.0, &d.damping())]);
        }
        // Support force at rest: the first element's pull, the bottom node's half
        // weight and its share of the current drag.
        let (e0, _, t0) = elements::element_state(p, x[0], x[1]);
        let w0 = -0.5 * self.loads.weight * p.length;
        let static_support_force = [
            t0 * e0[0] + static_drag[0][0],
            t0 * e0[1] + w0 + static_drag[0][1],
        ];
        let free = 2 * (nodes - 1);
        Ok(Dynamics {
            m_fb: block(&full_m, 2, 0),
            c_fb: block(&full_c, 2, 0),
            k_fb: block(&full_k, 2, 0),
            m_bb: block(&full_m, 0, 0),
            c_bb: block(&full_c, 0, 0),
            k_bb: block(&full_k, 0, 0),
            damped: self.effects.structural_damping || drag.is_some(),
            m_ff: trailing_block(&full_m, 2),
            c_ff: trailing_block(&full_c, 2),
            k_ff: trailing_block(&full_k, 2),
            newmark: IteratedNewmark::new(free, elements::BAND),
            drag,
            static_top_force: top_force,
            static_support_force,
            statics,
            node_velocity: vec![[0.0; 2]; nodes],
            node_drag: vec![[0.0; 2]; nodes],
        })
    }
}

impl Cable {
    /// The Morison drag about the static positions `x`: each element's direction
    /// and the current's speed at its middle (none without the `current` effect).
    fn drag_about(&self, x: &[[f64; 2]]) -> Drag {
        let p = &self.props;
        let nodes = x.len();
        let mut dirs = Vec::with_capacity(nodes - 1);
        let mut speeds = Vec::with_capacity(nodes - 1);
        for e in 0..nodes - 1 {
            let (dir, _, _) = elements::element_state(p, x[e], x[e + 1]);
            dirs.push(dir);
            let z = 0.5 * (x[e][1] + x[e + 1][1]);
            speeds.push(if self.effects.current {
                self.params.current.speed(z, self.params.water_depth)
            } else {
                0.0
            });
        }
        Drag::new(
            self.params.water_density,
            self.params.diameter,
            self.params.drag_normal,
            self.params.drag_tangential,
            p.length,
            dirs,
            speeds,
        )
    }
}

impl Dynamics {
    /// The drag's nonlinear remainder (N per node) for free velocities `v` and
    /// bottom velocity `vb`, into `node_drag`; its linear part is in the damping.
    pub(super) fn drag_change(&mut self, v: &[f64], vb: [f64; 2]) {
        let Some(drag) = &self.drag else { return };
        self.node_velocity[0] = vb;
        for (j, nv) in self.node_velocity.iter_mut().enumerate().skip(1) {
            *nv = [v[2 * (j - 1)], v[2 * (j - 1) + 1]];
        }
        self.node_drag.iter_mut().for_each(|f| *f = [0.0; 2]);
        drag.add_remainder(&self.node_velocity, &mut self.node_drag);
    }
}

/// The cable during one step, as the shared integrator sees it: its free DOFs
/// with the drag remainder as the nonlinear force (the bottom moves with `vb`).
pub(super) struct CableStep<'a> {
    pub(super) dynamics: &'a mut Dynamics,
    pub(super) state: &'a mut CableState,
    /// Bottom velocity at the step's end (m/s).
    pub(super) vb: [f64; 2],
}

impl SecondOrderSystem for CableStep<'_> {
    fn label(&self) -> &str {
        "cable"
    }

    fn matrices(&self) -> Matrices<'_> {
        let d = &*self.dynamics;
        Matrices {
            mass: &d.m_ff,
            damping: d.damped.then_some(&d.c_ff),
            stiffness: Some(&d.k_ff),
            varies: false,
        }
    }

    motion_fields!(state);

    fn is_linear(&self) -> bool {
        self.dynamics.drag.is_none()
    }

    /// The drag remainder at the free nodes' velocities `v`, as a force on the
    /// left-hand side (its negative is a load); no tangent (the iteration is on the
    /// fixed factorisation).
    fn nonlinear_force(
        &mut self,
        _q: &[f64],
        v: &[f64],
        _t: f64,
        _tangent: Option<(&mut SymmetricBand, TangentScales)>,
        force: &mut Vec<f64>,
    ) {
        let d = &mut *self.dynamics;
        d.drag_change(v, self.vb);
        force.clear();
        force.resize(v.len(), 0.0);
        for j in 1..d.node_drag.len() {
            force[2 * (j - 1)] = -d.node_drag[j][0];
            force[2 * (j - 1) + 1] = -d.node_drag[j][1];
        }
    }
}

pub(super) fn mat2(m: &[[f64; 2]; 2], x: [f64; 2]) -> [f64; 2] {
    [
        m[0][0] * x[0] + m[0][1] * x[1],
        m[1][0] * x[0] + m[1][1] * x[1],
    ]
}
