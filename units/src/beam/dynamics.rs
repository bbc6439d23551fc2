//! Time integration of the beam: HHT-alpha (alpha in [0, 1/3], beta = (1+alpha)^2/4,
//! gamma = 1/2 + alpha; seed 004 eqs. 4.29-4.37) with Newton iterations on the
//! contact terms, the consistent initial acceleration, and modal analysis.

use super::{Beam, ContactValues};
use crate::contact::Law;
use crate::contract::{Inputs, ModalAnalysis, Mode, UnitError};
use crate::numerics::banded::BandLdlt;

/// Buffers of one HHT step, kept between steps.
#[derive(Default)]
pub(super) struct StepWork {
    q0: Vec<f64>,
    v0: Vec<f64>,
    a0: Vec<f64>,
    f0: Vec<f64>,
    f1: Vec<f64>,
    constant: Vec<f64>,
    y: Vec<f64>,
    v1: Vec<f64>,
    a1: Vec<f64>,
    held: Vec<usize>,
    held_v: Vec<f64>,
    held_a: Vec<f64>,
    values: ContactValues,
    history: Vec<f64>,
    /// Factor of the Newton matrix with contact, refactorised in place.
    factor: Option<BandLdlt>,
}

impl StepWork {
    fn resize(&mut self, n: usize) {
        for v in [
            &mut self.q0,
            &mut self.v0,
            &mut self.a0,
            &mut self.f0,
            &mut self.f1,
            &mut self.constant,
            &mut self.y,
            &mut self.v1,
            &mut self.a1,
        ] {
            v.resize(n, 0.0);
        }
    }

    /// Newmark: acceleration and velocity at the step's end from the iterate y, the
    /// held DOFs keeping their prescribed motion.
    fn kinematics(&mut self, h: f64, beta: f64, gamma: f64) {
        for i in 0..self.y.len() {
            self.a1[i] = (self.y[i] - self.q0[i] - h * self.v0[i]) / (beta * h * h)
                - (0.5 / beta - 1.0) * self.a0[i];
            self.v1[i] = self.v0[i] + h * ((1.0 - gamma) * self.a0[i] + gamma * self.a1[i]);
        }
        for (k, &d) in self.held.iter().enumerate() {
            self.v1[d] = self.held_v[k];
            self.a1[d] = self.held_a[k];
        }
    }
}

impl Beam {
    /// Newmark parameters of the HHT-alpha scheme.
    fn hht(&self) -> (f64, f64, f64) {
        let alpha = self.params.alpha;
        (alpha, 0.25 * (1.0 + alpha).powi(2), 0.5 + alpha)
    }

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
        self.state.contact_force.copy_from_slice(&values.force);
        self.state.contact = [
            values.energy,
            values.start,
            values.end,
            values.length,
            values.max_penetration,
        ];
        self.record_gaps(t);
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

    /// M / (beta h^2) + (1 - alpha) (gamma / (beta h) C + K), formed when h changes.
    fn prepare_linear(&mut self, h: f64) {
        if self.linear_h == h {
            return;
        }
        let (alpha, beta, gamma) = self.hht();
        self.linear.set_combination(&[
            (1.0 / (beta * h * h), &self.m),
            ((1.0 - alpha) * gamma / (beta * h), &self.c),
            (1.0 - alpha, &self.k),
        ]);
        let mut held = self.linear.clone();
        for d in self.held_dofs().collect::<Vec<_>>() {
            held.set_identity_row(d);
        }
        self.linear_factor = BandLdlt::new(&held);
        self.linear_h = h;
    }

    /// One HHT-alpha step from t0 to t1 = t0 + h (s); returns the Newton iterations.
    /// h comes from the exact step length, not t1 - t0: that difference changes in
    /// its last bits from step to step, which would re-form and refactorise the
    /// linear Newton matrix every step. The step's buffers live in `self.work`
    /// between steps, so a contact-free step allocates nothing.
    pub(super) fn hht_step(
        &mut self,
        inputs: Inputs<'_>,
        t0: f64,
        t1: f64,
        h: f64,
    ) -> Result<u32, UnitError> {
        let mut w = std::mem::take(&mut self.work);
        let result = self.hht_step_with(inputs, &mut w, t0, t1, h);
        self.work = w;
        result
    }

