//! The section's last step moved to changed end inputs to first order
//! (`Unit::correct_step`, for a master closing a step after one sweep): the
//! coordinates by the step's derivatives (the columns its Jacobian solved
//! for), the velocities and accelerations by Newmark's relations (a driven
//! end by its drive's), then the step's end taken again at the moved state:
//! forces, reactions, contact summary, bend moments and the energy ledger's
//! last entry, from what they were before that end.

use super::NonlinearSection;
use crate::contract::{Inputs, UnitError};
use crate::integrators::hht_sensitivity::Drive;

impl NonlinearSection {
    /// Whether the section can correct its steps: it gives its Jacobian from
    /// its whole coordinates (HHT-alpha, no contact by discrete gradient, not
    /// reduced).
    pub(super) fn offers_correction(&self) -> bool {
        self.offers_jacobian() && self.params.reduced_modes.is_none() && self.reduction.is_none()
    }

    /// The last step with its end inputs moved by `change` (one per input);
    /// `inputs`: the moved end inputs.
    pub(super) fn correct_last_step(
        &mut self,
        inputs: Inputs<'_>,
        change: &[f64],
    ) -> Result<(), UnitError> {
        let n = self.model.dofs();
        let mut w = std::mem::take(&mut self.work);
        // `w.f1` holds the coordinates' change first, then the moved loads.
        w.f1.clear();
        w.f1.resize(n, 0.0);
        let known = self.offers_correction()
            && self.jacobian_work.ready
            && self.jacobian_work.warm.add_change(change, &mut w.f1);
        if !known {
            self.work = w;
            return Err(UnitError::State(
                "nonlinear section: a step correction needs the step's Jacobian, taken after a whole step".into(),
            ));
        }
        let h = self.jacobian_work.h;
        self.jacobian_work.ready = false;
        self.move_motion(inputs, &w.f1, (change, h));
        // The step's end again, from what it was before it.
        let t1 = self.state.t;
        self.applied_load(inputs, (t1, 1.0), &mut w.f1);
        self.add_end_load_moments((&w.q0, t1), 1.0, &mut w.f1);
        self.state.ledger = w.before_end.ledger;
        self.state.lambda.clone_from(&w.before_end.lambda);
        // A pending end left the step start's outside force in place.
        if !std::mem::take(&mut w.end_pending) {
            std::mem::swap(&mut self.state.outside, &mut w.outside);
        }
        self.take_end(w, h)?;
        crate::contract::require_finite_state("nonlinear section", &self.state.q)
    }

    /// Moves q by `dq`, v and a by Newmark's relations for a change of the
    /// free coordinates, and a driven end's v and a by its drive times the
    /// input's change.
    fn move_motion(&mut self, inputs: Inputs<'_>, dq: &[f64], (change, h): (&[f64], f64)) {
        let (_, beta, gamma) = self.hht.parameters();
        let s = &mut self.state;
        for (i, d) in dq.iter().enumerate() {
            s.q[i] += d;
            s.v[i] += gamma / (beta * h) * d;
            s.a[i] += d / (beta * h * h);
        }
        for k in 0..self.ends.len() {
            let (dof, input) = match &self.ends[k] {
                r if r.is_kinematic() => (r.dof, r.input),
                _ => continue,
            };
            // A held DOF moves only by its drive (its column is the drive's).
            let (v, a) = (self.state.v[dof], self.state.a[dof]);
            let d = dq[dof];
            let (mut dv, mut da) = (-gamma / (beta * h) * d, -d / (beta * h * h));
            if let Some(j) = input
                && let Some(Drive::Motion {
                    change: [_, v1, a1],
                    ..
                }) = self.drive_of(inputs, j, h)
            {
                dv += v1 * change[j];
                da += a1 * change[j];
            }
            self.state.v[dof] = v + dv;
            self.state.a[dof] = a + da;
        }
    }
}
