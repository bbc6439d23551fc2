//! The beam's interface Jacobian over its last step (`Unit::step_jacobian`): the
//! derivative of its end deflections, rotations, moments and shears with
//! respect to its coupled end inputs, one back-substitution per input with the
//! step's factorised HHT-alpha Newton matrix. The stiffness of the step's end
//! (elements and penalty contact) comes from that matrix:
//! `(1 - alpha) K_t = S - M / (beta h^2) - (1 - alpha) gamma / (beta h) C`.
//! Other outputs (energies, contact, stations) are left NaN. Not offered with
//! the energy-conserving contact law (its force is a discrete gradient).

use super::Beam;
use super::boundary::Quantity;
use crate::contract::{Hold, Inputs, UnitError};

/// Buffers of the Jacobian; `ready` while the last step's factor is the
/// integrator's.
#[derive(Default)]
pub(super) struct JacobianWork {
    pub ready: bool,
    /// The last step's length (s).
    pub h: f64,
    dq: Vec<f64>,
    dv: Vec<f64>,
    da: Vec<f64>,
}

impl Beam {
    /// Fills `jacobian` (outputs x inputs): the end rows, the others NaN.
    pub(super) fn interface_jacobian(
        &mut self,
        inputs: Inputs<'_>,
        jacobian: &mut [f64],
    ) -> Result<(), UnitError> {
        if !self.jacobian.ready {
            return Err(UnitError::Unsupported(
                "the step Jacobian of a beam before any step or after a rollback".into(),
            ));
        }
        let mut w = std::mem::take(&mut self.jacobian);
        jacobian.fill(f64::NAN);
        let n_in = inputs.len();
        let mut result = Ok(());
        for j in 0..n_in {
            if let Err(e) = self.beam_column(inputs, &mut w, j) {
                result = Err(e);
                break;
            }
            self.write_beam_column(&w, j, n_in, jacobian);
        }
        self.jacobian = w;
        result
    }

    /// dq, dv, da for a unit change of input `j`'s end value.
    fn beam_column(
        &self,
        inputs: Inputs<'_>,
        w: &mut JacobianWork,
        j: usize,
    ) -> Result<(), UnitError> {
        let n = self.state.q.len();
        let (alpha, beta, gamma) = self.hht.parameters();
        let h = w.h;
        for v in [&mut w.dq, &mut w.dv, &mut w.da] {
            v.clear();
            v.resize(n, 0.0);
        }
        let Some(c) = self.conditions.iter().find(|c| c.input == Some(j)) else {
            return Ok(());
        };
        let (s, factor) = self.hht.last_newton().ok_or_else(|| {
            UnitError::Numerical("beam: no Newton matrix of the last step".into())
        })?;
        let ramp = inputs.hold(j) == Hold::Ramp;
        let d = c.dof;
        let motion = if c.quantity.is_kinematic() {
            let (dv, da) = if ramp {
                (1.0 / h, 1.0 / (h * h))
            } else {
                (0.0, 0.0)
            };
            // dR_f = S dq + M (da - dq / (beta h^2)) + (1 - alpha) C (dv - gamma / (beta h) dq).
            let band = super::elements::BAND;
            for f in d.saturating_sub(band)..(d + band + 1).min(n) {
                w.dq[f] = -(s.get(f, d)
                    + self.m.get(f, d) * (da - 1.0 / (beta * h * h))
                    + (1.0 - alpha) * self.c.get(f, d) * (dv - gamma / (beta * h)));
            }
            for held in self.held_dofs() {
                w.dq[held] = 0.0;
            }
            w.dq[d] = 1.0;
            Some((dv, da))
        } else {
            // The coupled load enters f0 and f1 alike (its end value).
            let sign = match (c.quantity, c.end) {
                (Quantity::Moment, 1) | (Quantity::Shear, 0) => 1.0,
                _ => -1.0,
            };
            w.dq[d] = sign;
            None
        };
        factor.solve_in_place(&mut w.dq);
        for i in 0..n {
            w.da[i] = w.dq[i] / (beta * h * h);
            w.dv[i] = gamma / (beta * h) * w.dq[i];
        }
        for held in self.held_dofs() {
            w.dv[held] = 0.0;
            w.da[held] = 0.0;
        }
        if let Some((dv, da)) = motion {
            w.dv[d] = dv;
            w.da[d] = da;
        }
        Ok(())
    }

    /// Column `j` of the end rows: deflection and rotation, and the moment and
    /// shear from the reaction's change (or the coupled load itself).
    fn write_beam_column(&self, w: &JacobianWork, j: usize, n_in: usize, jacobian: &mut [f64]) {
        let nodes = self.state.q.len() / 2;
        for end in 0..2 {
            let node = if end == 0 { 0 } else { nodes - 1 };
            let (ry, rth) = (
                self.reaction_change(w, 2 * node),
                self.reaction_change(w, 2 * node + 1),
            );
            let (moment, shear) = if end == 0 { (-rth, ry) } else { (rth, -ry) };
            let base = 4 * end;
            let mut rows = [w.dq[2 * node], w.dq[2 * node + 1], moment, shear];
            for c in self
                .conditions
                .iter()
                .filter(|c| c.end == end && !c.quantity.is_kinematic())
            {
                let k = if c.quantity == Quantity::Moment { 2 } else { 3 };
                rows[k] = if c.input == Some(j) { 1.0 } else { 0.0 };
            }
            for (k, v) in rows.into_iter().enumerate() {
                jacobian[(base + k) * n_in + j] = v;
            }
        }
    }

    /// d(M a + C v + K_t q) at DOF `i`.
    fn reaction_change(&self, w: &JacobianWork, i: usize) -> f64 {
        let Some((s, _)) = self.hht.last_newton() else {
            return f64::NAN;
        };
        let (alpha, beta, gamma) = self.hht.parameters();
        let h = w.h;
        let n = self.state.q.len();
        let band = super::elements::BAND;
        (i.saturating_sub(band)..(i + band + 1).min(n))
            .map(|k| {
                let (m, c) = (self.m.get(i, k), self.c.get(i, k));
                let kt =
                    (s.get(i, k) - m / (beta * h * h)) / (1.0 - alpha) - gamma / (beta * h) * c;
                m * w.da[k] + c * w.dv[k] + kt * w.dq[k]
            })
            .sum()
    }
}
