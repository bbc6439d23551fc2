//! Time integration of the beam: the beam as a [`SecondOrderSystem`] (contact as
//! its nonlinear force) stepped by the shared HHT-alpha integrator (seed 004 eqs.
//! 4.29-4.37), the consistent initial acceleration, and modal analysis.

use super::{Beam, ContactValues};
use crate::contact::Law;
use crate::contract::{Inputs, ModalAnalysis, Mode, UnitError};
use crate::integrators::hht::{
    HhtAlpha, Matrices, NewtonSettings, SecondOrderSystem, StepLoads, TangentScales, motion_fields,
};
use crate::numerics::banded::{BandLdlt, SymmetricBand};

/// The beam's buffers of one step, kept between steps.
#[derive(Default)]
pub(super) struct StepWork {
    f0: Vec<f64>,
    f1: Vec<f64>,
    /// The contact force at the step's start (a copy: the system is borrowed
    /// while stepping).
    g0: Vec<f64>,
    /// Prescribed DOFs at the step's end: (DOF, [q, v, a]).
    held: Vec<(usize, [f64; 3])>,
}

impl Beam {
    /// M a0 = F - C v0 - K q0 - F_contact at the initial time, with the held DOFs'
    /// accelerations prescribed.
    pub(super) fn initial_acceleration(&mut self, inputs: Inputs<'_>) -> Result<(), UnitError> {
        let t = self.state.t;
        self.apply_kinematics(inputs, t, 0.0);
        let n = self.state.q.len();
        let mut values = ContactValues::default();
        let (q, v, lambda) = (
            self.state.q.clone(),
            self.state.v.clone(),
            self.state.lambda.clone(),
        );
        self.contact_at(&q, &v, t, &lambda, None, None, &mut values);
        let mut load = vec![0.0; n];
        self.external_load(inputs, t, 0.0, &mut load);
        let mut rhs = vec![0.0; n];
        for i in 0..n {
            rhs[i] = load[i] - values.force[i];
        }
        self.c.mul_add(-1.0, &v, &mut rhs);
        self.k.mul_add(-1.0, &q, &mut rhs);
        let mut m = self.m.clone();
        let held: Vec<usize> = self.held_dofs().collect();
        // Move the held accelerations to the right-hand side, then hold them.
        let mut held_a = vec![0.0; n];
        for &d in &held {
            held_a[d] = self.state.a[d];
        }
        self.m.mul_add(-1.0, &held_a, &mut rhs);
        for &d in &held {
            m.set_identity_row(d);
            rhs[d] = self.state.a[d];
        }
        let factor = BandLdlt::new(&m)
            .ok_or_else(|| UnitError::Numerical("mass matrix is not positive definite".into()))?;
        factor.solve_in_place(&mut rhs);
        self.state.a.copy_from_slice(&rhs);
        self.accept_contact(&values, t);
        self.residual_at(&load, &values.force);
        Ok(())
    }

    /// Reactions: M a + C v + K q + F_contact - F at the current state.
    fn residual_at(&mut self, load: &[f64], contact: &[f64]) {
        let n = self.state.q.len();
        let r = &mut self.state.reaction;
        for i in 0..n {
            r[i] = contact[i] - load[i];
        }
        self.m.mul_add(1.0, &self.state.a, r);
        self.c.mul_add(1.0, &self.state.v, r);
        self.k.mul_add(1.0, &self.state.q, r);
    }

    /// One HHT-alpha step from t0 to t1 = t0 + h (s) with the shared integrator;
    /// returns the Newton iterations. h comes from the exact step length, not
    /// t1 - t0: that difference changes in its last bits from step to step, which
    /// would re-form and refactorise the linear Newton matrix every step. The step's
    /// buffers live in `self.work` and `self.hht` between steps, so a contact-free
    /// step allocates nothing.
    pub(super) fn hht_step(
        &mut self,
        inputs: Inputs<'_>,
        t0: f64,
        t1: f64,
        h: f64,
    ) -> Result<u32, UnitError> {
        let mut w = std::mem::take(&mut self.work);
        let mut hht = std::mem::take(&mut self.hht);
        let result = self.hht_step_with(inputs, &mut w, &mut hht, t0, t1, h);
        self.hht = hht;
        self.work = w;
        result
    }

