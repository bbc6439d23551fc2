//! Dynamics of a nonlinear section: the section as a [`SecondOrderSystem`] whose
//! whole restoring force (elements, drag, contact) is the nonlinear force, stepped
//! by HHT-alpha with Newton or by explicit central differences; the initial
//! acceleration; modes about the current state.

use super::params::Integrator;
use super::{NonlinearSection, contact};
use crate::contract::{Inputs, UnitError};
use crate::integrators::central_difference::CentralDifference;
use crate::integrators::hht::{
    Matrices, NewtonSettings, SecondOrderSystem, StepLoads, TangentScales, motion_fields,
};
use crate::numerics::banded::{BandLdlt, SymmetricBand};

pub(super) use super::step_work::StepWork;

impl NonlinearSection {
    /// The tangent stiffness (elements and environment, without velocity terms)
    /// at the current state.
    pub(super) fn tangent_stiffness(&self) -> SymmetricBand {
        let n = self.model.dofs();
        let mut k = SymmetricBand::zeros(n, super::model::BAND);
        let mut scratch = vec![0.0; n];
        self.model
            .add_internal_force(&self.state.q, 1.0, Some((&mut k, 1.0)), &mut scratch);
        let zeros = vec![0.0; n];
        self.environment.add_force(
            &self.model,
            (&self.state.q, &zeros, self.state.t),
            &self.state.lambda,
            1.0,
            false,
            Some((&mut k, 1.0, 0.0)),
            &mut scratch,
        );
        k
    }

    /// Mass in the element frames of the current state, Rayleigh damping on the
    /// tangent there, and (for central differences) the critical step.
    pub(super) fn prepare_dynamics(&mut self) -> Result<(), UnitError> {
        self.hht.forget_matrices();
        let p = &self.params;
        self.m = self
            .model
            .mass(&self.state.q, &p.segments, p.mass, p.water_density);
        let mut k = self.tangent_stiffness();
        self.c = (p.rayleigh_mass > 0.0 || p.rayleigh_stiffness > 0.0).then(|| {
            let mut c = self.m.clone();
            c.set_combination(&[(p.rayleigh_mass, &self.m), (p.rayleigh_stiffness, &k)]);
            c
        });
        if self.params.integrator != Integrator::CentralDifference {
            return Ok(());
        }
        let held: Vec<usize> = self.held().map(|r| r.dof).collect();
        let mut m = self.m.clone();
        for &d in &held {
            m.set_identity_row(d);
            k.set_identity_row(d);
        }
        let matrices = Matrices {
            mass: &m,
            damping: None,
            stiffness: Some(&k),
            varies: false,
        };
        // With held DOFs as identity rows their "frequency" is 1 rad/s: harmless.
        self.critical_step = CentralDifference::critical_step(&matrices, 300)?;
        Ok(())
    }

    /// M a0 = f - C v0 - g(q0, v0) with the held DOFs' accelerations prescribed;
    /// then the reactions.
    pub(super) fn initial_acceleration(&mut self, inputs: Inputs<'_>) -> Result<(), UnitError> {
        let n = self.model.dofs();
        let t = self.state.t;
        let held: Vec<(usize, [f64; 3])> = self
            .held()
            .map(|r| {
                let d = r.dof;
                let start = [self.state.q[d], self.state.v[d], 0.0];
                (d, r.motion(inputs, (t, 0.0), (0.0, 1.0), start))
            })
            .collect();
        for &(d, [q, v, _]) in &held {
            self.state.q[d] = q;
            self.state.v[d] = v;
        }
        let mut load = vec![0.0; n];
        self.external_load(inputs, (t, 1.0), &mut load);
        let kept = self.restoring_forces(None, None);
        let mut rhs: Vec<f64> = load
            .iter()
            .zip(&self.state.force)
            .map(|(f, g)| f - g)
            .collect();
        if let Some(c) = &self.c {
            c.mul_add(-1.0, &self.state.v, &mut rhs);
        }
        for &(d, [_, _, a]) in &held {
            rhs[d] = a;
        }
        if self.params.reduced_modes.is_some() {
            self.reduced_start_rhs.clone_from(&rhs);
        }
        let reduced = self.reduced_start(&mut rhs)?;
        if reduced {
            // The state follows the reduced coordinates: evaluated anew.
            self.state.strain_energy = None;
        } else {
            let mut m = self.m.clone();
            for &(d, _) in &held {
                m.set_identity_row(d);
            }
            let factor = BandLdlt::new(&m).ok_or_else(|| {
                UnitError::Numerical(
                    "nonlinear section: the mass matrix is not positive definite".into(),
                )
            })?;
            // Held accelerations are zero at rest here, so no right-hand-side coupling.
            factor.solve_in_place(&mut rhs);
            self.state.a.copy_from_slice(&rhs);
        }
        self.finish(&load, false, kept && !reduced)?;
        self.open_ledger(&load);
        if self.params.static_start {
            // The force the section reports at its start is the equilibrium's
            // (g - f): the damping of an end already moving while every other
            // node rests (a Rayleigh beta K v of one node's velocity) and the
            // inertia of that jump are the first step's, not a load a
            // neighbour should solve its own statics under (issue 30: 3.32 MN
            // instead of 2.51 MN, which a cable section below kept as a 31 %
            // offset of its mean). A motion already moving at the start is an
            // impulsive start; `fade_in` starts it at rest.
            let s = &mut self.state;
            for ((r, g), f) in s.reaction.iter_mut().zip(&s.force).zip(&load) {
                *r = g - f;
            }
        }
        Ok(())
    }

