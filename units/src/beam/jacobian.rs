//! The beam's interface Jacobian over its last step (`Unit::step_jacobian`): the
//! derivative of its end deflections, rotations, moments and shears with
//! respect to its coupled end inputs, one back-substitution per input with the
//! step's factorised HHT-alpha Newton matrix (`integrators::hht_sensitivity`;
//! the penalty contact's stiffness comes with that matrix). Other outputs
//! (energies, contact, stations) are left NaN. Not offered with the
//! energy-conserving contact law (its force is a discrete gradient).

use super::Beam;
use super::boundary::Quantity;
use crate::contract::{Hold, Inputs, UnitError, require_step_jacobian_ready};
use crate::integrators::hht_sensitivity::{Change, Drive, StepSensitivity};

/// Buffers of the Jacobian; `ready` while the last step's factor is the
/// integrator's.
#[derive(Default)]
pub(super) struct JacobianWork {
    pub ready: bool,
    /// The last step's length (s).
    pub h: f64,
    held: Vec<usize>,
    change: Change,
}

impl Beam {
    /// Fills `jacobian` (outputs x inputs): the end rows, the others NaN.
    pub(super) fn interface_jacobian(
        &mut self,
        inputs: Inputs<'_>,
        jacobian: &mut [f64],
    ) -> Result<(), UnitError> {
        require_step_jacobian_ready(self.jacobian.ready, "a beam")?;
        let mut w = std::mem::take(&mut self.jacobian);
        w.held.clear();
        w.held.extend(self.held_dofs());
        jacobian.fill(f64::NAN);
        let mut result = Ok(());
        for j in 0..inputs.len() {
            if let Err(e) = self.beam_column(inputs, &mut w, j, jacobian) {
                result = Err(e);
                break;
            }
        }
        self.jacobian = w;
        result
    }

    /// How a unit change of input `j` drives the step, if it does: a
    /// deflection or rotation moves its DOF, a moment or shear loads it (in f0
    /// and f1 alike: the load is read at the step's end).
    fn beam_drive(&self, inputs: Inputs<'_>, j: usize, h: f64) -> Option<Drive> {
        let c = self.conditions.iter().find(|c| c.input == Some(j))?;
        if c.quantity.is_kinematic() {
            let ramp = inputs.hold(j) == Hold::Ramp;
            let (dv, da) = if ramp {
                (1.0 / h, 1.0 / (h * h))
            } else {
                (0.0, 0.0)
            };
            return Some(Drive::Motion {
                dof: c.dof,
                change: [1.0, dv, da],
            });
        }
        let sign = match (c.quantity, c.end) {
            (Quantity::Moment, 1) | (Quantity::Shear, 0) => 1.0,
            _ => -1.0,
        };
        Some(Drive::Load {
            dof: c.dof,
            weight: sign,
        })
    }

    /// Column `j` of the end rows: deflection and rotation, and the moment and
    /// shear from the reaction's change (or the coupled load itself).
    fn beam_column(
        &self,
        inputs: Inputs<'_>,
        w: &mut JacobianWork,
        j: usize,
        jacobian: &mut [f64],
    ) -> Result<(), UnitError> {
        let n_in = inputs.len();
        let damping_at = |i: usize, k: usize| self.c.get(i, k);
        let sensitivity =
            StepSensitivity::of_last_step(&self.hht, "beam", (&self.m, &damping_at), w.h)?;
        match self.beam_drive(inputs, j, w.h) {
            Some(drive) => sensitivity.solve(drive, &w.held, &mut w.change),
            None => w.change.clear(self.state.q.len()),
        }
        let nodes = self.state.q.len() / 2;
        for end in 0..2 {
            let node = if end == 0 { 0 } else { nodes - 1 };
            let reaction = |d: usize| sensitivity.reaction_change(&w.change, d);
            let (ry, rth) = (reaction(2 * node), reaction(2 * node + 1));
            let (moment, shear) = if end == 0 { (-rth, ry) } else { (rth, -ry) };
            let mut rows = [
                w.change.dq[2 * node],
                w.change.dq[2 * node + 1],
                moment,
                shear,
            ];
            for c in self
                .conditions
                .iter()
                .filter(|c| c.end == end && !c.quantity.is_kinematic())
            {
                let k = if c.quantity == Quantity::Moment { 2 } else { 3 };
                rows[k] = if c.input == Some(j) { 1.0 } else { 0.0 };
            }
            for (k, v) in rows.into_iter().enumerate() {
                jacobian[(4 * end + k) * n_in + j] = v;
            }
        }
        Ok(())
    }
}
