//! A step's end left pending for the correction that follows it
//! (`Unit::defer_step_end`, `newton.one_sweep`). A step's end evaluates every
//! element, its drag and the contacts at the reached state (forces,
//! reactions, bend moments, energy ledger); a step the master then corrects
//! takes that end again at the moved state (`correction.rs`), so the first
//! one is wasted. Deferred, the step's end takes only what the master reads
//! before correcting: the reactions at the end nodes, from the two end
//! elements, their drag and the contacts, summed in the order the whole end
//! sums them (the same values to the bit). The rest is taken by the
//! correction or by `complete_step`. A `linear` section's end reactions are
//! rows of its band products (K_t q + offset, the drag its step used, M a,
//! C v), taken the same way.

use super::NonlinearSection;
use super::dynamics::{Failure, StepWork};
use crate::contract::UnitError;

/// The outputs at the two ends (position, velocity and force, x, z and
/// rotation at each): what a deferred end brings to the step's end.
const END_OUTPUTS: usize = 18;

impl NonlinearSection {
    /// Whether the section can leave a step's end pending with `coupled`
    /// (the outputs the master reads before correcting) exact: a section that
    /// corrects its steps, coupled by its end outputs alone.
    pub(super) fn can_defer_end(&self, coupled: &[usize]) -> bool {
        self.offers_correction() && coupled.iter().all(|&o| o < END_OUTPUTS)
    }

    /// The support reactions at the end nodes at the current state under the
    /// step's end `load`, as the whole end forms them (`g`: scratch for the
    /// restoring force; `remainder`: the drag remainder a linear step used);
    /// the other DOFs' are left as they were.
    pub(super) fn end_reactions(&mut self, load: &[f64], remainder: &[f64], g: &mut Vec<f64>) {
        let nodes = self.model.reference.len();
        if self.linear.is_none() {
            self.end_restoring_force(g);
        }
        let s = &mut self.state;
        for node in [0, nodes - 1] {
            for d in 3 * node..3 * node + 3 {
                let force = match &self.linear {
                    // The rows of `linear_forces`, summed as it sums them.
                    Some(l) => {
                        let elastic = l.stiffness.mul_add_row(1.0, &s.q, d, l.offset[d]);
                        let force = elastic + remainder[d];
                        match l.has_drag {
                            true => l.drag_tangent.mul_add_row(1.0, &s.v, d, force),
                            false => force,
                        }
                    }
                    None => g[d],
                };
                let mut r = force - load[d];
                r = self.m.mul_add_row(1.0, &s.a, d, r);
                if let Some(c) = &self.c {
                    r = c.mul_add_row(1.0, &s.v, d, r);
                }
                s.reaction[d] = r;
            }
        }
    }

    /// The restoring force at the end nodes (into `g`, the other entries
    /// left zero): the two end elements' forces, their drag and the contacts.
    fn end_restoring_force(&self, g: &mut Vec<f64>) {
        let (ends, count) = self.model.end_elements();
        let elements = &ends[..count];
        g.clear();
        g.resize(self.model.dofs(), 0.0);
        let s = &self.state;
        for &e in elements {
            self.model.add_element_force(e, &s.q, g);
        }
        if !self.environment.is_empty() {
            let at = (s.q.as_slice(), s.v.as_slice(), s.t);
            (self.environment).add_end_force(&self.model, at, &s.lambda, elements, g);
        }
    }

    /// Takes the end of the last step if it was left pending; whether it was.
    pub(super) fn complete_pending_end(&mut self) -> Result<bool, UnitError> {
        if !self.work.end_pending {
            return Ok(false);
        }
        let mut w = std::mem::take(&mut self.work);
        w.end_pending = false;
        let h = self.jacobian_work.h;
        self.take_end(w, h).map(|()| true)
    }

    /// The end of the step of `h` seconds in `w` taken whole at the current
    /// state (after a pending end, or again after a correction), its bend
    /// moments the largest of the step's start and end; `w` back in place.
    pub(super) fn take_end(&mut self, mut w: StepWork, h: f64) -> Result<(), UnitError> {
        let jump = w.before_end.surface_jump;
        let ended = self.end_step(&mut w, h, jump, false);
        let start = w.before_end.bend_start;
        self.work = w;
        let s = &mut self.state;
        s.bend_step = [start[0].max(s.bend_now[0]), start[1].max(s.bend_now[1])];
        match ended {
            Ok(()) => Ok(()),
            Err(Failure::Newton(e) | Failure::Other(e)) => Err(e),
        }
    }
}
