//! Newmark average-acceleration (trapezoidal) integration of a linear system
//! `M a + C v + K u = f(t)`.
//!
//! Second order, unconditionally stable, and energy-conserving for undamped linear
//! systems, which makes it the reference integrator of the coupling benchmarks: a
//! converged iterative co-simulation of two units using it reproduces the
//! monolithic solution of the same integrator.

use crate::contract::{StateVector, UnitError};
use nalgebra::{DMatrix, DVector, Dyn, linalg::LU};

crate::state_struct! {
    /// Displacement, velocity and acceleration of a linear system.
    #[derive(Debug, PartialEq, serde::Serialize, serde::Deserialize)]
    pub struct NewmarkState {
        /// Displacements (each DOF's SI unit).
        pub u: StateVector,
        /// Velocities.
        pub v: StateVector,
        /// Accelerations.
        pub a: StateVector,
    }
}

/// The integrator: constant matrices, the effective stiffness factorised once per
/// step size, and scratch vectors so that a step allocates nothing.
pub struct LinearNewmark {
    m: DMatrix<f64>,
    c: DMatrix<f64>,
    k: DMatrix<f64>,
    h: f64,
    effective: LU<f64, Dyn, Dyn>,
    rhs: DVector<f64>,
    scratch: DVector<f64>,
}

impl LinearNewmark {
    /// Builds the integrator for step `h` (s).
    pub fn new(
        m: DMatrix<f64>,
        c: DMatrix<f64>,
        k: DMatrix<f64>,
        h: f64,
    ) -> Result<LinearNewmark, UnitError> {
        let n = m.nrows();
        let effective = Self::factorise(&m, &c, &k, h)?;
        Ok(LinearNewmark {
            m,
            c,
            k,
            h,
            effective,
            rhs: DVector::zeros(n),
            scratch: DVector::zeros(n),
        })
    }

    fn factorise(
        m: &DMatrix<f64>,
        c: &DMatrix<f64>,
        k: &DMatrix<f64>,
        h: f64,
    ) -> Result<LU<f64, Dyn, Dyn>, UnitError> {
        if !(h.is_finite() && h > 0.0) {
            return Err(UnitError::Numerical(format!(
                "Newmark step h = {h} s must be > 0"
            )));
        }
        let effective = k + c * (2.0 / h) + m * (4.0 / (h * h));
        let lu = effective.lu();
        if lu.is_invertible() {
            Ok(lu)
        } else {
            Err(UnitError::Numerical(
                "Newmark effective stiffness is singular".into(),
            ))
        }
    }

    /// The step size (s).
    pub fn step_size(&self) -> f64 {
        self.h
    }

    /// Changes the step size, refactorising only when it differs.
    pub fn set_step_size(&mut self, h: f64) -> Result<(), UnitError> {
        if h != self.h {
            self.effective = Self::factorise(&self.m, &self.c, &self.k, h)?;
            self.h = h;
        }
        Ok(())
    }

    /// The state at rest-or-moving initial conditions `u`, `v` under load `f`, with the
    /// acceleration that satisfies the equation of motion.
    pub fn initial_state(
        &self,
        u: DVector<f64>,
        v: DVector<f64>,
        f: &DVector<f64>,
    ) -> Result<NewmarkState, UnitError> {
        let rhs = f - &self.c * &v - &self.k * &u;
        let a = self
            .m
            .clone()
            .lu()
            .solve(&rhs)
            .ok_or_else(|| UnitError::Numerical("mass matrix is singular".into()))?;
        Ok(NewmarkState {
            u: StateVector(u),
            v: StateVector(v),
            a: StateVector(a),
        })
    }

    /// Advances `state` by one step of size `step_size()` with load `f_next` at the
    /// step's end.
    pub fn step(&mut self, state: &mut NewmarkState, f_next: &DVector<f64>) {
        let h = self.h;
        // rhs = f + M (4/h^2 u + 4/h v + a) + C (2/h u + v)
        self.rhs.copy_from(f_next);
        self.scratch.copy_from(&state.a);
        self.scratch.axpy(4.0 / (h * h), &state.u, 1.0);
        self.scratch.axpy(4.0 / h, &state.v, 1.0);
        self.rhs.gemv(1.0, &self.m, &self.scratch, 1.0);
        self.scratch.copy_from(&state.v);
        self.scratch.axpy(2.0 / h, &state.u, 1.0);
        self.rhs.gemv(1.0, &self.c, &self.scratch, 1.0);
        self.effective.solve_mut(&mut self.rhs);
        // rhs now holds u_{n+1}. a_{n+1} = 4/h^2 (u_{n+1} - u_n) - 4/h v_n - a_n.
        self.scratch.copy_from(&self.rhs);
        self.scratch.axpy(-1.0, &state.u, 1.0);
        self.scratch *= 4.0 / (h * h);
        self.scratch.axpy(-4.0 / h, &state.v, 1.0);
        self.scratch.axpy(-1.0, &state.a, 1.0);
        // v_{n+1} = v_n + h/2 (a_n + a_{n+1})
        state.v.axpy(h / 2.0, &state.a, 1.0);
        state.v.axpy(h / 2.0, &self.scratch, 1.0);
        state.a.copy_from(&self.scratch);
        state.u.copy_from(&self.rhs);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn free_oscillation_is_second_order_accurate_and_conserves_energy() {
        let omega = 2.0 * std::f64::consts::PI;
        let run = |h: f64| {
            let mut nm = LinearNewmark::new(
                DMatrix::from_element(1, 1, 1.0),
                DMatrix::zeros(1, 1),
                DMatrix::from_element(1, 1, omega * omega),
                h,
            )
            .unwrap();
            let f = DVector::zeros(1);
            let mut s = nm
                .initial_state(DVector::from_element(1, 1.0), DVector::zeros(1), &f)
                .unwrap();
            // At t = 0.3 s the phase error shows at first order in the displacement.
            let t_end = 0.3;
            let steps = (t_end / h).round() as usize;
            for _ in 0..steps {
                nm.step(&mut s, &f);
            }
            let energy = 0.5 * s.v[0] * s.v[0] + 0.5 * omega * omega * s.u[0] * s.u[0];
            (s.u[0] - (omega * t_end).cos(), energy)
        };
        let (e1, energy) = run(0.01);
        let (e2, _) = run(0.005);
        let order = (e1 / e2).abs().log2();
        assert!((order - 2.0).abs() < 0.05, "order {order}");
        assert_relative_eq!(energy, 0.5 * omega * omega, max_relative = 1e-12);
    }
}
