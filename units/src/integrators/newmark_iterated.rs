//! Newmark average acceleration in total form on banded systems, for any
//! [`SecondOrderSystem`] whose nonlinear force depends on the velocity only weakly
//! (a drag remainder): the effective stiffness `K + 2/h C + 4/h^2 M` is factorised
//! once per step size and the nonlinear force is iterated on that factorisation
//! (modified Newton) until the end velocity changes less than a tolerance.
//!
//! This is the cable's scheme (seed 000: linear dynamics about the static state
//! with the exact drag). Unlike [`HhtAlpha`](super::hht::HhtAlpha) it solves for the
//! displacement itself, not for a correction, and needs no tangent: a system whose
//! nonlinear force is stiff belongs with HHT-alpha and Newton. A step allocates
//! nothing once its buffers are sized.

use super::hht::{Matrices, SecondOrderSystem};
use crate::contract::UnitError;
use crate::numerics::banded::{BandLdlt, SymmetricBand};

/// The stopping rule of the iterations on the nonlinear force.
#[derive(Copy, Clone, Debug)]
pub struct LoadIteration {
    /// Largest change of any velocity between two iterations (its SI unit).
    pub tolerance: f64,
    /// Most iterations a step may take before it fails.
    pub max_iterations: u32,
}

/// The integrator: the factorised effective stiffness and the step's buffers.
pub struct IteratedNewmark {
    h: f64,
    effective: SymmetricBand,
    factor: Option<BandLdlt>,
    rhs: Vec<f64>,
    load: Vec<f64>,
    force: Vec<f64>,
    q_new: Vec<f64>,
    v_iter: Vec<f64>,
    a_new: Vec<f64>,
}

impl Default for IteratedNewmark {
    /// An empty integrator (no DOFs), e.g. as a placeholder while stepping.
    fn default() -> Self {
        IteratedNewmark::new(0, 0)
    }
}

impl IteratedNewmark {
    /// For `n` DOFs whose matrices have half-bandwidth `w`.
    pub fn new(n: usize, w: usize) -> IteratedNewmark {
        IteratedNewmark {
            h: f64::NAN,
            effective: SymmetricBand::zeros(n, w),
            factor: None,
            rhs: vec![0.0; n],
            load: vec![0.0; n],
            force: Vec::new(),
            q_new: vec![0.0; n],
            v_iter: vec![0.0; n],
            a_new: vec![0.0; n],
        }
    }

    /// The factorised effective stiffness of the last step size.
    pub fn factor(&self) -> Option<&BandLdlt> {
        self.factor.as_ref()
    }

    /// Forms and factorises `K + 2/h C + 4/h^2 M` when `h` (s) changed.
    fn prepare(&mut self, m: &Matrices<'_>, h: f64) -> Result<(), UnitError> {
        if self.factor.is_some() && self.h == h {
            return Ok(());
        }
        self.effective.set_present_combination(&[
            (1.0, m.stiffness),
            (2.0 / h, m.damping),
            (4.0 / (h * h), Some(m.mass)),
        ]);
        self.factor = Some(BandLdlt::new(&self.effective).ok_or_else(|| {
            UnitError::Numerical(format!(
                "the effective stiffness for h = {h} s is not positive definite"
            ))
        })?);
        self.h = h;
        Ok(())
    }

    /// One step of `h` seconds ending at `t1`: `end_load` adds the external load at
    /// the step's end to the right-hand side. Returns the iterations; on failure the
    /// system keeps its start state.
    pub fn step<S: SecondOrderSystem + ?Sized>(
        &mut self,
        system: &mut S,
        t1: f64,
        h: f64,
        end_load: impl FnOnce(&mut [f64]),
        iteration: LoadIteration,
    ) -> Result<u32, UnitError> {
        self.prepare(&system.matrices(), h)?;
        self.constant_part(system, h);
        end_load(&mut self.rhs);
        let [_, v, a] = system.motion();
        // Predict the end velocity from the start acceleration.
        for i in 0..v.len() {
            self.v_iter[i] = v[i] + h * a[i];
        }
        let linear = system.is_linear();
        let mut iterations = 0;
        loop {
            iterations += 1;
            self.load.copy_from_slice(&self.rhs);
            if !linear {
                let (q_new, v_iter) = (&self.q_new, &self.v_iter);
                system.nonlinear_force(q_new, v_iter, t1, None, &mut self.force);
                for (l, g) in self.load.iter_mut().zip(&self.force) {
                    *l -= g;
                }
            }
            let change = self.solve_and_update(system, h)?;
            if !change.is_finite() {
                return Err(UnitError::Numerical(format!(
                    "{}: the velocity became {change} in a step of {h} s",
                    system.label()
                )));
            }
            if linear || change <= iteration.tolerance {
                break;
            }
            if iterations == iteration.max_iterations {
                return Err(UnitError::Numerical(format!(
                    "{}: the iterations on the velocity-dependent force did not converge in {} iterations (last velocity change {change:.3e} m/s, step {h} s)",
                    system.label(),
                    iteration.max_iterations
                )));
            }
        }
        system.set_motion(&self.q_new, &self.v_iter, &self.a_new);
        Ok(iterations)
    }

    /// rhs = M (4/h^2 q + 4/h v + a) + C (2/h q + v).
    fn constant_part<S: SecondOrderSystem + ?Sized>(&mut self, system: &S, h: f64) {
        let m = system.matrices();
        let [q, v, a] = system.motion();
        self.rhs.fill(0.0);
        for i in 0..q.len() {
            self.a_new[i] = 4.0 / (h * h) * q[i] + 4.0 / h * v[i] + a[i];
        }
        m.mass.mul_add(1.0, &self.a_new, &mut self.rhs);
        if let Some(c) = m.damping {
            for i in 0..q.len() {
                self.a_new[i] = 2.0 / h * q[i] + v[i];
            }
            c.mul_add(1.0, &self.a_new, &mut self.rhs);
        }
    }

    /// Solves for the end displacement and updates the end velocity and
    /// acceleration by Newmark; returns the largest change of the velocity.
    fn solve_and_update<S: SecondOrderSystem + ?Sized>(
        &mut self,
        system: &S,
        h: f64,
    ) -> Result<f64, UnitError> {
        let factor = self.factor.as_ref().ok_or_else(|| {
            UnitError::Numerical("the effective stiffness was not factorised".into())
        })?;
        self.q_new.copy_from_slice(&self.load);
        factor.solve_in_place(&mut self.q_new);
        let [q, v, a] = system.motion();
        let mut change: f64 = 0.0;
        for i in 0..q.len() {
            let a_new = 4.0 / (h * h) * (self.q_new[i] - q[i]) - 4.0 / h * v[i] - a[i];
            let v_new = v[i] + 0.5 * h * (a[i] + a_new);
            change = change.max((v_new - self.v_iter[i]).abs());
            self.v_iter[i] = v_new;
            self.a_new[i] = a_new;
        }
        Ok(change)
    }
}
