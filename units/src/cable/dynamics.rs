//! The cable's linear dynamics about its static state: the matrices and their
//! factorisation for a step, the drag's nonlinear remainder, and the step's drag
//! iterations on the fixed factorisation.

use super::*;

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
    /// Step size of `factor` (s) and the factorised effective stiffness.
    pub(super) h: f64,
    pub(super) factor: Option<BandLdlt>,
    pub(super) effective: SymmetricBand,
    // Scratch, sized once.
    pub(super) rhs: Vec<f64>,
    pub(super) load: Vec<f64>,
    pub(super) scratch: Vec<f64>,
    pub(super) q_new: Vec<f64>,
    pub(super) v_iter: Vec<f64>,
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
        let drag = self.effects.drag.then(|| {
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
        });
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
            effective: SymmetricBand::zeros(free, elements::BAND),
            drag,
            static_top_force: top_force,
            static_support_force,
            h: 0.0,
            factor: None,
            statics,
            rhs: vec![0.0; free],
            load: vec![0.0; free],
            scratch: vec![0.0; free],
            q_new: vec![0.0; free],
            v_iter: vec![0.0; free],
            node_velocity: vec![[0.0; 2]; nodes],
            node_drag: vec![[0.0; 2]; nodes],
        })
    }
}

impl Dynamics {
    /// Factorises K + 2/h C + 4/h^2 M for step h (s) when h changed.
    pub(super) fn prepare(&mut self, h: f64) -> Result<(), UnitError> {
        if self.factor.is_some() && self.h == h {
            return Ok(());
        }
        self.effective.set_combination(&[
            (1.0, &self.k_ff),
            (2.0 / h, &self.c_ff),
            (4.0 / (h * h), &self.m_ff),
        ]);
        self.factor = Some(BandLdlt::new(&self.effective).ok_or_else(|| {
            UnitError::Numerical(format!(
                "the effective stiffness for h = {h} s is not positive definite"
            ))
        })?);
        self.h = h;
        Ok(())
    }

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

/// Solves the step for the free DOFs, iterating on the drag with the factorised
/// effective stiffness (modified Newton). Leaves the new displacement in `q_new`,
/// velocity in `v_iter` and acceleration in `scratch`; returns the iterations.
pub(super) fn drag_iterations(
    d: &mut Dynamics,
    s: &CableState,
    factor: &BandLdlt,
    h: f64,
    vb: [f64; 2],
    tolerance: f64,
) -> Result<u32, UnitError> {
    let n = s.q.len();
    // Predict the end velocity from the start acceleration.
    for i in 0..n {
        d.v_iter[i] = s.v[i] + h * s.a[i];
    }
    let max_iterations = 100u32;
    let mut iterations = 0;
    loop {
        iterations += 1;
        d.load.copy_from_slice(&d.rhs);
        if d.drag.is_some() {
            let v_iter = std::mem::take(&mut d.v_iter);
            d.drag_change(&v_iter, vb);
            d.v_iter = v_iter;
            for j in 1..d.node_drag.len() {
                d.load[2 * (j - 1)] += d.node_drag[j][0];
                d.load[2 * (j - 1) + 1] += d.node_drag[j][1];
            }
        }
        d.q_new.copy_from_slice(&d.load);
        factor.solve_in_place(&mut d.q_new);
        let mut change: f64 = 0.0;
        for i in 0..n {
            let a_new = 4.0 / (h * h) * (d.q_new[i] - s.q[i]) - 4.0 / h * s.v[i] - s.a[i];
            let v_new = s.v[i] + 0.5 * h * (s.a[i] + a_new);
            change = change.max((v_new - d.v_iter[i]).abs());
            d.v_iter[i] = v_new;
            d.scratch[i] = a_new;
        }
        if !change.is_finite() {
            return Err(UnitError::Numerical(format!(
                "the cable's velocity became {change} in a step of {h} s"
            )));
        }
        if d.drag.is_none() || change <= tolerance {
            return Ok(iterations);
        }
        if iterations == max_iterations {
            return Err(UnitError::Numerical(format!(
                "drag iterations did not converge in {max_iterations} iterations (last velocity change {change:.3e} m/s, step {h} s)"
            )));
        }
    }
}

pub(super) fn mat2(m: &[[f64; 2]; 2], x: [f64; 2]) -> [f64; 2] {
    [
        m[0][0] * x[0] + m[0][1] * x[1],
        m[1][0] * x[0] + m[1][1] * x[1],
    ]
}
