//! The section's interface Jacobian over its last step (`Unit::step_jacobian`):
//! the derivative of its end outputs (positions, velocities, forces) with
//! respect to its coupled end inputs, by one back-substitution per input with
//! the step's factorised HHT-alpha Newton matrix; no new factorisation. The
//! other outputs (energies, stations, extremes) are left NaN: a master that
//! needs one takes it by finite differences.
//!
//! At the converged step the free DOFs satisfy `R(q1; u) = 0` with
//! `R = M a1 + (1 - alpha) (C v1 + g(q1, v1)) + ... - (1 - alpha) f1 - alpha f0`
//! and a1, v1 from q1 by Newmark. An input moves a held DOF (its q, v and a as
//! the end condition prescribes them) or loads one; then
//! `S dq_free = -dR/du`, S the Newton matrix, and the outputs follow from dq.
//! The Newton matrix `S = M / (beta h^2) + (1 - alpha) (gamma / (beta h) (C +
//! C_t) + K_t)` is the integrator's last, kept before its held rows became
//! identity rows; only the drag's tangent damping C_t is assembled anew, to
//! tell K_t from C_t where a held DOF's kinematics are not Newmark's.

use super::NonlinearSection;
use super::params::{DofCondition, Integrator};
use crate::beam::boundary::TimeFunction;
use crate::contract::{Hold, Inputs, UnitError};
use crate::numerics::banded::SymmetricBand;

/// Buffers of the Jacobian, kept between calls; `ready` while the section's
/// last step is one HHT-alpha step whose factor is still the integrator's.
#[derive(Default)]
pub(super) struct JacobianWork {
    pub ready: bool,
    /// The last step's length (s).
    pub h: f64,
    /// The last whole step: its start time (s), end inputs and end
    /// displacements, and (`columns_valid`) d q / d input per input
    /// (`n_in x dofs`): the warm start of a repeated step.
    last_t0: f64,
    last_inputs: Vec<f64>,
    last_end: Vec<f64>,
    columns: Vec<f64>,
    columns_valid: bool,
    /// The next step repeats the last one (`Unit::warm_repeat`).
    pub warm: bool,
    guess: Vec<f64>,
    /// The drag's tangent damping C_t at the step's end.
    damping: Option<SymmetricBand>,
    force: Vec<f64>,
    dq: Vec<f64>,
    dv: Vec<f64>,
    da: Vec<f64>,
}

/// How a unit change of an input moves its DOF: (dq, dv, da) of a held DOF, or
/// the weight of a load in the residual.
enum Effect {
    Motion([f64; 3]),
    Load(f64),
}

impl NonlinearSection {
    /// Whether the section can give its Jacobian at all: HHT-alpha without
    /// contact laws stepped by their discrete gradient.
    pub(super) fn offers_jacobian(&self) -> bool {
        matches!(self.params.integrator, Integrator::Hht { .. })
            && !self.environment.contacts.is_discrete()
    }

    /// Fills `jacobian` (outputs x inputs, row-major): the end outputs' rows
    /// exactly, the others NaN.
    pub(super) fn interface_jacobian(
        &mut self,
        inputs: Inputs<'_>,
        jacobian: &mut [f64],
    ) -> Result<(), UnitError> {
        if !self.jacobian_work.ready {
            return Err(UnitError::Unsupported(
                "the step Jacobian of a nonlinear section after a step taken in sub-steps, or before any step".into(),
            ));
        }
        let mut w = std::mem::take(&mut self.jacobian_work);
        self.tangents(&mut w);
        let n_in = inputs.len();
        let n = self.model.dofs();
        jacobian.fill(f64::NAN);
        w.columns.resize(n_in * n, 0.0);
        w.columns_valid = false;
        let mut result = Ok(());
        for j in 0..n_in {
            if let Err(e) = self.input_column(inputs, &mut w, j) {
                result = Err(e);
                break;
            }
            self.write_column(&w, j, n_in, jacobian);
            w.columns[j * n..(j + 1) * n].copy_from_slice(&w.dq);
        }
        w.columns_valid = result.is_ok();
        self.jacobian_work = w;
        result
    }

