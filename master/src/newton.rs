//! Newton's method on the interface residual `R(x) = G(x) - x`, with the Jacobian
//! `dG/dx - I` from finite differences: each column costs one extra sweep from the
//! rolled-back start of the step. For loops that fixed-point iteration cannot solve
//! (benchmark B6).

use crate::coupler::Master;
use crate::error::MasterError;
use crate::settings::{Acceleration, JacobianUpdate};
use nalgebra::{DMatrix, DVector, Dyn, linalg::LU};

/// Buffers of the Newton scheme, sized once for the torn values.
pub(crate) struct NewtonWork {
    jacobian: DMatrix<f64>,
    factorised: Option<LU<f64, Dyn, Dyn>>,
    correction: DVector<f64>,
    base_gx: Vec<f64>,
}

impl NewtonWork {
    pub(crate) fn new(n: usize) -> NewtonWork {
        NewtonWork {
            jacobian: DMatrix::zeros(n, n),
            factorised: None,
            correction: DVector::zeros(n),
            base_gx: vec![0.0; n],
        }
    }
}

impl Master {
    /// One synchronisation step solved by Newton on the torn values.
    pub(crate) fn step_newton(&mut self) -> Result<(u32, f64, bool), MasterError> {
        let Acceleration::Newton {
            perturbation,
            jacobian: update,
        } = self.settings.acceleration
        else {
            return Err(MasterError::Invalid(
                "step_newton without Newton settings".into(),
            ));
        };
        let mut work = self
            .newton
            .take()
            .ok_or_else(|| MasterError::Invalid("Newton buffers missing".into()))?;
        work.factorised = None;
        let result = self.newton_iterations(&mut work, perturbation, update);
        self.newton = Some(work);
        result
    }

    fn newton_iterations(
        &mut self,
        work: &mut NewtonWork,
        perturbation: f64,
        update: JacobianUpdate,
    ) -> Result<(u32, f64, bool), MasterError> {
        self.save_all()?;
        let max = self.settings.max_iterations;
        let mut k = 1;
        loop {
            if k > 1 {
                self.restore_all(k)?;
            }
            self.sweep(k)?;
            let residual = self.residual();
            if residual.scaled <= 1.0 {
                return Ok((k, residual.scaled, true));
            }
            if k == max {
                return self.give_up(k, residual);
            }
            work.base_gx.copy_from_slice(&self.gx);
            if work.factorised.is_none() || update == JacobianUpdate::EveryIteration {
                self.probe_jacobian(work, perturbation, k)?;
            }
            // Scaled residual r = (G(x) - x) / tol; solve J dz = -r.
            for (i, &c) in self.torn.iter().enumerate() {
                work.correction[i] = -(work.base_gx[i] - self.x[i]) / self.tolerance[c];
            }
            let lu = work
                .factorised
                .as_ref()
                .ok_or(MasterError::SingularJacobian {
                    time: self.target_time(),
                    iteration: k,
                })?;
            lu.solve_mut(&mut work.correction);
            for (i, &c) in self.torn.iter().enumerate() {
                self.x[i] += work.correction[i] * self.tolerance[c];
            }
            k += 1;
        }
    }

    /// Fills the scaled Jacobian of the residual, column by column, and factorises it.
    fn probe_jacobian(
        &mut self,
        work: &mut NewtonWork,
        perturbation: f64,
        iteration: u32,
    ) -> Result<(), MasterError> {
        for j in 0..self.torn.len() {
            let xj = self.x[j];
            let delta = perturbation * xj.abs().max(1.0);
            self.restore_all(iteration)?;
            self.x[j] = xj + delta;
            let probe = self.sweep(iteration);
            self.x[j] = xj;
            probe?;
            let tol_j = self.tolerance[self.torn[j]];
            for (i, &c) in self.torn.iter().enumerate() {
                let dg = (self.gx[i] - work.base_gx[i]) / self.tolerance[c];
                let identity = if i == j { 1.0 } else { 0.0 };
                work.jacobian[(i, j)] = dg / (delta / tol_j) - identity;
            }
        }
        self.counters.jacobian_evaluations += 1;
        let lu = work.jacobian.clone().lu();
        if !lu.is_invertible() {
            return Err(MasterError::SingularJacobian {
                time: self.target_time(),
                iteration,
            });
        }
        work.factorised = Some(lu);
        Ok(())
    }
}
