//! A reduced section's interface Jacobian over its last step
//! (`Unit::step_jacobian`): the derivative of its end outputs (positions,
//! velocities, forces) and station positions with respect to its coupled end
//! loads. Its inputs enter only through the projected load `Phi^T e_dof`, so
//! the derivative is the step's tangent-linear response to that load:
//! - trapezoidal rule: one back-substitution per input with the step's own
//!   factorised Newton matrix (`S ds = Phi^T e_dof`), no new factorisation;
//! - central differences: the scheme's tangent-linear recursion over the
//!   step's sub-steps (`m ds'' = w(s) Phi^T e_dof - (Q1 + K_t) ds`, the
//!   reduced mass factorised once per unit), with the tangent K_t frozen at
//!   the step's end: exact but for the tangent's change over one step.
//!
//! A Taylor basis (whose coordinates move the derivatives' columns) gives
//! none: a master takes it by finite differences. The critical step's row is
//! zero.

use super::build::{Model, Stepper};
use super::unit::{CRITICAL_STEP, EndForce, PER_END, ReducedUnit};
use crate::contract::{Hold, Inputs, UnitError, require_step_jacobian_ready};
use crate::integrators::hht::{SecondOrderSystem, TangentScales};
use crate::nonlinear::model::element_dofs;
use crate::numerics::banded::{BandLdlt, SymmetricBand};
use nalgebra::DVector;

/// Buffers of the Jacobian, kept between calls; `ready` while the unit's
/// motion is the end of one whole step (not restored since).
#[derive(Default)]
pub(super) struct JacobianWork {
    pub ready: bool,
    /// The last step's start time and length (s).
    pub t0: f64,
    pub h: f64,
    /// d s, d s', d s'' per unit input, one column of N per input.
    dq: Vec<f64>,
    dv: Vec<f64>,
    da: Vec<f64>,
    half: Vec<f64>,
    rhs: Vec<f64>,
    /// Each input's projected unit load `Phi^T e_dof`, one column of N each.
    loads: Vec<f64>,
    /// The replayed motion and its nonlinear force and tangent.
    q: Vec<f64>,
    v: Vec<f64>,
    force: Vec<f64>,
    tangent: Option<SymmetricBand>,
    mass: Option<BandLdlt>,
    /// Phi x on the free DOFs for x = d s, d s', d s''.
    free: [DVector<f64>; 3],
    /// Displacement and acceleration changes on all DOFs, the residual's.
    full: [Vec<f64>; 2],
    residual: Vec<f64>,
    /// The end elements' tangent stiffness at the step's end.
    element_tangent: [[[f64; 6]; 6]; 2],
}

/// The derivative of input `j`'s value at fraction `s` of the step with
/// respect to its end value.
fn weight(inputs: Inputs<'_>, j: usize, s: f64) -> f64 {
    match inputs.hold(j) {
        Hold::ZeroOrder => 1.0,
        Hold::Ramp => s,
    }
}

/// One tangent-linear central-difference sub-step of length `hk` (s): the
/// change of the reduced motion per unit input, given that input's weighted
/// projected load.
struct TangentLinear<'a> {
    hk: f64,
    /// Q1 (absent with sampled elements) and the nonlinear force's tangent
    /// at the sub-step's new coordinates.
    stiffness: [Option<&'a SymmetricBand>; 2],
    mass: Option<&'a BandLdlt>,
}

impl TangentLinear<'_> {
    /// Advances `[ds, ds', ds'']` as the scheme advances the motion; `rhs`
    /// holds the load on entry.
    fn advance(&self, [dq, dv, da]: [&mut [f64]; 3], half: &mut [f64], rhs: &mut [f64]) {
        let hk = self.hk;
        for i in 0..dq.len() {
            half[i] = dv[i] + 0.5 * hk * da[i];
            dq[i] += hk * half[i];
        }
        for k in self.stiffness.into_iter().flatten() {
            k.mul_add(-1.0, dq, rhs);
        }
        if let Some(mass) = self.mass {
            mass.solve_in_place(rhs);
        }
        for i in 0..dq.len() {
            da[i] = rhs[i];
            dv[i] = half[i] + 0.5 * hk * da[i];
        }
    }
}

impl ReducedUnit {
    /// Whether the unit gives its step Jacobian: a linear basis.
    pub(super) fn offers_jacobian(model: &Model) -> bool {
        matches!(model, Model::Linear(..))
    }