    /// Reactions (M a + C v + g - f at the held DOFs), the contact summary (a
    /// node deeper than nodal contact represents is an error), the bend moments
    /// and, after a step, the Lagrangian updates; `kept`: `element_states`
    /// holds the elements at the current displacements.
    fn finish(&mut self, load: &[f64], after_step: bool, kept: bool) -> Result<(), UnitError> {
        let s = &mut self.state;
        for ((r, g), f) in s.reaction.iter_mut().zip(&s.force).zip(load) {
            *r = g - f;
        }
        self.m.mul_add(1.0, &s.a, &mut s.reaction);
        if let Some(c) = &self.c {
            c.mul_add(1.0, &s.v, &mut s.reaction);
        }
        let contacts = &self.environment.contacts;
        if !contacts.is_empty() {
            s.contact = contacts.summary(&self.model, (&s.q, s.t, &s.lambda));
            contacts.roller_loads(&self.model, (&s.q, s.t, &s.lambda), &mut s.rollers);
            if after_step {
                contacts.update_lambda(&self.model, (&s.q, s.t), &mut s.lambda);
            }
        }
        let (largest, now) = self.extremes(kept);
        let s = &mut self.state;
        s.largest = largest;
        if !after_step {
            s.bend_step = now;
        }
        s.bend_now = now;
        contact::check_penetration(&s.contact, s.t)
    }

    /// One step from t0 to t1 = t0 + h (s); returns the Newton iterations (0 for
    /// central differences). Where Newton fails, the step is retried in 2, 4, ...
    /// equal sub-steps up to `max_substeps`. On a Newton failure the state is
    /// unchanged; after any other failure only its time is reset.
    pub(super) fn step(
        &mut self,
        inputs: Inputs<'_>,
        t0: f64,
        t1: f64,
        h: f64,
    ) -> Result<u32, UnitError> {
        // A pending end the master did not take (it always does): taken now.
        self.complete_pending_end()?;
        let mut w = std::mem::take(&mut self.work);
        let defer = std::mem::take(&mut w.defer_next);
        self.jacobian_work.ready = false;
        let offers = self.offers_jacobian();
        if let (Some(guess), true) = (self.jacobian_work.warm.guess(t0, inputs.end()), offers) {
            match self.reduction.as_mut() {
                Some(r) => r.guess_next(guess),
                None => self.hht.guess_next(guess),
            }
        }
        // A whole step leaves the state at its start when Newton fails, so the
        // copy for sub-stepping is only taken then (nothing per ordinary step).
        let mut pieces = 1;
        let result = loop {
            match self.step_in_pieces(inputs, &mut w, (t0, t1, h), (pieces, defer)) {
                Ok(iterations) => break Ok(iterations),
                Err(failure) => {
                    if pieces > 1 {
                        if let Some(b) = &w.backup {
                            self.state.clone_from(b);
                        }
                    }
                    match failure {
                        Failure::Newton(_) if pieces < self.params.max_substeps => {
                            if pieces == 1 {
                                match w.backup.as_mut() {
                                    Some(b) => b.clone_from(&self.state),
                                    None => w.backup = Some(self.state.clone()),
                                }
                            }
                            pieces *= 2;
                        }
                        Failure::Newton(e) | Failure::Other(e) => {
                            self.state.t = t0;
                            break Err(e);
                        }
                    }
                }
            }
        };
        self.work = w;
        // The integrator's factor is this step's only when it was taken whole.
        self.jacobian_work.ready = pieces == 1 && result.is_ok() && self.offers_jacobian();
        self.jacobian_work.h = h;
        if self.jacobian_work.ready {
            let mut warm = std::mem::take(&mut self.jacobian_work.warm);
            warm.record_step(t0, inputs.end(), self.stepped_coordinates());
            self.jacobian_work.warm = warm;
        }
        result
    }