    fn hht_step_with(
        &mut self,
        inputs: Inputs<'_>,
        w: &mut StepWork,
        hht: &mut HhtAlpha,
        t0: f64,
        t1: f64,
        h: f64,
    ) -> Result<u32, UnitError> {
        let n = self.state.q.len();
        w.f0.resize(n, 0.0);
        w.f1.resize(n, 0.0);
        self.external_load(inputs, t0, h, &mut w.f0);
        self.external_load(inputs, t1, h, &mut w.f1);
        // Held DOFs at t1 (from the start velocities, for input rates).
        w.held.clear();
        for c in self.conditions.iter().filter(|c| c.quantity.is_kinematic()) {
            w.held.push((c.dof, self.prescribed(inputs, c, t1, h)));
        }
        w.g0.clear();
        w.g0.extend_from_slice(&self.state.contact_force);
        let loads = StepLoads {
            t0,
            t1,
            h,
            f0: &w.f0,
            f1: &w.f1,
            g0: (!self.energy_conserving()).then_some(w.g0.as_slice()),
            held: &w.held,
        };
        self.state.t = t1;
        let newton = NewtonSettings {
            tolerance: self.params.newton_tolerance,
            max_iterations: self.params.newton_max_iterations,
        };
        let iterations = hht
            .step(self, &loads, newton)
            .inspect_err(|_| self.state.t = t0)?;
        self.finish_step(hht, &w.f1, t1);
        self.state.newton_iterations = iterations;
        Ok(iterations)
    }

    fn energy_conserving(&self) -> bool {
        matches!(
            self.params.contact.as_ref().map(|c| &c.method),
            Some(Law::EnergyConserving { .. })
        )
    }

    /// After a step: the contact force at t1 (unweighted) for the next step and the
    /// reactions (for the energy-conserving law the force the step used,
    /// 2 F_bar - X0), the contact region, the gaps, the reactions and the
    /// Lagrangian update of a time-step law.
    fn finish_step(&mut self, hht: &HhtAlpha, f1: &[f64], t1: f64) {
        let mut values = std::mem::take(&mut self.step_contact);
        let (q, v) = (&self.state.q, &self.state.v);
        if !self.points.is_empty() {
            let lambda = &self.state.lambda;
            if self.energy_conserving() {
                let mut scratch = hht.newton_matrix().clone();
                self.discrete_gradient(q, t1, &mut scratch, &mut values);
                let effective = values.force.clone();
                self.contact_at(q, v, t1, lambda, None, None, &mut values);
                values.force.copy_from_slice(&effective);
            } else {
                self.contact_at(q, v, t1, lambda, None, None, &mut values);
            }
        } else {
            values.force.clear();
            values.force.resize(q.len(), 0.0);
        }
        self.accept_contact(&values, t1);
        self.residual_at(f1, &values.force);
        if let Some(law) = self.params.contact.as_ref().map(|c| c.method.clone())
            && let Some(crate::contact::LambdaUpdate::TimeStep) = law.lambda_update()
        {
            self.update_lambda(&law, t1);
        }
        self.step_contact = values;
    }

    /// Energy-conserving contact: per point the force averaged over the step is the
    /// discrete gradient F_bar = (Xi(d1) - Xi(d0)) / (d1 - d0). The trapezoidal rule
    /// averages the end forces, so the force at the step's end is X1 = 2 F_bar - X0
    /// (X0 the previous step's end force): the step then follows the midpoint rule
    /// and the contact neither adds nor removes energy.
    fn discrete_gradient(
        &self,
        y: &[f64],
        t1: f64,
        jac: &mut crate::numerics::banded::SymmetricBand,
        out: &mut ContactValues,
    ) {
        out.force.clear();
        out.force
            .extend(self.state.contact_force.iter().map(|x| -x));
        let Some(contact) = &self.params.contact else {
            return;
        };
        for (i, p) in self.points.iter().enumerate() {
            let Some((f, _)) = contact.surface.at(p.x, t1) else {
                continue;
            };
            let base = 2 * p.element;
            let d1 = (0..4).map(|j| p.shape[j] * y[base + j]).sum::<f64>() - f;
            let d0 = self.state.gap[i];
            let (xi1, g1, k1) = contact.method.evaluate(d1, 0.0);
            let (g, k) = if d0.is_finite() && (d1 - d0).abs() > 1e-12 {
                let (xi0, _, _) = contact.method.evaluate(d0, 0.0);
                let gbar = (xi1 - xi0) / (d1 - d0);
                (gbar, (g1 - gbar) / (d1 - d0))
            } else {
                (g1, 0.5 * k1)
            };
            for j in 0..4 {
                out.force[base + j] += 2.0 * p.weight * g * p.shape[j];
            }
            let s = 2.0 * p.weight * k;
            if s != 0.0 {
                for r in 0..4 {
                    for col in 0..=r {
                        jac.add(base + r, base + col, s * p.shape[r] * p.shape[col]);
                    }
                }
            }
        }
    }
}