    /// Fills `jacobian` (outputs x inputs, row-major): every row but the
    /// energies' and extremes' (none here) exactly.
    pub(super) fn interface_jacobian(
        &mut self,
        inputs: Inputs<'_>,
        jacobian: &mut [f64],
    ) -> Result<(), UnitError> {
        require_step_jacobian_ready(self.jacobian.ready, "a reduced section")?;
        let mut w = std::mem::take(&mut self.jacobian);
        let result = self.columns(inputs, &mut w);
        if result.is_ok() {
            self.element_tangents(&mut w);
            for j in 0..inputs.len() {
                self.rows(inputs.len(), j, &mut w, jacobian);
            }
        }
        self.jacobian = w;
        result
    }

    /// The model DOF input `j` loads, if it is an end load.
    fn input_dof(&self, j: usize) -> Option<usize> {
        (self.input_dofs.iter())
            .find(|(i, _)| *i == j)
            .map(|&(_, dof)| dof)
    }

    /// The input's projected unit load `Phi^T e_dof` into `out` (zero where
    /// the input loads a held DOF or is no load).
    fn unit_load(&self, j: usize, out: &mut [f64]) {
        out.fill(0.0);
        let Model::Linear(system, _) = &self.model else {
            return;
        };
        let free = self.cubic.free_dofs();
        if let Some(k) = self.input_dof(j).and_then(|d| free.binary_search(&d).ok()) {
            for (c, o) in out.iter_mut().enumerate() {
                *o = system.basis()[(k, c)];
            }
        }
    }

    /// d s, d s', d s'' per input into `w`.
    fn columns(&mut self, inputs: Inputs<'_>, w: &mut JacobianWork) -> Result<(), UnitError> {
        let Model::Linear(system, _) = &self.model else {
            return Err(UnitError::Unsupported(
                "the step Jacobian of a reduced section on a Taylor basis".into(),
            ));
        };
        let n = system.size();
        for v in [&mut w.dq, &mut w.dv, &mut w.da] {
            v.clear();
            v.resize(n * inputs.len(), 0.0);
        }
        for v in [&mut w.half, &mut w.rhs, &mut w.q, &mut w.v] {
            v.resize(n, 0.0);
        }
        match self.model {
            Model::Linear(_, Stepper::Implicit(_)) => self.implicit_columns(inputs.len(), w),
            _ => self.explicit_columns(inputs, w),
        }
    }

    /// The trapezoidal rule: `S ds = Phi^T e_dof` (the end load's weight in
    /// the residual is 1 under either hold), `ds'' = ds / (beta h^2)`, `ds' =
    /// gamma / (beta h) ds`.
    fn implicit_columns(&self, n_in: usize, w: &mut JacobianWork) -> Result<(), UnitError> {
        let Model::Linear(system, Stepper::Implicit(implicit)) = &self.model else {
            return Ok(());
        };
        let (_, factor) = implicit.hht.last_newton_of("reduced section")?;
        let (_, beta, gamma) = implicit.hht.parameters();
        let (n, h) = (system.size(), w.h);
        for j in 0..n_in {
            let column = j * n..(j + 1) * n;
            self.unit_load(j, &mut w.dq[column.clone()]);
            factor.solve_in_place(&mut w.dq[column.clone()]);
            for i in column {
                w.da[i] = w.dq[i] / (beta * h * h);
                w.dv[i] = gamma / (beta * h) * w.dq[i];
            }
        }
        Ok(())
    }

    /// Central differences: the tangent-linear recursion of the step's
    /// sub-steps with the tangent frozen at the step's end (one evaluation of
    /// it, not one per sub-step: the reduced tensors' tangent costs about N^4,
    /// more than the sub-steps themselves; the error is the tangent's change
    /// over the step).
    fn explicit_columns(
        &mut self,
        inputs: Inputs<'_>,
        w: &mut JacobianWork,
    ) -> Result<(), UnitError> {
        let h = w.h;
        let substeps = self.substeps(h);
        let hk = h / substeps as f64;
        // Each input's projected unit load, weighted per sub-step below.
        let n = w.half.len();
        w.loads.resize(n * inputs.len(), 0.0);
        for j in 0..inputs.len() {
            self.unit_load(j, &mut w.loads[j * n..(j + 1) * n]);
        }
        let Model::Linear(system, Stepper::Explicit(_)) = &mut self.model else {
            return Ok(());
        };
        if w.mass.is_none() {
            w.mass = Some(BandLdlt::new(system.matrices().mass).ok_or_else(|| {
                UnitError::Numerical(
                    "reduced section: the reduced mass is not positive definite".into(),
                )
            })?);
        }
        let tangent = w
            .tangent
            .get_or_insert_with(|| SymmetricBand::zeros(n, n.saturating_sub(1)));
        tangent.fill_zero();
        let [q, v, _] = system.motion();
        w.q.copy_from_slice(q);
        w.v.copy_from_slice(v);
        let scales = TangentScales {
            stiffness: 1.0,
            damping: 0.0,
        };
        let t1 = w.t0 + h;
        system.nonlinear_force(&w.q, &w.v, t1, Some((tangent, scales)), &mut w.force);
        let stiffness = [system.matrices().stiffness, Some(&*tangent)];
        for j in 0..inputs.len() {
            let column = j * n..(j + 1) * n;
            let change = TangentLinear {
                hk,
                stiffness,
                mass: w.mass.as_ref(),
            };
            for k in 1..=substeps {
                // The unit load of input j, weighted at fraction s.
                let scale = weight(inputs, j, k as f64 / substeps as f64);
                for (r, l) in w.rhs.iter_mut().zip(&w.loads[column.clone()]) {
                    *r = scale * l;
                }
                change.advance(
                    [
                        &mut w.dq[column.clone()],
                        &mut w.dv[column.clone()],
                        &mut w.da[column.clone()],
                    ],
                    &mut w.half,
                    &mut w.rhs,
                );
            }
        }
        Ok(())
    }

