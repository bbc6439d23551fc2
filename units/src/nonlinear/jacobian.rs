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

use super::NonlinearSection;
use super::params::{DofCondition, Integrator};
use crate::beam::boundary::TimeFunction;
use crate::contract::{Hold, Inputs, UnitError};
use crate::integrators::hht::{SecondOrderSystem, TangentScales};
use crate::numerics::banded::SymmetricBand;

/// Buffers of the Jacobian, kept between calls; `ready` while the section's
/// last step is one HHT-alpha step whose factor is still the integrator's.
#[derive(Default)]
pub(super) struct JacobianWork {
    pub ready: bool,
    /// The last step's length (s).
    pub h: f64,
    stiffness: Option<SymmetricBand>,
    damping: Option<SymmetricBand>,
    q: Vec<f64>,
    v: Vec<f64>,
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
        jacobian.fill(f64::NAN);
        let mut result = Ok(());
        for j in 0..n_in {
            if let Err(e) = self.input_column(inputs, &mut w, j) {
                result = Err(e);
                break;
            }
            self.write_column(&w, j, n_in, jacobian);
        }
        self.jacobian_work = w;
        result
    }

    /// The tangent stiffness and damping of the restoring force at the step's
    /// end state.
    fn tangents(&mut self, w: &mut JacobianWork) {
        let n = self.model.dofs();
        w.q.clone_from(&self.state.q);
        w.v.clone_from(&self.state.v);
        let t = self.state.t;
        for (band, scales) in [(&mut w.stiffness, (1.0, 0.0)), (&mut w.damping, (0.0, 1.0))] {
            let b = band.get_or_insert_with(|| SymmetricBand::zeros(n, super::model::BAND));
            b.fill_zero();
            let scales = TangentScales {
                stiffness: scales.0,
                damping: scales.1,
            };
            self.nonlinear_force(&w.q, &w.v, t, Some((b, scales)), &mut w.force);
        }
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
                let (Some(kt), Some(ct)) = (&w.stiffness, &w.damping) else {
                    return Err(UnitError::Numerical(
                        "nonlinear section: the tangents of the Jacobian are missing".into(),
                    ));
                };
                let c = self.c.as_ref();
                let lo = d.saturating_sub(super::model::BAND);
                let hi = (d + super::model::BAND + 1).min(n);
                for f in lo..hi {
                    let damping = c.map_or(0.0, |c| c.get(f, d)) + ct.get(f, d);
                    w.dq[f] = -(self.m.get(f, d) * da
                        + (1.0 - alpha) * (damping * dv + kt.get(f, d) * dq));
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

    /// d(M a + (C + C_t) v + g) at DOF `i`.
    fn reaction_change(&self, w: &JacobianWork, i: usize) -> f64 {
        let n = self.model.dofs();
        let lo = i.saturating_sub(super::model::BAND);
        let hi = (i + super::model::BAND + 1).min(n);
        let (Some(kt), Some(ct)) = (&w.stiffness, &w.damping) else {
            return f64::NAN;
        };
        let c = self.c.as_ref();
        (lo..hi)
            .map(|k| {
                self.m.get(i, k) * w.da[k]
                    + (c.map_or(0.0, |c| c.get(i, k)) + ct.get(i, k)) * w.dv[k]
                    + kt.get(i, k) * w.dq[k]
            })
            .sum()
    }
}