    /// The step as `pieces` equal sub-steps; the bend moments' maxima over all.
    /// With `defer`, a whole step's end is left pending (`deferred_end.rs`;
    /// only a whole step's end can be taken again by a correction).
    fn step_in_pieces(
        &mut self,
        inputs: Inputs<'_>,
        w: &mut StepWork,
        (t0, t1, h): (f64, f64, f64),
        (pieces, defer): (u32, bool),
    ) -> Result<u32, Failure> {
        let mut bend = self.state.bend_now;
        w.before_end.bend_start = bend;
        let defer = defer && pieces == 1;
        let mut total = 0;
        for k in 0..pieces {
            let (s0, s1) = (
                f64::from(k) / f64::from(pieces),
                f64::from(k + 1) / f64::from(pieces),
            );
            let a = if k == 0 { t0 } else { t0 + s0 * h };
            let b = if k + 1 == pieces { t1 } else { t0 + s1 * h };
            // The coupling step's own length when whole (bit-identical to before).
            let length = h / f64::from(pieces);
            total += self.step_with(inputs, w, (a, b, length), (s0, s1), defer)?;
            bend = [
                bend[0].max(self.state.bend_now[0]),
                bend[1].max(self.state.bend_now[1]),
            ];
        }
        self.state.bend_step = bend;
        self.state.newton_iterations = total;
        Ok(total)
    }

    fn step_with(
        &mut self,
        inputs: Inputs<'_>,
        w: &mut StepWork,
        (t0, t1, h): (f64, f64, f64),
        (s0, s1): (f64, f64),
        defer: bool,
    ) -> Result<u32, Failure> {
        let n = self.model.dofs();
        w.f0.resize(n, 0.0);
        w.f1.resize(n, 0.0);
        self.external_load(inputs, (t0, s0), &mut w.f0);
        self.external_load(inputs, (t1, s1), &mut w.f1);
        self.linear_loads(w);
        let linear = self.linear.is_some();
        w.held.clear();
        for r in self.ends.iter().filter(|r| r.is_kinematic()) {
            let d = r.dof;
            let start = [self.state.q[d], self.state.v[d], self.state.a[d]];
            w.held.push((d, r.motion(inputs, (t1, h), (s0, s1), start)));
        }
        w.q0.clear();
        w.q0.extend_from_slice(&self.state.q);
        let surface_jump = self.surface_jump(t1);
        let iterations = match self.params.integrator {
            Integrator::Hht {
                tolerance,
                max_iterations,
                ..
            }
            | Integrator::EnergyConserving {
                tolerance,
                max_iterations,
            } => {
                w.g0.clear();
                w.g0.extend_from_slice(&self.state.force);
                let loads = StepLoads {
                    t0,
                    t1,
                    h,
                    f0: if linear { &w.linear_f0 } else { &w.f0 },
                    f1: if linear { &w.linear_f1 } else { &w.f1 },
                    g0: (!self.energy_conserving() && !linear).then_some(w.g0.as_slice()),
                    held: &w.held,
                };
                let newton = NewtonSettings {
                    tolerance,
                    max_iterations,
                };
                let result = if self.reduction.is_some() {
                    self.reduced_step((&w.f0, &w.f1, &w.held), (t0, t1, h), newton)
                } else {
                    let mut hht = std::mem::take(&mut self.hht);
                    let result = hht.step(self, &loads, newton);
                    self.hht = hht;
                    result
                };
                result.map_err(Failure::Newton)?
            }
            Integrator::CentralDifference => {
                if h > self.critical_step {
                    return Err(Failure::Other(UnitError::Numerical(format!(
                        "nonlinear section: the step {h} s exceeds the critical step {:.4e} s of central differences (2 / omega_max of the tangent at the start)",
                        self.critical_step
                    ))));
                }
                let mut explicit = std::mem::take(&mut self.explicit);
                let result = explicit.step(self, t1, h, &w.f1, &w.held);
                self.explicit = explicit;
                result.map_err(Failure::Other)?;
                0
            }
        };
        self.state.t = t1;
        self.end_step(w, h, surface_jump, defer)?;
        Ok(iterations)
    }