    fn hht_step_with(
        &mut self,
        inputs: Inputs<'_>,
        w: &mut StepWork,
        t0: f64,
        t1: f64,
        h: f64,
    ) -> Result<u32, UnitError> {
        let (alpha, beta, gamma) = self.hht();
        self.prepare_linear(h);
        let n = self.state.q.len();
        w.resize(n);
        w.q0.copy_from_slice(&self.state.q);
        w.v0.copy_from_slice(&self.state.v);
        w.a0.copy_from_slice(&self.state.a);
        let energy_conserving = matches!(
            self.params.contact.as_ref().map(|c| &c.method),
            Some(Law::EnergyConserving { .. })
        );
        // Constant part: alpha (C v0 + K q0 + Fc0) - ((1 - alpha) F1 + alpha F0).
        self.external_load(inputs, t0, h, &mut w.f0);
        self.external_load(inputs, t1, h, &mut w.f1);
        for i in 0..n {
            let fc0 = if energy_conserving {
                0.0
            } else {
                self.state.contact_force[i]
            };
            w.constant[i] = alpha * fc0 - (1.0 - alpha) * w.f1[i] - alpha * w.f0[i];
        }
        self.c.mul_add(alpha, &w.v0, &mut w.constant);
        self.k.mul_add(alpha, &w.q0, &mut w.constant);
        // Held DOFs at t1 (the state's time still t0 for input rates).
        self.state.t = t1;
        self.apply_kinematics(inputs, t1, h);
        w.held.clear();
        w.held.extend(
            self.conditions
                .iter()
                .filter(|c| c.quantity.is_kinematic())
                .map(|c| c.dof),
        );
        w.held_v.clear();
        w.held_a.clear();
        for &d in &w.held {
            w.held_v.push(self.state.v[d]);
            w.held_a.push(self.state.a[d]);
        }
        w.y.copy_from_slice(&w.q0);
        for &d in &w.held {
            w.y[d] = self.state.q[d];
        }
        w.history.clear();
        let cap = self.params.newton_max_iterations;
        let law = self.params.contact.as_ref().map(|c| c.method.clone());
        let linear_only = self.points.is_empty();
        let mut converged = None;
        for iteration in 1..=cap {
            w.kinematics(h, beta, gamma);
            // Without contact the Newton matrix is constant: factorised once per step
            // size, and one correction solves the linear step exactly.
            let mut fresh = false;
            w.values.force.clear();
            if !linear_only {
                self.jacobian.copy_from(&self.linear);
                let mut jac = std::mem::replace(
                    &mut self.jacobian,
                    crate::numerics::banded::SymmetricBand::zeros(0, 0),
                );
                if energy_conserving {
                    self.discrete_gradient(&w.y, t1, &mut jac, &mut w.values);
                } else {
                    let c_scale = (1.0 - alpha) * gamma / (beta * h);
                    let lambda = std::mem::take(&mut self.state.lambda);
                    self.contact_at(
                        &w.y,
                        &w.v1,
                        t1,
                        &lambda,
                        None,
                        Some((&mut jac, 1.0 - alpha, c_scale)),
                        &mut w.values,
                    );
                    self.state.lambda = lambda;
                    for f in w.values.force.iter_mut() {
                        *f *= 1.0 - alpha;
                    }
                }
                for &d in &w.held {
                    jac.set_identity_row(d);
                }
                fresh = match w.factor.as_mut() {
                    Some(f) => f.refactorise(&jac),
                    None => {
                        w.factor = BandLdlt::new(&jac);
                        w.factor.is_some()
                    }
                };
                self.jacobian = jac;
            }
            let r = &mut self.residual;
            r.copy_from_slice(&w.constant);
            for (ri, f) in r.iter_mut().zip(&w.values.force) {
                *ri += f;
            }
            self.m.mul_add(1.0, &w.a1, r);
            self.c.mul_add(1.0 - alpha, &w.v1, r);
            self.k.mul_add(1.0 - alpha, &w.y, r);
            for &d in &w.held {
                r[d] = 0.0;
            }
            let factor = if linear_only {
                self.linear_factor.as_ref()
            } else if fresh {
                w.factor.as_ref()
            } else {
                None
            };
            let factor = factor.ok_or_else(|| {
                UnitError::Numerical(format!("beam: the Newton matrix is not positive definite at t = {t1} s (iteration {iteration})"))
            })?;
            for v in self.residual.iter_mut() {
                *v = -*v;
            }
            factor.solve_in_place(&mut self.residual);
            let step = self.residual.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            w.history.push(step);
            for (yi, dy) in w.y.iter_mut().zip(&self.residual) {
                *yi += dy;
            }
            if let (Some(law), Some(crate::contact::LambdaUpdate::NewtonIteration)) =
                (&law, law.as_ref().and_then(Law::lambda_update))
            {
                self.state.q.copy_from_slice(&w.y);
                self.update_lambda(law, t1);
            }
            if !step.is_finite() {
                break;
            }
            // Relative to the solution's size: below ~1e-12 |y| only round-off moves.
            let size = w.y.iter().fold(1.0f64, |a, v| a.max(v.abs()));
            if linear_only || step < self.params.newton_tolerance * size {
                converged = Some(iteration);
                break;
            }
        }
        let Some(iterations) = converged else {
            self.state.t = t0;
            return Err(UnitError::Numerical(format!(
                "beam: Newton did not converge in the step ending at t = {t1} s; largest corrections per iteration: {}",
                w.history
                    .iter()
                    .map(|v| format!("{v:.3e}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            )));
        };
        w.kinematics(h, beta, gamma);
        self.state.q.copy_from_slice(&w.y);
        self.state.v.copy_from_slice(&w.v1);
        self.state.a.copy_from_slice(&w.a1);
        // Contact force at t1 (unweighted) for the next step and the reactions; for
        // the energy-conserving law the force the step used, 2 F_bar - X0.
        if !linear_only {
            let lambda = std::mem::take(&mut self.state.lambda);
            if energy_conserving {
                let mut scratch = self.jacobian.clone();
                self.discrete_gradient(&w.y, t1, &mut scratch, &mut w.values);
                let effective = w.values.force.clone();
                self.contact_at(&w.y, &w.v1, t1, &lambda, None, None, &mut w.values);
                w.values.force.copy_from_slice(&effective);
            } else {
                self.contact_at(&w.y, &w.v1, t1, &lambda, None, None, &mut w.values);
            }
            self.state.lambda = lambda;
        } else {
            w.values.force.clear();
            w.values.force.resize(n, 0.0);
        }
        self.state.contact_force.copy_from_slice(&w.values.force);
        let v = &w.values;
        self.state.contact = [v.energy, v.start, v.end, v.length, v.max_penetration];
        self.record_gaps(t1);
        self.residual_at(&w.f1, &w.values.force);
        if let (Some(law), Some(crate::contact::LambdaUpdate::TimeStep)) =
            (&law, law.as_ref().and_then(Law::lambda_update))
        {
            self.update_lambda(law, t1);
        }
        self.state.newton_iterations = iterations;
        Ok(iterations)
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
