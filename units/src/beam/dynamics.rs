//! Time integration of the beam: HHT-alpha (alpha in [0, 1/3], beta = (1+alpha)^2/4,
//! gamma = 1/2 + alpha; seed 004 eqs. 4.29-4.37) with Newton iterations on the
//! contact terms, the consistent initial acceleration, and modal analysis.

use super::{Beam, ContactValues};
use crate::contact::Law;
use crate::numerics::banded::BandLdlt;
use crate::unit::{ModalAnalysis, Mode, UnitError};

impl Beam {
    /// Newmark parameters of the HHT-alpha scheme.
    fn hht(&self) -> (f64, f64, f64) {
        let alpha = self.params.alpha;
        (alpha, 0.25 * (1.0 + alpha).powi(2), 0.5 + alpha)
    }

    /// M a0 = F - C v0 - K q0 - F_contact at the initial time, with the held DOFs'
    /// accelerations prescribed.
    pub(super) fn initial_acceleration(&mut self) -> Result<(), UnitError> {
        let t = self.state.t;
        self.apply_kinematics(t, 0.0);
        let n = self.state.q.len();
        let mut values = ContactValues::default();
        let (q, v, lambda) = (
            self.state.q.clone(),
            self.state.v.clone(),
            self.state.lambda.clone(),
        );
        self.contact_at(&q, &v, t, &lambda, None, None, &mut values);
        let mut load = vec![0.0; n];
        self.external_load(t, 0.0, &mut load);
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
        self.residual_at(t, &load, &values.force);
        Ok(())
    }