    /// The last step's local displacement error (m) over the nodes' x and z,
    /// where HHT-alpha took it on the full coordinates (not the reduced or
    /// explicit steps).
    pub(super) fn local_displacement_error(&self) -> Option<f64> {
        let hht = matches!(
            self.params.integrator,
            Integrator::Hht { .. } | Integrator::EnergyConserving { .. }
        );
        (hht && self.reduction.is_none()).then(|| self.hht.local_error(|d| d % 3 < 2))
    }

    /// After a step of length `h` (s) from `w.q0` under `w.f1`: the restoring
    /// forces, reactions and contact summary at its end, and its entry in the
    /// energy balance (with the moving surfaces' `surface_jump`, J). With
    /// `defer`, the end reactions alone, the rest left pending.
    pub(super) fn end_step(
        &mut self,
        w: &mut StepWork,
        h: f64,
        surface_jump: f64,
        defer: bool,
    ) -> Result<(), Failure> {
        w.before_end.ledger = self.state.ledger;
        w.before_end.lambda.clone_from(&self.state.lambda);
        w.before_end.surface_jump = surface_jump;
        if defer {
            self.end_reactions(&w.f1, &w.drag_remainder, &mut w.end_force);
            w.end_pending = true;
            return Ok(());
        }
        let q0 = self.energy_conserving().then_some(w.q0.as_slice());
        let kept = self.restoring_forces(q0, Some(&w.drag_remainder));
        let surface_power = self.surface_power();
        self.finish(&w.f1, true, kept).map_err(Failure::Other)?;
        let surface = (surface_power, surface_jump);
        self.record_step(&w.f1, (&w.q0, h), surface, &mut w.outside);
        Ok(())
    }
}

/// Why a step failed: Newton (worth retrying in sub-steps) or anything else.
pub(super) enum Failure {
    Newton(UnitError),
    Other(UnitError),
}

impl NonlinearSection {
    fn energy_conserving(&self) -> bool {
        matches!(self.params.integrator, Integrator::EnergyConserving { .. })
    }

    /// The restoring force at the current state: the linear model's (with
    /// the drag its step used, from the step's drag `remainder`) where the
    /// section is linear, else [`Self::refresh_forces`].
    /// True when each element's state at the current displacements is kept
    /// (`element_states`) for the extremes.
    fn restoring_forces(&mut self, step_start: Option<&[f64]>, remainder: Option<&[f64]>) -> bool {
        if self.linear.is_some() {
            self.state.strain_energy = None;
            self.element_states.clear();
            self.linear_forces(remainder);
        } else {
            self.refresh_forces(step_start);
        }
        !self.element_states.is_empty()
    }

    /// The elastic force at the current state as the integrator used it (the
    /// element forces, or after an energy-conserving step from `q0`, 2 g_bar(q0,
    /// q) - g0) and the total restoring force with drag and contact.
    fn refresh_forces(&mut self, step_start: Option<&[f64]>) {
        let s = &mut self.state;
        self.element_states.clear();
        s.strain_energy = None;
        if let Some(q0) = step_start {
            for g in s.elastic.iter_mut() {
                *g = -*g;
            }
            self.model
                .add_discrete_gradient((q0, &s.q), 2.0, None, &mut s.elastic);
        } else {
            s.elastic.fill(0.0);
            let states = &mut self.element_states;
            (self.model).add_internal_force_keeping(&s.q, &mut s.elastic, states);
            s.strain_energy = Some(states.iter().map(|e| e.strain_energy).sum());
        }
        s.force.copy_from_slice(&s.elastic);
        let contacts = &self.environment.contacts;
        if contacts.is_discrete() {
            if let Some(q0) = step_start {
                for g in s.stepped_contact.iter_mut() {
                    *g = -*g;
                }
                let dg = (q0, s.q.as_slice(), s.t);
                contacts.add_discrete_gradient(&self.model, dg, 1.0, None, &mut s.stepped_contact);
            } else {
                // The discrete gradient of a step of zero length is the gradient.
                s.stepped_contact.fill(0.0);
                let at = (s.q.as_slice(), s.q.as_slice(), s.t);
                contacts.add_discrete_gradient(&self.model, at, 0.5, None, &mut s.stepped_contact);
            }
            for (f, c) in s.force.iter_mut().zip(&s.stepped_contact) {
                *f += c;
            }
        }
        if !self.environment.is_empty() {
            let state = (s.q.as_slice(), s.v.as_slice(), s.t);
            let drag = &mut self.drag_at_state;
            (self.environment).add_force_keeping_drag(
                &self.model,
                state,
                &s.lambda,
                &mut s.force,
                drag,
            );
        }
    }

