//! The body's step Jacobian: the derivative of its outputs after a step by
//! the inputs at the step's end, from the converged step itself (the
//! implicit function theorem on the trapezoidal rule's residual) rather than
//! by stepping again per input.
//!
//! The residual `R(u1, f) = u1 - u0 - h (a0 + a(u1, f)) / 2` vanishes at the
//! step's end velocity `u1`; the loads are linear in the inputs `f`, so
//! `da/df = M^-1 G` (`G`: the load at the reference point of a unit input) and
//! `du1/df = (dR/du1)^-1 (h / 2) M^-1 G`. The outputs are functions of `u1`
//! alone (the position, the rotation and, by the rule, the acceleration
//! `2 (u1 - u0) / h - a0` follow from it): `dy/df = dy/du1 du1/df`. `dR/du1`
//! and `dy/du1` are central differences in the six components of `u1`: 24
//! evaluations of the body's loads and outputs, where differencing whole steps
//! per input took some 600.

use super::Body;
use super::dynamics::skew;
use super::ports;
use super::step::{EndLoads, Kinematics, moved, residual};
use crate::contract::{UnitError, require_step_jacobian_ready};
use nalgebra::{DMatrix, Matrix6, Vector3, Vector6};

impl Body {
    /// The step Jacobian of the last step, from `start` at `t0` over `h` (s), into
    /// `jacobian` (outputs x inputs, row-major).
    pub(super) fn implicit_jacobian(
        &mut self,
        start: &Kinematics,
        (t0, h): (f64, f64),
        jacobian: &mut [f64],
    ) -> Result<(), UnitError> {
        let n_in = self.end_inputs.len();
        let end = self.kinematics();
        let inputs = std::mem::take(&mut self.end_inputs);
        let loads = self.end_loads(&inputs, t0 + h);
        let mut du = std::mem::take(&mut self.velocity_by_input);
        let result = self.velocity_sensitivity(start, &end, h, &loads, &mut du);
        self.end_inputs = inputs;
        if let Err(e) = result {
            self.velocity_by_input = du;
            return Err(e);
        }
        let mut dy = std::mem::take(&mut self.output_by_velocity);
        let rows = self.output_sensitivity(start, &end, h, &mut dy);
        for i in 0..rows {
            for j in 0..n_in {
                jacobian[i * n_in + j] = (0..6).map(|k| dy[(i, k)] * du[(k, j)]).sum();
            }
        }
        ports::clear_energy_rows(self, jacobian, n_in);
        (self.velocity_by_input, self.output_by_velocity) = (du, dy);
        self.sensitivity_ready = true;
        Ok(())
    }

    /// The last step with its end inputs moved by `change` (`Unit::correct_step`;
    /// `inputs`: the moved end values): the end velocity by `du1/df` times the
    /// change, the motion and acceleration from it as the step makes them
    /// (`step::residual`), the power's trapezoid in the work with the moved
    /// end's; a prescribed motion stays, its loads' power moves.
    pub(super) fn correct_last_step(
        &mut self,
        inputs: &[f64],
        change: &[f64],
    ) -> Result<(), UnitError> {
        let Some((start, t0, h)) = self.last_start else {
            return require_step_jacobian_ready(false, "a body");
        };
        let loads = self.end_loads(inputs, t0 + h);
        let end = if self.is_prescribed() {
            self.kinematics()
        } else {
            if !self.sensitivity_ready {
                return require_step_jacobian_ready(
                    false,
                    "a body whose step Jacobian was not taken",
                );
            }
            let du = &self.velocity_by_input;
            let mut u1 = self.kinematics().motion.velocity;
            for (j, dj) in change.iter().enumerate() {
                for k in 0..6 {
                    u1[k] += du[(k, j)] * dj;
                }
            }
            residual(&self.model, &start, &u1, h, &loads)?.1
        };
        crate::contract::require_finite_state("the body's motion", end.acceleration.as_slice())?;
        let power = self.power(&end, &loads);
        self.state.work += 0.5 * h * (power - self.state.power);
        self.state.power = power;
        self.set_kinematics(&end);
        self.sensitivity_ready = false;
        self.end_inputs.clear();
        self.end_inputs.extend_from_slice(inputs);
        Ok(())
    }

    /// `du1/df` (6 x inputs) at the converged `end` into `du`.
    fn velocity_sensitivity(
        &self,
        start: &Kinematics,
        end: &Kinematics,
        h: f64,
        loads: &EndLoads<'_>,
        du: &mut DMatrix<f64>,
    ) -> Result<(), UnitError> {
        let u1 = end.motion.velocity;
        let mut d_residual = Matrix6::zeros();
        for k in 0..6 {
            let delta = 1e-6 * (1.0 + u1[k].abs());
            let (mut plus, mut minus) = (u1, u1);
            plus[k] += delta;
            minus[k] -= delta;
            let rp = residual(&self.model, start, &plus, h, loads)?.0;
            let rm = residual(&self.model, start, &minus, h, loads)?.0;
            d_residual.set_column(k, &((rp - rm) / (2.0 * delta)));
        }
        let solve = |m: &Matrix6<f64>, what: &str| {
            m.lu().try_inverse().ok_or_else(|| {
                UnitError::Numerical(format!("the body's step Jacobian: a singular {what}"))
            })
        };
        let mass = solve(&self.model.mass_matrix(&end.motion.rotation), "mass matrix")?;
        let map = solve(&d_residual, "Newton matrix")? * mass * (0.5 * h);
        let fairleads = self.model.fairleads.len();
        for j in 0..du.ncols() {
            let mut g = Vector6::zeros();
            if j < 3 * fairleads {
                let arm = end.motion.rotation * self.model.fairleads[j / 3];
                let mut unit = Vector3::zeros();
                unit[j % 3] = 1.0;
                g.fixed_rows_mut::<3>(0).copy_from(&unit);
                g.fixed_rows_mut::<3>(3).copy_from(&(skew(&arm) * unit));
            } else {
                g[j - 3 * fairleads] = 1.0;
            }
            du.set_column(j, &(map * g));
        }
        Ok(())
    }

    /// `dy/du1` into `dy` for the motion outputs (pose, velocity,
    /// fairleads: the first rows, whose count it returns) as functions of
    /// the end velocity alone; the energy rows are left out (unknown).
    fn output_sensitivity(
        &mut self,
        start: &Kinematics,
        end: &Kinematics,
        h: f64,
        dy: &mut DMatrix<f64>,
    ) -> usize {
        let mut rows = 0;
        let (mut plus, mut minus) = (
            std::mem::take(&mut self.plus),
            std::mem::take(&mut self.minus),
        );
        let u1 = end.motion.velocity;
        let at = |u: Vector6<f64>| Kinematics {
            motion: moved(&start.motion, &u, h),
            acceleration: (u - start.motion.velocity) * (2.0 / h) - start.acceleration,
        };
        for k in 0..6 {
            let delta = 1e-5 * (1.0 + u1[k].abs());
            let (mut up, mut down) = (u1, u1);
            up[k] += delta;
            down[k] -= delta;
            rows = ports::write_motion(self, &at(up), &mut plus);
            ports::write_motion(self, &at(down), &mut minus);
            for i in 0..rows {
                dy[(i, k)] = (plus[i] - minus[i]) / (2.0 * delta);
            }
        }
        (self.plus, self.minus) = (plus, minus);
        rows
    }
}
