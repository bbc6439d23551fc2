//! Newton's method on the interface residual `R(x) = G(x) - x`, with the Jacobian
//! `dG/dx - I` from finite differences: each column costs one extra sweep from the
//! rolled-back start of the step. For loops that fixed-point iteration cannot solve
//! (benchmark B6).

use crate::coupler::Master;
use crate::error::MasterError;
use crate::settings::{JacobianUpdate, NewtonSettings};
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
        let Some(NewtonSettings {
            perturbation,
            jacobian: update,
        }) = self.settings.newton
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
        self.iterate(&mut |m, k| {
            work.base_gx.copy_from_slice(&m.gx);
            if work.factorised.is_none() || update == JacobianUpdate::EveryIteration {
                m.probe_jacobian(work, perturbation, k)?;
            }
            // Scaled residual r = (G(x) - x) / tol; solve J dz = -r.
            for (i, &c) in m.torn.iter().enumerate() {
                work.correction[i] = -(work.base_gx[i] - m.x[i]) / m.tolerance[c];
            }
            let lu = work
                .factorised
                .as_ref()
                .ok_or(MasterError::SingularJacobian {
                    time: m.target_time(),
                    iteration: k,
                })?;
            lu.solve_mut(&mut work.correction);
            for (i, &c) in m.torn.iter().enumerate() {
                m.x[i] += work.correction[i] * m.tolerance[c];
            }
            Ok(())
        })
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