    /// The drag's tangent damping at the step's end state (zero without drag).
    fn tangents(&mut self, w: &mut JacobianWork) {
        let n = self.model.dofs();
        let b = w
            .damping
            .get_or_insert_with(|| SymmetricBand::zeros(n, super::model::BAND));
        b.fill_zero();
        if self.environment.is_empty() {
            return;
        }
        w.force.clear();
        w.force.resize(n, 0.0);
        let s = &self.state;
        self.environment.add_force(
            &self.model,
            (&s.q, &s.v, s.t),
            &s.lambda,
            1.0,
            true,
            Some((b, 0.0, 1.0)),
            &mut w.force,
        );
    }

    /// The damping of the step's end, C + C_t, at (i, k).
    fn damping_at(&self, w: &JacobianWork, i: usize, k: usize) -> f64 {
        self.c.as_ref().map_or(0.0, |c| c.get(i, k))
            + w.damping.as_ref().map_or(0.0, |c| c.get(i, k))
    }

    /// dq, dv, da of every DOF for a unit change of input `j`.
    fn input_column(
        &self,
        inputs: Inputs<'_>,
        w: &mut JacobianWork,
        j: usize,
    ) -> Result<(), UnitError> {
        let n = self.model.dofs();
        let (alpha, beta, gamma) = self.hht.parameters();
        let h = w.h;
        for v in [&mut w.dq, &mut w.dv, &mut w.da] {
            v.clear();
            v.resize(n, 0.0);
        }
        let Some(r) = self.ends.iter().find(|r| r.input == Some(j)) else {
            return Ok(());
        };
        let ramp = inputs.hold(j) == Hold::Ramp;
        let effect = match r.condition {
            DofCondition::Velocity | DofCondition::VelocityFrom(_) => {
                Effect::Motion([0.5 * h, 1.0, 2.0 / h])
            }
            DofCondition::Displacement(TimeFunction::Input(_)) if ramp => {
                Effect::Motion([1.0, 1.0 / h, 1.0 / (h * h)])
            }
            DofCondition::Displacement(TimeFunction::Input(_)) => Effect::Motion([1.0, 0.0, 0.0]),
            DofCondition::Force(TimeFunction::Input(_)) => {
                Effect::Load(1.0 - alpha + if ramp { 0.0 } else { alpha })
            }
            _ => return Ok(()),
        };
        let d = r.dof;
        // The right-hand side -dR/du on the free DOFs (in dq), the held DOFs'
        // prescribed change on their identity rows.
        match effect {
            Effect::Load(weight) => w.dq[d] = weight,
            Effect::Motion([dq, dv, da]) => {
                let s = self.hht.kept_newton_matrix().ok_or_else(|| {
                    UnitError::Numerical("nonlinear section: no Newton matrix kept".into())
                })?;
                // dR_f = S dq + M (da - dq / (beta h^2))
                //        + (1 - alpha) (C + C_t) (dv - gamma / (beta h) dq).
                let lo = d.saturating_sub(super::model::BAND);
                let hi = (d + super::model::BAND + 1).min(n);
                for f in lo..hi {
                    w.dq[f] = -(s.get(f, d) * dq
                        + self.m.get(f, d) * (da - dq / (beta * h * h))
                        + (1.0 - alpha)
                            * self.damping_at(w, f, d)
                            * (dv - gamma / (beta * h) * dq));
                }
                for held in self.held() {
                    w.dq[held.dof] = 0.0;
                }
                w.dq[d] = dq;
            }
        }
        let factor = self.hht.newton_factor().ok_or_else(|| {
            UnitError::Numerical("nonlinear section: no factorised Newton matrix".into())
        })?;
        factor.solve_in_place(&mut w.dq);
        for i in 0..n {
            w.da[i] = w.dq[i] / (beta * h * h);
            w.dv[i] = gamma / (beta * h) * w.dq[i];
        }
        for held in self.held() {
            w.dv[held.dof] = 0.0;
            w.da[held.dof] = 0.0;
        }
        if let Effect::Motion([_, dv, da]) = effect {
            w.dv[d] = dv;
            w.da[d] = da;
        }
        Ok(())
    }

