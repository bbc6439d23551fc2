//! The section linearised about its start (`linear = true`): the cheap
//! fidelity of a section whose motion stays small about its static state (a
//! laid pipe on the seabed, the lower part of a mooring line, a riser's top).
//!
//! At `initialize`, after the static solve, the tangent stiffness K_t of the
//! elements and of the seabed (penalty springs at the nodes in contact then)
//! is formed once; the restoring force is then g(q) = g_s + K_t (q - q_s), so
//! HHT-alpha solves each step with one back-substitution of a matrix
//! factorised once per step size: no element tangent, no Newton. Morison drag
//! stays quadratic, linearised at each step's start: its velocity tangent
//! D_0 there joins the damping and the remainder F_d(v_0) - D_0 v_0 is a
//! load, so the step's drag is F_d(v_0) + D_0 (v - v_0), implicit in the
//! velocity (a Rosenbrock-like step: a section with drag forms and
//! factorises its matrix once per step, one solve, no Newton). Held
//! explicitly over the step instead, the drag blew up past h ~ 2 m / D_0
//! (the polyester line's lower part at 2 s steps, where the nonlinear
//! section stays bounded; `tests/tests/linear_section.rs`). Iterating the
//! remainder to Newton's tolerance cost as much as the nonlinear section
//! and changed the answers at the usual steps by less than 1e-5. Outputs (end
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
    /// Whether the section has drag (else the matrices stay constant).
    pub has_drag: bool,
    /// The drag's velocity tangent D_0 at the step's start (N s/m, N s).
    pub drag_tangent: SymmetricBand,
    /// The step's damping: the section's C plus D_0 (N s/m, N s).
    pub damping: SymmetricBand,
    /// The constant of the linear restoring force's potential,
    /// ½ q^T K_t q + offset . q + constant, chosen so that it equals the
    /// strain and contact energy at the start (J).
    pub potential_constant: f64,
}

impl Linearised {
    /// The potential (J) of the linear restoring force at `q`: the strain
    /// and contact energy of the linear model, whose balance the energy
    /// watch reads (the elements' own strain energy is not the potential of
    /// the linear force, so a cycle about the start left work over: a drift
    /// of 400 J/s on the polyester line).
    pub(super) fn potential(&self, q: &[f64]) -> f64 {
        let linear: f64 = self.offset.iter().zip(q).map(|(o, q)| o * q).sum();
        0.5 * self.stiffness.quadratic_form(q) + linear + self.potential_constant
    }
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
        let at_start = self.strain_energy() + self.state.contact.energy;
        let s = &self.state;
        let band = stiffness.half_bandwidth();
        let damping = match &self.c {
            Some(c) => c.clone(),
            None => SymmetricBand::zeros(n, band),
        };
        let mut linearised = Linearised {
            stiffness,
            offset,
            has_drag: self.environment.has_drag(),
            drag_tangent: SymmetricBand::zeros(n, band),
            damping,
            potential_constant: 0.0,
        };
        linearised.potential_constant = at_start - linearised.potential(&s.q);
        self.linear = Some(linearised);
        Ok(())
    }

    /// The linear step's loads (into `w.linear_f0`, `w.linear_f1`): the
    /// external `w.f0`, `w.f1` less the offset and the drag's remainder
    /// F_d(v_0) - D_0 v_0 at the step's start (into `w.drag_remainder`); the
    /// drag's tangent D_0 there into the step's damping C + D_0. The
    /// external loads stay as they are: the reactions are taken against them.
    pub(super) fn linear_loads(&mut self, w: &mut super::dynamics::StepWork) {
        let Some(l) = &mut self.linear else {
            return;
        };
        let s = &self.state;
        w.drag_remainder.clear();
        w.drag_remainder.resize(s.q.len(), 0.0);
        if l.has_drag {
            l.drag_tangent.fill_zero();
            let (tangent, remainder) = (&mut l.drag_tangent, &mut w.drag_remainder);
            (self.environment).add_drag_with_tangent(&self.model, (&s.q, &s.v), tangent, remainder);
            tangent.mul_add(-1.0, &s.v, remainder);
            match &self.c {
                Some(c) => l.damping.set_combination(&[(1.0, c), (1.0, tangent)]),
                None => l.damping.copy_from(tangent),
            }
        }
        for (out, f) in [(&mut w.linear_f0, &w.f0), (&mut w.linear_f1, &w.f1)] {
            out.clear();
            let shifted = f.iter().zip(&l.offset).zip(&w.drag_remainder);
            out.extend(shifted.map(|((f, o), r)| f - o - r));
        }
    }

    /// The restoring force at the current state: K_t q + offset, with the
    /// drag the step used at its end (its `remainder` plus D_0 v, so that
    /// the reactions are the step's own balance), or the drag at the current
    /// state where no step was taken (into `elastic` and `force`).
    pub(super) fn linear_forces(&mut self, remainder: Option<&[f64]>) {
        let Some(l) = &self.linear else {
            return;
        };
        let s = &mut self.state;
        s.elastic.copy_from_slice(&l.offset);
        l.stiffness.mul_add(1.0, &s.q, &mut s.elastic);
        s.force.copy_from_slice(&s.elastic);
        match remainder {
            Some(remainder) => {
                s.force.iter_mut().zip(remainder).for_each(|(f, r)| *f += r);
                if l.has_drag {
                    l.drag_tangent.mul_add(1.0, &s.v, &mut s.force);
                }
            }
            None => (self.environment).add_drag_force(&self.model, (&s.q, &s.v), 1.0, &mut s.force),
        }
    }

    /// The drag's tangent damping the last linear step used (D_0 at its
    /// start), for the step Jacobian: consistent with the step's matrix.
    pub(super) fn linear_drag_tangent(&self) -> Option<&SymmetricBand> {
        self.linear
            .as_ref()
            .filter(|l| l.has_drag)
            .map(|l| &l.drag_tangent)
    }
}