/// The beam for the integrator: M, C, K from the elements; contact as the
/// nonlinear force, with its Lagrangian updates after each Newton correction.
impl SecondOrderSystem for Beam {
    fn label(&self) -> &str {
        "beam"
    }

    fn matrices(&self) -> Matrices<'_> {
        Matrices {
            mass: &self.m,
            damping: Some(&self.c),
            stiffness: Some(&self.k),
            varies: false,
        }
    }

    motion_fields!(state);

    fn is_linear(&self) -> bool {
        self.points.is_empty()
    }

    fn nonlinear_force(
        &mut self,
        q: &[f64],
        v: &[f64],
        t: f64,
        tangent: Option<(&mut SymmetricBand, TangentScales)>,
        force: &mut Vec<f64>,
    ) {
        let mut values = std::mem::take(&mut self.step_contact);
        match tangent {
            Some((band, _)) if self.energy_conserving() => {
                self.discrete_gradient(q, t, band, &mut values);
            }
            Some((band, scales)) => {
                self.contact_at(
                    q,
                    v,
                    t,
                    &self.state.lambda,
                    None,
                    Some((band, scales.stiffness, scales.damping)),
                    &mut values,
                );
                for f in values.force.iter_mut() {
                    *f *= scales.stiffness;
                }
            }
            // A fixed-matrix iteration: the force alone (the beam is normally
            // stepped with its tangent by HHT-alpha).
            None if self.energy_conserving() => {
                let mut unused = SymmetricBand::zeros(q.len(), super::elements::BAND);
                self.discrete_gradient(q, t, &mut unused, &mut values);
            }
            None => self.contact_at(q, v, t, &self.state.lambda, None, None, &mut values),
        }
        // Hand the force over without copying; the buffer swapped in is cleared
        // by the next contact evaluation.
        std::mem::swap(force, &mut values.force);
        self.step_contact = values;
    }

    fn after_iteration(&mut self, q: &[f64], t: f64) {
        if let Some(law) = self.params.contact.as_ref().map(|c| c.method.clone())
            && let Some(crate::contact::LambdaUpdate::NewtonIteration) = law.lambda_update()
        {
            self.state.q.copy_from_slice(q);
            self.update_lambda(&law, t);
        }
    }
}

/// Modes of the beam with its kinematic conditions held (generalised eigenproblem
/// on the free DOFs), longest period first.
pub(super) fn modes(beam: &Beam, count: usize) -> Result<ModalAnalysis, UnitError> {
    let held: Vec<usize> = beam.held_dofs().collect();
    let n = beam.state.q.len();
    let free: Vec<usize> = (0..n).filter(|d| !held.contains(d)).collect();
    let pick = |m: &crate::numerics::banded::SymmetricBand| {
        nalgebra::DMatrix::from_fn(free.len(), free.len(), |i, j| m.get(free[i], free[j]))
    };
    let (m, k) = (pick(&beam.m), pick(&beam.k));
    let mut modes = Vec::new();
    for (w2, phi) in
        crate::numerics::modal::lowest_modes(&m, &k, count, "the beam has a rigid-body mode")?
    {
        let mut full = vec![0.0; n];
        for (a, &d) in free.iter().enumerate() {
            full[d] = phi[a];
        }
        let scale = full
            .iter()
            .step_by(2)
            .fold(0.0f64, |a, v| a.max(v.abs()))
            .max(1e-300);
        modes.push(Mode {
            period: 2.0 * std::f64::consts::PI / w2.sqrt(),
            shape: full
                .chunks(2)
                .map(|c| [c[0] / scale, c[1] / scale])
                .collect(),
        });
    }
    let positions = beam.node_positions().iter().map(|&x| [x, 0.0]).collect();
    Ok(ModalAnalysis { positions, modes })
}