    /// The end elements' tangent stiffness at the step's end displacements.
    fn element_tangents(&self, w: &mut JacobianWork) {
        let model = self.section.model();
        let full = &mut w.full[0];
        full.clear();
        full.resize(model.dofs(), 0.0);
        for (k, &dof) in self.cubic.free_dofs().iter().enumerate() {
            full[dof] = self.displacement[k];
        }
        let last = model.elements.len() - 1;
        for (side, e) in [0, last].into_iter().enumerate() {
            let p = element_dofs(full, e);
            w.element_tangent[side] = model.elements[e].force(model.formulation, &p, true).1;
        }
    }

    /// Column `j` of the Jacobian from `w`'s d s, d s', d s'': positions,
    /// velocities and stations through the basis, each end force as the
    /// output's own rule differentiated (`end_forces`).
    fn rows(&self, n_in: usize, j: usize, w: &mut JacobianWork, jacobian: &mut [f64]) {
        let Model::Linear(system, _) = &self.model else {
            return;
        };
        let n = system.size();
        let column = j * n..(j + 1) * n;
        let [dd, dv, da] = &mut w.free;
        for (x, out) in [(&w.dq, &mut *dd), (&w.dv, &mut *dv), (&w.da, &mut *da)] {
            out.resize_vertically_mut(self.cubic.size(), 0.0);
            let x = nalgebra::DVectorView::from_slice(&x[column.clone()], n);
            out.gemv(1.0, system.basis(), &x, 0.0);
        }
        let mut put = |row: usize, value: f64| jacobian[row * n_in + j] = value;
        put(CRITICAL_STEP, 0.0);
        self.kinematic_rows(dd, dv, false, &mut put);
        // The residual's change d(f - M a) on all DOFs: the unit load at the
        // step's end less the mass times the accelerations' change.
        let model = self.section.model();
        let free = self.cubic.free_dofs();
        let [full_d, full_a] = &mut w.full;
        full_d.fill(0.0);
        full_a.resize(model.dofs(), 0.0);
        full_a.fill(0.0);
        for (k, &dof) in free.iter().enumerate() {
            full_d[dof] = dd[k];
            full_a[dof] = da[k];
        }
        let residual = &mut w.residual;
        residual.clear();
        residual.resize(model.dofs(), 0.0);
        let loaded = self.input_dof(j);
        if let Some(dof) = loaded {
            residual[dof] = 1.0;
        }
        self.section.mass_matrix().mul_add(-1.0, full_a, residual);
        let last = model.reference.len() - 1;
        for (side, node) in [0, last].into_iter().enumerate() {
            let e = if side == 0 { 0 } else { last - 1 };
            let p = element_dofs(full_d, e);
            for c in 0..3 {
                let dof = 3 * node + c;
                let value = match self.end_force_rule(side, c, dof) {
                    EndForce::BalanceSum => residual.iter().skip(c).step_by(3).sum(),
                    EndForce::Element(local) => {
                        let k = &w.element_tangent[side][local];
                        residual[dof] - (0..6).map(|i| k[i] * p[i]).sum::<f64>()
                    }
                    // Minus the load: -1 per unit of this input's own load.
                    EndForce::Load if loaded == Some(dof) => -1.0,
                    EndForce::Load => 0.0,
                    EndForce::Zero => 0.0,
                };
                put(PER_END * side + 6 + c, value);
            }
        }
    }
}
