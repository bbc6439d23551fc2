//! The cable's interface Jacobian over its last step (`Unit::step_jacobian`):
//! the derivative of every output with respect to the top force and the bottom
//! velocity at the step's end. The step solves `K_eff q1 = rhs + L(u) + r(v1)`
//! (Newmark average acceleration, the drag's remainder r iterated on the fixed
//! factorisation), so its derivative is iterated the same way: `dq = K_eff^-1
//! (dL + dr/dv dv)`, dv = 2/h dq, with the remainder's tangent at the step's
//! end velocities; back-substitutions with the step's own factor, no new one.

use super::dynamics::{Dynamics, mat2};
use super::{BOTTOM_VX, Cable, TOP_FX};
use crate::contract::{Hold, Inputs, UnitError, require_step_jacobian_ready};

/// Buffers of the Jacobian; `ready` while the last step's factor is the
/// integrator's.
#[derive(Default)]
pub(super) struct JacobianWork {
    pub ready: bool,
    /// The last step's length (s).
    pub h: f64,
    load: Vec<f64>,
    dq: Vec<f64>,
    previous: Vec<f64>,
    /// Per element: the remainder's tangent at the step's end.
    tangents: Vec<[[f64; 2]; 2]>,
}

/// The bottom's change per unit input: (dqb, dvb, dab).
type BottomChange = [[f64; 2]; 3];

impl Cable {
    /// Fills `jacobian` (8 outputs x 4 inputs, row-major).
    pub(super) fn interface_jacobian(
        &mut self,
        inputs: Inputs<'_>,
        jacobian: &mut [f64],
    ) -> Result<(), UnitError> {
        require_step_jacobian_ready(self.jacobian.ready, "a cable")?;
        let mut w = std::mem::take(&mut self.jacobian);
        let result = self.cable_columns(inputs, &mut w, jacobian);
        self.jacobian = w;
        result
    }

    fn cable_columns(
        &self,
        inputs: Inputs<'_>,
        w: &mut JacobianWork,
        jacobian: &mut [f64],
    ) -> Result<(), UnitError> {
        let d = self
            .dynamics
            .as_ref()
            .ok_or_else(|| UnitError::Unsupported("step Jacobian before initialize".into()))?;
        self.remainder_tangents(d, w);
        let h = w.h;
        let n_in = inputs.len();
        for j in 0..n_in {
            let bottom = bottom_change(j, inputs.hold(BOTTOM_VX), h);
            self.solve_column(d, w, j, bottom)?;
            let column = self.output_changes(d, w, bottom);
            for (i, v) in column.iter().enumerate() {
                jacobian[i * n_in + j] = *v;
            }
        }
        Ok(())
    }

