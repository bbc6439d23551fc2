//! The section linearised about its start (`linear = true`): the cheap
//! fidelity of a section whose motion stays small about its static state (a
//! laid pipe on the seabed, the lower part of a mooring line, a riser's top).
//!
//! At `initialize`, after the static solve, the tangent stiffness K_t of the
//! elements and of the seabed (penalty springs at the nodes in contact then)
//! is formed once; the restoring force is then g(q) = g_s + K_t (q - q_s), so
//! HHT-alpha solves each step with one back-substitution of a matrix
//! factorised once per step size: no element tangent, no Newton. Morison drag
//! stays quadratic, evaluated explicitly at the step's start and held over the
//! step (an O(h) lag, which light drag damping tolerates). Outputs (end
//! forces, stations, moments, touchdown) are those of the nonlinear section
//! at the linear state, but for the elements' axial force, linearised too
//! (the element's own on the linear state counts a rotation of its chord as
//! stretch: a riser's top in a 4 m sea read 2.3 % high). What it does not represent: large rotations of the
//! section, a touchdown point that moves (a node off the seabed at the start
//! never touches it, one on it is held by a bilateral spring), a stinger (a
//! section resting on one is refused; one it does not touch is left out).

use super::NonlinearSection;
use super::params::{Integrator, NonlinearParams};
use crate::contact::Law;
use crate::contract::UnitError;
use crate::numerics::banded::SymmetricBand;

/// The section's linear model about its start state.
#[derive(Clone, Debug)]
pub(super) struct Linearised {
    /// K_t at the start: elements and contact springs, no drag (N/m, N, N m).
    pub stiffness: SymmetricBand,
    /// g_s - K_t q_s: the restoring force is K_t q + offset (N, N m).
    pub offset: Vec<f64>,
}

/// Refuses what the linear section cannot represent, naming the key.
pub(super) fn validate(params: &NonlinearParams) -> Result<(), UnitError> {
    if !params.linear {
        return Ok(());
    }
    let refuse = |key: &str, value: &str, why: &str| Err(UnitError::parameter(key, value, why));
    if !matches!(params.integrator, Integrator::Hht { .. }) {
        return refuse(
            "integrator",
            "not hht",
            "with linear = true, kind = \"hht\" (one back-substitution a step)",
        );
    }
    if let Some(c) = &params.contact {
        if !matches!(c.method, Law::Penalty { .. }) {
            return refuse(
                "contact.method",
                "not penalty",
                "kind = \"penalty\" with linear = true (the seabed as springs at the nodes in contact at the start)",
            );
        }
    }
    Ok(())
}

impl NonlinearSection {
    /// Forms the linear model about the current state (after the statics).
    /// A section resting on a stinger is refused: its rollers move and the
    /// pipe lifts off them (a stinger it does not touch is left out).
    pub(super) fn linearise(&mut self) -> Result<(), UnitError> {
        self.linear = None;
        self.model.linear_axial = None;
        if !self.params.linear {
            return Ok(());
        }
        let (q, t) = (self.state.q.as_slice(), self.state.t);
        if self.environment.contacts.on_stinger(&self.model, (q, t)) {
            return Err(UnitError::parameter(
                "linear",
                "true",
                "false here: the section rests on the stinger's rollers at the start, which move and which the pipe lifts off; use the nonlinear section there",
            ));
        }
        let n = self.model.dofs();
        let stiffness = self.tangent_stiffness();
        // g_s: the elastic and contact force at the start, without drag.
        let mut offset = vec![0.0; n];
        let s = &self.state;
        self.model.add_internal_force(&s.q, 1.0, None, &mut offset);
        let contacts = &self.environment.contacts;
        if !contacts.is_empty() {
            contacts.add_force(
                &self.model,
                (&s.q, s.t, &s.lambda),
                1.0,
                true,
                None,
                &mut offset,
            );
        }
        stiffness.mul_add(-1.0, &s.q, &mut offset);
        self.model.linear_axial = Some(self.model.linearise_axial(&s.q));
        self.linear = Some(Linearised { stiffness, offset });
        Ok(())
    }

    /// The linear step's loads (into `w.linear_f0`, `w.linear_f1`): the
    /// external `w.f0`, `w.f1` less the offset and the drag at the step's
    /// start (into `w.drag`). The external loads stay as they are: the
    /// reactions are taken against them.
    pub(super) fn linear_loads(&self, w: &mut super::dynamics::StepWork) {
        let Some(l) = &self.linear else {
            return;
        };
        let s = &self.state;
        w.drag.clear();
        w.drag.resize(s.q.len(), 0.0);
        self.environment
            .add_drag_force(&self.model, (&s.q, &s.v), 1.0, &mut w.drag);
        for (out, f) in [(&mut w.linear_f0, &w.f0), (&mut w.linear_f1, &w.f1)] {
            out.clear();
            let shifted = f.iter().zip(&l.offset).zip(&w.drag);
            out.extend(shifted.map(|((f, o), d)| f - o - d));
        }
    }

    /// The restoring force at the current state: K_t q + offset, with the
    /// drag the step used (`step_drag`, so that the reactions are the step's
    /// own balance), or at the current state where no step was taken (into
    /// `elastic` and `force`).
    pub(super) fn linear_forces(&mut self, step_drag: Option<&[f64]>) {
        let Some(l) = &self.linear else {
            return;
        };
        let s = &mut self.state;
        s.elastic.copy_from_slice(&l.offset);
        l.stiffness.mul_add(1.0, &s.q, &mut s.elastic);
        s.force.copy_from_slice(&s.elastic);
        match step_drag {
            Some(drag) => s.force.iter_mut().zip(drag).for_each(|(f, d)| *f += d),
            None => self
                .environment
                .add_drag_force(&self.model, (&s.q, &s.v), 1.0, &mut s.force),
        }
    }
}