    /// Column `j` of the end outputs' rows from dq, dv, da: positions and
    /// velocities directly, a force as minus the change of the support
    /// reaction `M a + C v + g - f`, or of the applied load where the end is
    /// loaded.
    fn write_column(&self, w: &JacobianWork, j: usize, n_in: usize, jacobian: &mut [f64]) {
        let nodes = self.model.reference.len();
        for end in 0..2 {
            let node = if end == 0 { 0 } else { nodes - 1 };
            let base = 9 * end;
            for k in 0..3 {
                let dof = 3 * node + k;
                jacobian[(base + k) * n_in + j] = w.dq[dof];
                jacobian[(base + 3 + k) * n_in + j] = w.dv[dof];
                let loaded = self
                    .ends
                    .iter()
                    .find(|c| c.end == end && c.component == k && !c.is_kinematic());
                jacobian[(base + 6 + k) * n_in + j] = match loaded {
                    Some(c) => {
                        if c.input == Some(j) {
                            -1.0
                        } else {
                            0.0
                        }
                    }
                    None => -self.reaction_change(w, dof),
                };
            }
        }
    }

    /// d(M a + (C + C_t) v + g) at DOF `i`, with K_t from the kept Newton
    /// matrix: (1 - alpha) K_t = S - M / (beta h^2) - (1 - alpha) gamma /
    /// (beta h) (C + C_t).
    fn reaction_change(&self, w: &JacobianWork, i: usize) -> f64 {
        let Some(s) = self.hht.kept_newton_matrix() else {
            return f64::NAN;
        };
        let (alpha, beta, gamma) = self.hht.parameters();
        let h = w.h;
        let n = self.model.dofs();
        let lo = i.saturating_sub(super::model::BAND);
        let hi = (i + super::model::BAND + 1).min(n);
        (lo..hi)
            .map(|k| {
                let (m, c) = (self.m.get(i, k), self.damping_at(w, i, k));
                let kt =
                    (s.get(i, k) - m / (beta * h * h)) / (1.0 - alpha) - gamma / (beta * h) * c;
                m * w.da[k] + c * w.dv[k] + kt * w.dq[k]
            })
            .sum()
    }
}

impl JacobianWork {
    /// Records a whole step from `t0` that ended at `q` with end `inputs`.
    pub fn record_step(&mut self, t0: f64, inputs: &[f64], q: &[f64]) {
        self.last_t0 = t0;
        self.last_inputs.clear();
        self.last_inputs.extend_from_slice(inputs);
        self.last_end.clear();
        self.last_end.extend_from_slice(q);
        self.columns_valid = false;
    }

    /// The first iterate of a step from `t0` with end `inputs` that repeats
    /// the last one (after `Unit::warm_repeat`): its end displacements moved
    /// by the Jacobian's columns where they are of that step; None when the
    /// step is another one. Clears the hint.
    pub fn warm_guess(&mut self, t0: f64, inputs: &[f64]) -> Option<&[f64]> {
        let warm = std::mem::take(&mut self.warm);
        if !warm
            || t0 != self.last_t0
            || inputs.len() != self.last_inputs.len()
            || self.last_end.is_empty()
        {
            return None;
        }
        let n = self.last_end.len();
        self.guess.clone_from(&self.last_end);
        if self.columns_valid && self.columns.len() == n * inputs.len() {
            for (j, (u, u0)) in inputs.iter().zip(&self.last_inputs).enumerate() {
                let du = u - u0;
                if du != 0.0 {
                    for (g, c) in self.guess.iter_mut().zip(&self.columns[j * n..(j + 1) * n]) {
                        *g += c * du;
                    }
                }
            }
        }
        Some(&self.guess)
    }
}