    /// Reactions: M a + C v + K q + F_contact - F at the current state.
    fn residual_at(&mut self, _t: f64, load: &[f64], contact: &[f64]) {
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

    /// One HHT-alpha step from t0 to t1 (s); returns the Newton iterations.
    pub(super) fn hht_step(&mut self, t0: f64, t1: f64) -> Result<u32, UnitError> {
        let h = t1 - t0;
        let (alpha, beta, gamma) = self.hht();
        self.prepare_linear(h);
        let n = self.state.q.len();
        let (q0, v0, a0) = (
            self.state.q.clone(),
            self.state.v.clone(),
            self.state.a.clone(),
        );
        let energy_conserving = matches!(
            self.params.contact.as_ref().map(|c| &c.method),
            Some(Law::EnergyConserving { .. })
        );
        // Constant part: alpha (C v0 + K q0 + Fc0) - ((1 - alpha) F1 + alpha F0).
        let mut f0 = vec![0.0; n];
        self.external_load(t0, h, &mut f0);
        let mut f1 = vec![0.0; n];
        self.external_load(t1, h, &mut f1);
        let mut constant = vec![0.0; n];
        for i in 0..n {
            let fc0 = if energy_conserving {
                0.0
            } else {
                self.state.contact_force[i]
            };
            constant[i] = alpha * fc0 - (1.0 - alpha) * f1[i] - alpha * f0[i];
        }
        self.c.mul_add(alpha, &v0, &mut constant);
        self.k.mul_add(alpha, &q0, &mut constant);
        // Held DOFs at t1 (the state's time still t0 for input rates).
        self.state.t = t1;
        self.apply_kinematics(t1, h);
        let held: Vec<usize> = self.held_dofs().collect();
        let (held_v, held_a): (Vec<f64>, Vec<f64>) = held
            .iter()
            .map(|&d| (self.state.v[d], self.state.a[d]))
            .unzip();
        let mut y = q0.clone();
        for &d in &held {
            y[d] = self.state.q[d];
        }
        let mut v1 = vec![0.0; n];
        let mut a1 = vec![0.0; n];
        let kinematics = |y: &[f64], v1: &mut [f64], a1: &mut [f64]| {
            for i in 0..n {
                a1[i] = (y[i] - q0[i] - h * v0[i]) / (beta * h * h) - (0.5 / beta - 1.0) * a0[i];
                v1[i] = v0[i] + h * ((1.0 - gamma) * a0[i] + gamma * a1[i]);
            }
            for (k, &d) in held.iter().enumerate() {
                v1[d] = held_v[k];
                a1[d] = held_a[k];
            }
        };
        let mut values = ContactValues::default();
        let mut history = Vec::new();
        let cap = self.params.newton_max_iterations;
        let law = self.params.contact.as_ref().map(|c| c.method.clone());
        let mut converged = None;
        for iteration in 1..=cap {
            kinematics(&y, &mut v1, &mut a1);
            // Without contact the Newton matrix is constant: factorised once per step
            // size, and one correction solves the linear step exactly.
            let linear_only = self.points.is_empty();
            let mut fresh = None;
            if !linear_only {
                self.jacobian.copy_from(&self.linear);
                let lambda = self.state.lambda.clone();
                let mut jac = std::mem::replace(
                    &mut self.jacobian,
                    crate::numerics::banded::SymmetricBand::zeros(0, 0),
                );
                if energy_conserving {
                    self.discrete_gradient(&y, t1, &mut jac, &mut values);
                } else {
                    let c_scale = (1.0 - alpha) * gamma / (beta * h);
                    self.contact_at(
                        &y,
                        &v1,
                        t1,
                        &lambda,
                        None,
                        Some((&mut jac, 1.0 - alpha, c_scale)),
                        &mut values,
                    );
                    for f in values.force.iter_mut() {
                        *f *= 1.0 - alpha;
                    }
                }
                for &d in &held {
                    jac.set_identity_row(d);
                }
                fresh = BandLdlt::new(&jac);
                self.jacobian = jac;
            }
            let r = &mut self.residual;
            r.copy_from_slice(&constant);
            for (ri, f) in r.iter_mut().zip(&values.force) {
                *ri += f;
            }
            self.m.mul_add(1.0, &a1, r);
            self.c.mul_add(1.0 - alpha, &v1, r);
            self.k.mul_add(1.0 - alpha, &y, r);
            for &d in &held {
                r[d] = 0.0;
            }
            let factor = if linear_only {
                self.linear_factor.as_ref()
            } else {
                fresh.as_ref()
            };
            let factor = factor.ok_or_else(|| {
                UnitError::Numerical(format!("beam: the Newton matrix is not positive definite at t = {t1} s (iteration {iteration})"))
            })?;
            for v in self.residual.iter_mut() {
                *v = -*v;
            }
            factor.solve_in_place(&mut self.residual);
            let step = self.residual.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            history.push(step);
            for (yi, dy) in y.iter_mut().zip(&self.residual) {
                *yi += dy;
            }
            if let (Some(law), Some(crate::contact::LambdaUpdate::NewtonIteration)) =
                (&law, law.as_ref().and_then(Law::lambda_update))
            {
                self.state.q.copy_from_slice(&y);
                self.update_lambda(law, t1);
            }
            if !step.is_finite() {
                break;
            }
            // Relative to the solution's size: below ~1e-12 |y| only round-off moves.
            let size = y.iter().fold(1.0f64, |a, v| a.max(v.abs()));
            if linear_only || step < self.params.newton_tolerance * size {
                converged = Some(iteration);
                break;
            }
        }
        let Some(iterations) = converged else {
            self.state.t = t0;
            return Err(UnitError::Numerical(format!(
                "beam: Newton did not converge in the step ending at t = {t1} s; largest corrections per iteration: {}",
                history
                    .iter()
                    .map(|v| format!("{v:.3e}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            )));
        };
        kinematics(&y, &mut v1, &mut a1);
        self.state.q.copy_from_slice(&y);
        self.state.v.copy_from_slice(&v1);
        self.state.a.copy_from_slice(&a1);
        // Contact force at t1 (unweighted) for the next step and the reactions; for
        // the energy-conserving law the force the step used, 2 F_bar - X0.
        if energy_conserving {
            let mut scratch = self.jacobian.clone();
            self.discrete_gradient(&y, t1, &mut scratch, &mut values);
            let effective = values.force.clone();
            let lambda = self.state.lambda.clone();
            self.contact_at(&y, &v1, t1, &lambda, None, None, &mut values);
            values.force.copy_from_slice(&effective);
        } else {
            let lambda = self.state.lambda.clone();
            self.contact_at(&y, &v1, t1, &lambda, None, None, &mut values);
        }
        self.state.contact_force.copy_from_slice(&values.force);
        self.state.contact = [
            values.energy,
            values.start,
            values.end,
            values.length,
            values.max_penetration,
        ];
        self.record_gaps(t1);
        self.residual_at(t1, &f1, &values.force.clone());
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
