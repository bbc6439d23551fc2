//! The 3D line's interface Jacobian over its last step (`Unit::step_jacobian`):
//! the derivative of its end outputs (positions, velocities, forces) with
//! respect to its coupled end inputs (velocities or forces), by one
//! back-substitution per input with the step's factorised HHT-alpha Newton
//! matrix (`integrators::hht_sensitivity`); no new factorisation. The other
//! outputs are NaN: a master that needs one takes it by finite differences.
//!
//! Offered after a coupling step taken as one internal step (not cut by
//! `max_step`, not halved). Exact where the Newton matrix is (bars, bending,
//! the seabed's spring, mass); drag, the seabed's damper and the axial damper
//! enter through their velocity tangent only (their position derivatives are
//! left out of Newton's matrix too: 1e-4 of the derivative with drag in a
//! current in the tests). Sliding friction enters by its true velocity
//! tangent, not the secant Newton iterates with: where the line slides, a copy
//! of the step's matrix takes it and is factorised once more (without it the
//! 3D riser took 3 coupling sweeps a step, with it 2). Friction's position
//! derivatives (through the normal force and the line's direction) are left
//! out: a vertical motion's effect on friction is missing, and 6e-2 of the
//! force's scale remains on a pipe sliding at 50 stick velocities.

use super::Line3d;
use super::mechanics::{BAND, DOF, add_block};
use super::params::EndCondition;
use crate::contract::{Hold, Inputs, UnitError, require_step_jacobian_ready};
use crate::integrators::hht_sensitivity::{Change, Drive, StepSensitivity};
use crate::integrators::warm_start::WarmStart;
use crate::numerics::banded::{BandLdlt, SymmetricBand};

/// Buffers of the Jacobian, kept between calls.
#[derive(Default)]
pub(super) struct JacobianWork {
    /// The last coupling step was one internal step and nothing was restored
    /// since.
    pub ready: bool,
    /// The last step's length (s).
    pub h: f64,
    /// The velocity tangent of the line's forces at the step's end.
    damping: Option<SymmetricBand>,
    force: Vec<f64>,
    held: Vec<usize>,
    change: Change,
    /// The Newton matrix with friction's true tangent in place of Newton's
    /// secant, and its factor (buffers kept between calls), and whether the
    /// last Jacobian used them (the line slid).
    corrected: Option<Corrected>,
    sliding: bool,
    /// The last whole step and its derivatives: the warm start of a
    /// repeated step.
    pub warm: WarmStart,
    /// A linear line's Jacobian (without drag), the same at every step of one length with
    /// the same ends held: (step length (s), released ends, the rows).
    linear: Option<(f64, [bool; 2], Vec<f64>)>,
}

/// The Newton matrix with friction's true tangent: with its held rows (for
/// the reactions), with them as identity rows, and the latter's factor.
struct Corrected {
    newton: SymmetricBand,
    held: SymmetricBand,
    factor: BandLdlt,
}

impl Line3d {
    /// Fills `jacobian` (outputs x inputs, row-major): the end outputs' rows,
    /// the others NaN.
    pub(super) fn interface_jacobian(
        &mut self,
        inputs: Inputs<'_>,
        jacobian: &mut [f64],
    ) -> Result<(), UnitError> {
        require_step_jacobian_ready(
            self.jacobian.ready,
            "a 3D line after a step taken in internal steps, after a rollback, or before any step",
        )?;
        let mut w = std::mem::take(&mut self.jacobian);
        let key = (w.h, self.state.released);
        if let Some((h, released, rows)) = &w.linear
            && self.linear.as_ref().is_some_and(|l| !l.has_drag)
            && (*h, *released) == key
            && rows.len() == jacobian.len()
        {
            // Its matrices and the columns the warm start holds are unchanged.
            jacobian.copy_from_slice(rows);
            w.warm.columns_done(true);
            self.jacobian = w;
            return Ok(());
        }
        self.velocity_tangent(&mut w);
        w.held = self.held_dofs();
        if let Err(e) = self.correct_friction(&mut w) {
            self.jacobian = w;
            return Err(e);
        }
        let n_in = inputs.len();
        jacobian.fill(f64::NAN);
        w.warm.begin_columns(n_in, self.state.q.len());
        let mut result = Ok(());
        for j in 0..n_in {
            if let Err(e) = self.input_column(&inputs, &mut w, j, jacobian) {
                result = Err(e);
                break;
            }
            w.warm.set_column(j, &w.change.dq);
        }
        w.warm.columns_done(result.is_ok());
        if result.is_ok() && self.linear.as_ref().is_some_and(|l| !l.has_drag) {
            w.linear = Some((key.0, key.1, jacobian.to_vec()));
        }
        self.jacobian = w;
        result
    }

    /// The velocity tangent of the line's forces at the current state.
    fn velocity_tangent(&self, w: &mut JacobianWork) {
        let n = self.state.q.len();
        let mut band = w
            .damping
            .take()
            .unwrap_or_else(|| SymmetricBand::zeros(n, BAND));
        band.fill_zero();
        if let Some(l) = &self.linear {
            band.copy_from(&l.step_damping);
            w.damping = Some(band);
            return;
        }
        w.force.clear();
        w.force.resize(n, 0.0);
        let s = &self.state;
        let tangent = Some((&mut band, 0.0, 1.0));
        self.mechanics
            .add_force(&s.q, &s.v, 1.0, tangent, &mut w.force);
        let tangent = Some((&mut band, 0.0, 1.0));
        self.environment
            .add_force(&s.q, &s.v, s.t, 1.0, tangent, &mut w.force);
        w.damping = Some(band);
    }

