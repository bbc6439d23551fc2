//! The section's interface Jacobian over its last step (`Unit::step_jacobian`):
//! the derivative of its end outputs (positions, velocities, forces) with
//! respect to its coupled end inputs, by one back-substitution per input (all
//! inputs in one pass, `BandLdlt::solve_columns_in_place`) with
//! the step's factorised HHT-alpha Newton matrix; no new factorisation. The
//! other outputs (energies, stations, extremes) are left NaN: a master that
//! needs one takes it by finite differences.
//!
//! The section's Newton matrix is the integrator's last, kept before its held
//! rows became identity rows; only the drag's tangent damping C_t is assembled
//! anew (`integrators::hht_sensitivity` tells K_t from it).

use super::NonlinearSection;
use super::params::{DofCondition, Integrator};
use crate::beam::boundary::TimeFunction;
use crate::contract::{Hold, Inputs, UnitError};
use crate::integrators::hht_sensitivity::{Change, Drive, StepSensitivity};
use crate::integrators::warm_start::WarmStart;
use crate::numerics::banded::SymmetricBand;

/// Buffers of the Jacobian, kept between calls; `ready` while the section's
/// last step is one HHT-alpha step whose factor is still the integrator's.
#[derive(Default)]
pub(super) struct JacobianWork {
    pub ready: bool,
    /// The last step's length (s).
    pub h: f64,
    /// The last whole step and its derivatives: the warm start of a
    /// repeated step.
    pub warm: WarmStart,
    /// The drag's tangent damping C_t at the step's end.
    damping: Option<SymmetricBand>,
    force: Vec<f64>,
    held: Vec<usize>,
    change: Change,
    /// How each input drives the step, and the displacements' change
    /// solved for them (a column each).
    drives: Vec<Option<Drive>>,
    columns: Vec<f64>,
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
        if self.reduction.is_some() {
            return self.reduced_jacobian(inputs, jacobian);
        }
        if !self.jacobian_work.ready {
            return Err(UnitError::Unsupported(
                "the step Jacobian of a nonlinear section after a step taken in sub-steps, or before any step".into(),
            ));
        }
        let mut w = std::mem::take(&mut self.jacobian_work);
        self.tangents(&mut w);
        w.held.clear();
        w.held.extend(self.held().map(|r| r.dof));
        jacobian.fill(f64::NAN);
        w.warm.begin_columns(inputs.len(), self.model.dofs());
        let result = self.input_columns(inputs, &mut w, jacobian);
        w.warm.columns_done(result.is_ok());
        self.jacobian_work = w;
        result
    }

    /// The drag's tangent damping at the step's end state (zero without
    /// drag), or the one a linear section's step used. The sensitivity reads
    /// it only at the end nodes' rows and columns (the held DOFs and the
    /// reactions are there), so only the two end elements are evaluated:
    /// those entries are the whole section's, in the same order of sums.
    fn tangents(&mut self, w: &mut JacobianWork) {
        let n = self.model.dofs();
        let b = w
            .damping
            .get_or_insert_with(|| SymmetricBand::zeros(n, super::model::BAND));
        match self.linear_drag_tangent() {
            Some(d0) => b.copy_from(d0),
            None => {
                b.fill_zero();
                w.force.clear();
                w.force.resize(n, 0.0);
                let (ends, count) = self.model.end_elements();
                let s = &self.state;
                (self.environment).add_drag_damping_of(
                    &self.model,
                    (&s.q, &s.v),
                    &ends[..count],
                    b,
                    &mut w.force,
                );
            }
        }
    }

    /// Adds the drag's tangent damping C_t at the current state to `band`
    /// (nothing without drag; in a current not zero at rest), with `scratch`
    /// for the force it also forms.
    pub(super) fn add_drag_damping(&self, band: &mut SymmetricBand, scratch: &mut Vec<f64>) {
        if self.environment.is_empty() {
            return;
        }
        scratch.clear();
        scratch.resize(self.model.dofs(), 0.0);
        let s = &self.state;
        let at = (s.q.as_slice(), s.v.as_slice(), s.t);
        let tangent = Some((band, 0.0, 1.0));
        (self.environment).add_force(&self.model, at, &s.lambda, 1.0, true, tangent, scratch);
    }

    /// How a unit change of input `j` drives the step, if it does.
    pub(super) fn drive_of(&self, inputs: Inputs<'_>, j: usize, h: f64) -> Option<Drive> {
        let r = self.ends.iter().find(|r| r.input == Some(j))?;
        let ramp = inputs.hold(j) == Hold::Ramp;
        let (alpha, _, _) = self.hht.parameters();
        let (dof, motion) = (r.dof, |change| Drive::Motion { dof: r.dof, change });
        Some(match r.condition {
            DofCondition::Velocity | DofCondition::VelocityFrom(_) => {
                motion([0.5 * h, 1.0, 2.0 / h])
            }
            DofCondition::Displacement(TimeFunction::Input(_)) if ramp => {
                motion([1.0, 1.0 / h, 1.0 / (h * h)])
            }
            DofCondition::Displacement(TimeFunction::Input(_)) => motion([1.0, 0.0, 0.0]),
            DofCondition::Force(TimeFunction::Input(_)) => Drive::Load {
                dof,
                weight: 1.0 - alpha + if ramp { 0.0 } else { alpha },
            },
            _ => return None,
        })
    }

    /// Every input's column: the motion's change (its displacements solved
    /// for all inputs together, into the warm start's columns too), then the
    /// end outputs' rows: positions and velocities directly, a force as
    /// minus the change of the support reaction, or of the applied load
    /// where the end is loaded.
    fn input_columns(
        &self,
        inputs: Inputs<'_>,
        w: &mut JacobianWork,
        jacobian: &mut [f64],
    ) -> Result<(), UnitError> {
        let n_in = inputs.len();
        let JacobianWork {
            damping,
            held,
            change,
            h,
            drives,
            columns,
            warm,
            ..
        } = w;
        let c = self.c.as_ref();
        let damping_at = |i: usize, k: usize| {
            c.map_or(0.0, |c| c.get(i, k)) + damping.as_ref().map_or(0.0, |c| c.get(i, k))
        };
        let sensitivity = StepSensitivity::of_last_step(
            &self.hht,
            "nonlinear section",
            (&self.m, &damping_at),
            *h,
        )?;
        drives.clear();
        drives.extend((0..n_in).map(|j| self.drive_of(inputs, j, *h)));
        sensitivity.solve_columns(drives, held, columns);
        let solved = drives.iter().zip(columns.chunks_exact(self.model.dofs()));
        for (j, (drive, column)) in solved.enumerate() {
            sensitivity.change_of(*drive, held, column, change);
            let reaction = |dof| sensitivity.reaction_change(change, dof);
            self.end_rows((&change.dq, &change.dv), &reaction, (j, n_in), jacobian);
            warm.set_column(j, &change.dq);
        }
        Ok(())
    }

    /// Column `j` of the end outputs' rows from the motion's change `dq`,
    /// `dv` (all DOFs): positions and velocities directly, a force as minus
    /// the change of the support `reaction` at its DOF, or of the applied
    /// load where the end is loaded.
    pub(super) fn end_rows(
        &self,
        (dq, dv): (&[f64], &[f64]),
        reaction: &dyn Fn(usize) -> f64,
        (j, n_in): (usize, usize),
        jacobian: &mut [f64],
    ) {
        let nodes = self.model.reference.len();
        for end in 0..2 {
            let node = if end == 0 { 0 } else { nodes - 1 };
            let base = 9 * end;
            for k in 0..3 {
                let dof = 3 * node + k;
                jacobian[(base + k) * n_in + j] = dq[dof];
                jacobian[(base + 3 + k) * n_in + j] = dv[dof];
                let loaded = self
                    .ends
                    .iter()
                    .find(|c| c.end == end && c.component == k && !c.is_kinematic());
                jacobian[(base + 6 + k) * n_in + j] = match loaded {
                    Some(c) if c.input == Some(j) => -1.0,
                    Some(_) => 0.0,
                    None => -reaction(dof),
                };
            }
        }
    }
}