    /// The remainder's tangent of every element at the step's end velocities.
    fn remainder_tangents(&self, d: &Dynamics, w: &mut JacobianWork) {
        w.tangents.clear();
        let Some(drag) = &d.drag else { return };
        let s = &self.state;
        let node = |k: usize| {
            if k == 0 {
                s.vb
            } else {
                [s.v[2 * (k - 1)], s.v[2 * (k - 1) + 1]]
            }
        };
        for e in 0..d.node_drag.len() - 1 {
            let (a, b) = (node(e), node(e + 1));
            w.tangents
                .push(drag.remainder_tangent(e, [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])]));
        }
    }

    /// dq for input `j` into `w.dq`, iterating on the remainder as the step did.
    fn solve_column(
        &self,
        d: &Dynamics,
        w: &mut JacobianWork,
        j: usize,
        bottom: BottomChange,
    ) -> Result<(), UnitError> {
        let n = self.state.q.len();
        let factor = d.newmark.factor().ok_or_else(|| {
            UnitError::Numerical("cable: no factorised effective stiffness".into())
        })?;
        let [dqb, dvb, dab] = bottom;
        w.load.clear();
        w.load.resize(n, 0.0);
        if j < BOTTOM_VX {
            w.load[n - 2 + j - TOP_FX] = 1.0;
        } else {
            let coupling = [mat2(&d.m_fb, dab), mat2(&d.c_fb, dvb), mat2(&d.k_fb, dqb)];
            for (c, load) in w.load.iter_mut().take(2).enumerate() {
                *load -= coupling[0][c] + coupling[1][c] + coupling[2][c];
            }
        }
        w.dq.clear();
        w.dq.resize(n, 0.0);
        let scale = 2.0 / w.h;
        for _ in 0..100 {
            let mut rhs = std::mem::take(&mut w.previous);
            rhs.clear();
            rhs.extend_from_slice(&w.load);
            add_remainder_change(&w.tangents, &w.dq, scale, dvb, &mut rhs);
            factor.solve_in_place(&mut rhs);
            let change = rhs
                .iter()
                .zip(&w.dq)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            let size = rhs.iter().fold(0.0f64, |m, a| m.max(a.abs()));
            w.previous = std::mem::replace(&mut w.dq, rhs);
            if w.tangents.is_empty() || change <= 1e-13 * size.max(1e-300) {
                return Ok(());
            }
        }
        Err(UnitError::Numerical(
            "cable: the step Jacobian's iteration on the drag did not converge".into(),
        ))
    }

    /// The outputs' change: top velocity, bottom force, top displacement, top
    /// and bottom tension.
    fn output_changes(&self, d: &Dynamics, w: &JacobianWork, bottom: BottomChange) -> [f64; 8] {
        let n = self.state.q.len();
        let h = w.h;
        let (dq, [dqb, dvb, dab]) = (&w.dq, bottom);
        let at = |k: usize, f: f64| [f * dq[k], f * dq[k + 1]];
        let (dq1, dv1, da1) = (at(0, 1.0), at(0, 2.0 / h), at(0, 4.0 / (h * h)));
        let t = |m: &[[f64; 2]; 2], x: [f64; 2]| {
            [
                m[0][0] * x[0] + m[1][0] * x[1],
                m[0][1] * x[0] + m[1][1] * x[1],
            ]
        };
        let terms = [
            mat2(&d.m_bb, dab),
            t(&d.m_fb, da1),
            mat2(&d.c_bb, dvb),
            t(&d.c_fb, dv1),
            mat2(&d.k_bb, dqb),
            t(&d.k_fb, dq1),
        ];
        let mut force: [f64; 2] = std::array::from_fn(|c| -terms.iter().map(|x| x[c]).sum::<f64>());
        if let Some(t0) = w.tangents.first() {
            // The bottom node's half of element 0's remainder.
            let dve = [0.5 * (dvb[0] + dv1[0]), 0.5 * (dvb[1] + dv1[1])];
            let dr = mat2(t0, dve);
            force = [force[0] + 0.5 * dr[0], force[1] + 0.5 * dr[1]];
        }
        let x = &d.statics.positions;
        let m = x.len() - 1;
        let ea = self.props.axial_stiffness / self.props.length;
        let (et, _, _) = super::elements::element_state(&self.props, x[m - 1], x[m]);
        let (eb, _, _) = super::elements::element_state(&self.props, x[0], x[1]);
        let below = if m >= 2 { [dq[n - 4], dq[n - 3]] } else { dqb };
        let dt = [dq[n - 2] - below[0], dq[n - 1] - below[1]];
        let db = [dq1[0] - dqb[0], dq1[1] - dqb[1]];
        [
            2.0 / h * dq[n - 2],
            2.0 / h * dq[n - 1],
            force[0],
            force[1],
            dq[n - 2],
            dq[n - 1],
            ea * (et[0] * dt[0] + et[1] * dt[1]),
            ea * (eb[0] * db[0] + eb[1] * db[1]),
        ]
    }
}

/// How a unit change of input `j` moves the bottom: (dqb, dvb, dab) by the
/// bottom's own kinematics (trapezoidal under a ramp, held under zero order).
fn bottom_change(j: usize, hold: Hold, h: f64) -> BottomChange {
    let mut change = [[0.0; 2]; 3];
    if j >= BOTTOM_VX {
        let c = j - BOTTOM_VX;
        let (dq, da) = match hold {
            Hold::Ramp => (0.5 * h, 1.0 / h),
            Hold::ZeroOrder => (h, 0.0),
        };
        change[0][c] = dq;
        change[1][c] = 1.0;
        change[2][c] = da;
    }
    change
}

/// Adds the remainder's change at the free nodes, half of each element's
/// to each of its nodes, for free velocities `scale dq` and bottom `dvb`.
fn add_remainder_change(
    tangents: &[[[f64; 2]; 2]],
    dq: &[f64],
    scale: f64,
    dvb: [f64; 2],
    rhs: &mut [f64],
) {
    let node = |k: usize| {
        if k == 0 {
            dvb
        } else {
            [scale * dq[2 * (k - 1)], scale * dq[2 * (k - 1) + 1]]
        }
    };
    for (e, t) in tangents.iter().enumerate() {
        let (a, b) = (node(e), node(e + 1));
        let dr = mat2(t, [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])]);
        for k in [e, e + 1] {
            if k > 0 {
                rhs[2 * (k - 1)] += 0.5 * dr[0];
                rhs[2 * (k - 1) + 1] += 0.5 * dr[1];
            }
        }
    }
}