    /// Where the line slides on the seabed, Newton took friction's secant
    /// (force over speed) for its tangent, so the step's sensitivity through
    /// its matrix is the iteration's, not the derivative: puts the true
    /// tangent of mu N tanh(v / v_stick) in the damping and in a copy of the
    /// Newton matrix, factorised once (`w.corrected`, `w.sliding`).
    fn correct_friction(&self, w: &mut JacobianWork) -> Result<(), UnitError> {
        let s = &self.state;
        let (alpha, beta, gamma) = self.hht.parameters();
        let scale = (1.0 - alpha) * gamma / (beta * w.h);
        w.sliding = false;
        if self.linear.is_some() {
            // The linear line's friction is its damping at rest: exact.
            return Ok(());
        }
        for i in 0..self.mechanics.nodes {
            let Some(m) = self.environment.friction_correction(&s.q, &s.v, s.t, i) else {
                continue;
            };
            let (newton, factor) = self.hht.last_newton_of("line3d")?;
            let c = w.corrected.get_or_insert_with(|| Corrected {
                newton: newton.clone(),
                held: newton.clone(),
                factor: factor.clone(),
            });
            if !w.sliding {
                c.newton.copy_from(newton);
                w.sliding = true;
            }
            add_block(&mut c.newton, i, i, &m, scale);
            if let Some(damping) = w.damping.as_mut() {
                add_block(damping, i, i, &m, 1.0);
            }
        }
        let Some(c) = w.corrected.as_mut().filter(|_| w.sliding) else {
            return Ok(());
        };
        c.held.copy_from(&c.newton);
        for &d in &w.held {
            c.held.set_identity_row(d);
        }
        if c.factor.refactorise(&c.held) {
            Ok(())
        } else {
            Err(UnitError::Numerical(
                "line3d: the step's matrix with friction's tangent is singular".into(),
            ))
        }
    }

    /// The end (0 start, 1 end), its node and its condition, for input `j`.
    fn input_end(&self, j: usize) -> Option<(usize, usize, EndCondition)> {
        let last = self.mechanics.nodes - 1;
        (0..2).find_map(|k| {
            let first = self.first_input[k]?;
            let end = if k == 0 {
                &self.params.start
            } else {
                &self.params.end
            };
            (first..first + DOF).contains(&j).then_some((
                k,
                if k == 0 { 0 } else { last },
                end.condition,
            ))
        })
    }

    /// Column `j` of the end outputs' rows.
    fn input_column(
        &self,
        inputs: &Inputs<'_>,
        w: &mut JacobianWork,
        j: usize,
        jacobian: &mut [f64],
    ) -> Result<(), UnitError> {
        let n_in = inputs.len();
        let (newton, factor) = match (&w.corrected, w.sliding) {
            (Some(c), true) => (&c.newton, &c.factor),
            _ => self.hht.last_newton_of("line3d")?,
        };
        let damping = w.damping.as_ref();
        let damping_at = |i: usize, k: usize| damping.map_or(0.0, |c| c.get(i, k));
        let h = w.h;
        let sensitivity = StepSensitivity {
            newton,
            factor,
            mass: &self.mass,
            damping: &damping_at,
            parameters: self.hht.parameters(),
            h,
        };
        let (alpha, beta, gamma) = self.hht.parameters();
        let ramp = inputs.hold(j) == Hold::Ramp;
        // An input that moves nothing has a zero column (the warm start and the
        // step's correction read it).
        w.change.clear(self.state.q.len());
        let Some((end, node, condition)) = self.input_end(j) else {
            return Ok(());
        };
        if self.state.released[end] {
            // A released end's velocity inputs move nothing any more.
            for i in 0..18 {
                jacobian[i * n_in + j] = 0.0;
            }
            return Ok(());
        }
        let dof = DOF * node + (j - self.first_input[end].unwrap_or(0));
        let drive = match condition {
            // Newmark from the node's start motion (`step::held_motion`):
            // v1 the input, a1 = (v1 - v0) / (gamma h) - ..., q1 = ... +
            // beta h^2 a1; the same under either hold.
            EndCondition::Velocity => Drive::Motion {
                dof,
                change: [beta * h / gamma, 1.0, 1.0 / (gamma * h)],
            },
            _ => Drive::Load {
                dof,
                weight: if ramp { 1.0 - alpha } else { 1.0 },
            },
        };
        sensitivity.solve(drive, &w.held, &mut w.change);
        let last = self.mechanics.nodes - 1;
        for (k, i) in [0, last].into_iter().enumerate() {
            let condition = if k == 0 {
                self.params.start.condition
            } else {
                self.params.end.condition
            };
            for c in 0..DOF {
                let d = DOF * i + c;
                let base = 9 * k;
                jacobian[(base + c) * n_in + j] = w.change.dq[d];
                jacobian[(base + 3 + c) * n_in + j] = w.change.dv[d];
                jacobian[(base + 6 + c) * n_in + j] = match condition {
                    _ if self.state.released[k] => 0.0,
                    EndCondition::Force if d == dof => -1.0,
                    EndCondition::Force => 0.0,
                    _ => -sensitivity.reaction_change(&w.change, d),
                };
            }
        }
        Ok(())
    }
}