    /// The elastic force of an iterate q1 as it enters the residual, times
    /// `scale`, with its tangent.
    fn add_elastic(
        &self,
        q: &[f64],
        scale: f64,
        tangent: Option<(&mut SymmetricBand, f64)>,
        out: &mut [f64],
    ) {
        if self.energy_conserving() {
            self.model.add_discrete_gradient(
                (&self.state.q, q),
                2.0 * scale,
                tangent.map(|(b, f)| (b, 2.0 * f)),
                out,
            );
            for (o, g) in out.iter_mut().zip(&self.state.elastic) {
                *o -= scale * g;
            }
        } else {
            self.model.add_internal_force(q, scale, tangent, out);
        }
    }
}

/// The section for the integrators: M and C constant, no linear stiffness, the
/// whole restoring force nonlinear with its tangent.
impl SecondOrderSystem for NonlinearSection {
    fn label(&self) -> &str {
        "nonlinear section"
    }

    fn matrices(&self) -> Matrices<'_> {
        match &self.linear {
            Some(l) => Matrices {
                mass: &self.m,
                damping: (l.has_drag || self.c.is_some()).then_some(&l.damping),
                stiffness: Some(&l.stiffness),
                varies: l.has_drag,
            },
            None => Matrices {
                mass: &self.m,
                damping: self.c.as_ref(),
                stiffness: None,
                varies: false,
            },
        }
    }

    motion_fields!(state);

    fn is_linear(&self) -> bool {
        self.linear.is_some()
    }

    /// A correction moving a node by more than the shortest element or turning
    /// it by more than 0.5 rad is scaled down: where a slack part makes the
    /// tangent nearly singular, an undamped step can turn a node by whole turns,
    /// which the wrapped local rotations accept as an equilibrium.
    fn limit_correction(&self, dq: &mut [f64]) -> f64 {
        if self.linear.is_some() {
            // One exact solve: nothing to damp.
            return 1.0;
        }
        let factor = self.model.correction_limit(dq);
        if factor < 1.0 {
            dq.iter_mut().for_each(|d| *d *= factor);
        }
        factor
    }

    fn nonlinear_force(
        &mut self,
        q: &[f64],
        v: &[f64],
        t: f64,
        tangent: Option<(&mut SymmetricBand, TangentScales)>,
        force: &mut Vec<f64>,
    ) {
        force.resize(q.len(), 0.0);
        force.fill(0.0);
        let (mut band, scales) = TangentScales::split(tangent);
        let stiffness = scales.stiffness;
        let elastic_tangent = band.as_mut().map(|b| (&mut **b, stiffness));
        self.add_elastic(q, stiffness, elastic_tangent, force);
        if !self.environment.is_empty() {
            let contacts = &self.environment.contacts;
            if contacts.is_discrete() {
                let tangent = band.as_mut().map(|b| (&mut **b, stiffness));
                let dg = (self.state.q.as_slice(), q, t);
                contacts.add_discrete_gradient(&self.model, dg, stiffness, tangent, force);
                for (f, c) in force.iter_mut().zip(&self.state.stepped_contact) {
                    *f -= stiffness * c;
                }
            }
            let tangent = band.map(|b| (b, stiffness, scales.damping));
            let lambda = &self.state.lambda;
            self.environment.add_force(
                &self.model,
                (q, v, t),
                lambda,
                stiffness,
                true,
                tangent,
                force,
            );
        }
    }
}
