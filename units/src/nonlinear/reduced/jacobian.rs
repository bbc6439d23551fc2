//! The reduced section's interface Jacobian over its last step: the
//! sensitivity of the reduced step (`integrators::hht_sensitivity`) with the
//! reduced Newton matrix formed exactly at the step's end (the step itself may
//! have converged on a frozen tangent), mapped to the end outputs through the
//! basis. A coupled end motion drives its constraint coordinate; a coupled end
//! force loads the coordinates through its row of the basis.

use super::products::times_rows;
use super::sampled::{Hyper, Sample};
use super::{Reduction, project};
use crate::contract::{Inputs, UnitError};
use crate::integrators::hht_sensitivity::{Change, Drive, StepSensitivity};
use crate::nonlinear::NonlinearSection;
use crate::numerics::banded::{BandLdlt, SymmetricBand};

/// Buffers of the Jacobian, kept between calls.
#[derive(Default)]
pub(super) struct JacobianBuffers {
    /// The full tangent stiffness and drag damping at the step's end.
    stiffness: Option<SymmetricBand>,
    drag: Option<SymmetricBand>,
    force: Vec<f64>,
    scratch: Vec<f64>,
    /// K_t + c C_t, and the projections (m x m, row-major) of that and of
    /// C_t's columns at the held coordinates.
    combined: Option<SymmetricBand>,
    reduced_stiffness: Vec<f64>,
    reduced_drag: Vec<f64>,
    change: Change,
    /// The reduced Newton matrix, it with the held coordinates as identity
    /// rows factorised, and those coordinates (kept: nothing allocated per
    /// call once sized).
    newton: Option<SymmetricBand>,
    with_held: Option<SymmetricBand>,
    factor: Option<BandLdlt>,
    held: Vec<usize>,
    /// dz / d input per input (`n_in x m`): the warm start of a repeated step.
    columns: Vec<f64>,
    /// The change of the full motion: dq, dv, da.
    full: [Vec<f64>; 3],
}

impl JacobianBuffers {
    /// The full tangent stiffness and drag damping bands (n DOFs), zeroed.
    fn zeroed_tangents(&mut self, n: usize) -> (SymmetricBand, SymmetricBand) {
        let mut k = (self.stiffness.take())
            .unwrap_or_else(|| SymmetricBand::zeros(n, crate::nonlinear::model::BAND));
        let mut c = self.drag.take().unwrap_or_else(|| k.clone());
        k.fill_zero();
        c.fill_zero();
        (k, c)
    }
}

impl NonlinearSection {
    /// Fills `jacobian` (outputs x inputs, row-major): the end outputs' rows,
    /// the others NaN.
    pub(in crate::nonlinear) fn reduced_jacobian(
        &mut self,
        inputs: Inputs<'_>,
        jacobian: &mut [f64],
    ) -> Result<(), UnitError> {
        let Some(mut r) = self.reduction.take() else {
            return Err(UnitError::Unsupported(
                "the Jacobian of a reduced section before its basis is formed".into(),
            ));
        };
        let result = self.reduced_columns(&mut r, inputs, jacobian);
        if result.is_ok() {
            self.jacobian_work.warm.set_columns(&r.jacobian.columns);
        }
        self.reduction = Some(r);
        result
    }

    /// The full tangents at the step's end; projected, K_t + `damping_scale`
    /// C_t and C_t's columns at the held coordinates.
    fn end_tangents(&self, r: &mut Reduction, b: &mut JacobianBuffers, damping_scale: f64) {
        if let Some(Hyper::Sampled(sample)) = r.hyper.as_mut() {
            return self.sampled_end_tangents(sample, (r.n, r.m - r.held.len()), b, damping_scale);
        }
        let n = r.n;
        let s = &self.state;
        b.force.clear();
        b.force.resize(n, 0.0);
        let (mut k, mut c) = b.zeroed_tangents(n);
        self.model
            .add_internal_force(&s.q, 1.0, Some((&mut k, 1.0)), &mut b.force);
        if !self.environment.is_empty() {
            let at = (s.q.as_slice(), s.v.as_slice(), s.t);
            let tangent = Some((&mut k, 1.0, 0.0));
            (self.environment).add_force(
                &self.model,
                at,
                &s.lambda,
                1.0,
                true,
                tangent,
                &mut b.force,
            );
        }
        self.add_drag_damping(&mut c, &mut b.force);
        // The Newton matrix needs K_t + c C_t only; the motion of a held
        // coordinate also C_t's columns there.
        let mut combined = b.combined.take().unwrap_or_else(|| k.clone());
        combined.set_combination(&[(1.0, &k), (damping_scale, &c)]);
        let m = r.m;
        project(
            &r.basis,
            (n, m),
            &combined,
            &mut b.scratch,
            &mut b.reduced_stiffness,
        );
        b.combined = Some(combined);
        b.reduced_drag.clear();
        b.reduced_drag.resize(m * m, 0.0);
        b.scratch.resize(n, 0.0);
        let free = m - r.held.len();
        for j in free..m {
            b.scratch.fill(0.0);
            c.mul_add(1.0, &r.basis[j * n..(j + 1) * n], &mut b.scratch);
            for i in 0..m {
                b.reduced_drag[i * m + j] =
                    super::products::dot(&r.basis[i * n..(i + 1) * n], &b.scratch);
            }
        }
        (b.stiffness, b.drag) = (Some(k), Some(c));
    }

    /// [`Self::end_tangents`] through the sample (the tangent of the force
    /// the step solved); the full bands hold the end terms only, all the
    /// reactions read.
    fn sampled_end_tangents(
        &self,
        sample: &mut Sample,
        (n, free): (usize, usize),
        b: &mut JacobianBuffers,
        damping_scale: f64,
    ) {
        let (mut k, mut c) = b.zeroed_tangents(n);
        self.add_end_tangents(&mut k, &mut c);
        let projected = (&mut b.reduced_stiffness, &mut b.reduced_drag);
        sample.tangents(self, damping_scale, free, projected);
        (b.stiffness, b.drag) = (Some(k), Some(c));
    }

    fn reduced_columns(
        &self,
        r: &mut Reduction,
        inputs: Inputs<'_>,
        jacobian: &mut [f64],
    ) -> Result<(), UnitError> {
        if !self.jacobian_work.ready {
            return Err(UnitError::Unsupported(
                "the step Jacobian of a reduced section after a step taken in sub-steps, or before any step".into(),
            ));
        }
        let mut b = std::mem::take(&mut r.jacobian);
        let (n, m, free) = (r.n, r.m, r.m - r.held.len());
        let h = self.jacobian_work.h;
        let (alpha, beta, gamma) = r.hht.parameters();
        self.end_tangents(r, &mut b, gamma / (beta * h));
        let (newton, factor) = reduced_newton(r, &mut b, h)?;
        let rayleigh = |i: usize, k: usize| r.damping.as_ref().map_or(0.0, |c| c.get(i, k));
        let damping = |i: usize, k: usize| rayleigh(i, k) + b.reduced_drag[i * m + k];
        let mut held = std::mem::take(&mut b.held);
        held.clear();
        held.extend(free..m);
        let sensitivity = StepSensitivity {
            newton: &newton,
            factor: &factor,
            mass: &r.mass,
            damping: &damping,
            parameters: (alpha, beta, gamma),
            h,
        };
        let n_in = inputs.len();
        jacobian.fill(f64::NAN);
        b.columns.clear();
        for j in 0..n_in {
            let mut change = std::mem::take(&mut b.change);
            match self.drive_of(inputs, j, h) {
                Some(Drive::Motion { dof, change: c }) => {
                    match r.held.iter().position(|&d| d == dof) {
                        Some(p) => {
                            let drive = Drive::Motion {
                                dof: free + p,
                                change: c,
                            };
                            sensitivity.solve(drive, &held, &mut change);
                        }
                        None => change.clear(m),
                    }
                }
                Some(Drive::Load { dof, weight }) => {
                    load_change(r, (dof, weight), &factor, (beta, gamma, h), &mut change);
                }
                None => change.clear(m),
            }
            // Only where the end rows read: the end nodes and their band.
            let reach = (3 + crate::nonlinear::model::BAND).min(n);
            let rows = [0..reach, (n - reach).max(reach)..n];
            for (full, reduced) in b.full.iter_mut().zip([&change.dq, &change.dv, &change.da]) {
                full.clear();
                full.resize(n, 0.0);
                times_rows(&r.basis, (n, m), reduced, &rows, full);
            }
            let [dq, dv, _] = &b.full;
            let reaction = |dof| self.reaction_change(&b, dof);
            self.end_rows((dq, dv), &reaction, (j, n_in), jacobian);
            b.columns.extend_from_slice(&change.dq);
            b.change = change;
        }
        (b.newton, b.factor, b.held) = (Some(newton), Some(factor), held);
        r.jacobian = b;
        Ok(())
    }

    /// The change of the reaction M a + (C + C_t) v + K_t q at DOF `i`.
    fn reaction_change(&self, b: &JacobianBuffers, i: usize) -> f64 {
        let [dq, dv, da] = &b.full;
        let (Some(k), Some(ct)) = (&b.stiffness, &b.drag) else {
            return f64::NAN;
        };
        let w = k.half_bandwidth();
        (i.saturating_sub(w)..(i + w + 1).min(dq.len()))
            .map(|c| {
                let damping = self.c.as_ref().map_or(0.0, |m| m.get(i, c)) + ct.get(i, c);
                self.m.get(i, c) * da[c] + damping * dv[c] + k.get(i, c) * dq[c]
            })
            .sum()
    }
}

/// The reduced Newton matrix at the step's end, M_r / (beta h^2) + (1 -
/// alpha) (gamma / (beta h) C_r + [K_t + c C_t]_r), and its factor with the
/// held coordinates as identity rows, in `b`'s buffers.
fn reduced_newton(
    r: &Reduction,
    b: &mut JacobianBuffers,
    h: f64,
) -> Result<(SymmetricBand, BandLdlt), UnitError> {
    let (m, free) = (r.m, r.m - r.held.len());
    let (alpha, beta, gamma) = r.hht.parameters();
    let rayleigh = |i: usize, k: usize| r.damping.as_ref().map_or(0.0, |c| c.get(i, k));
    let mut newton = (b.newton.take()).unwrap_or_else(|| SymmetricBand::zeros(m, m - 1));
    newton.fill_zero();
    for i in 0..m {
        for k in i..m {
            let value = r.mass.get(i, k) / (beta * h * h)
                + (1.0 - alpha)
                    * (gamma / (beta * h) * rayleigh(i, k) + b.reduced_stiffness[i * m + k]);
            newton.add(i, k, value);
        }
    }
    let with_held = b.with_held.get_or_insert_with(|| newton.clone());
    with_held.copy_from(&newton);
    (free..m).for_each(|j| with_held.set_identity_row(j));
    let mut factor = (b.factor.take()).unwrap_or_else(|| BandLdlt::zeros(m, m - 1));
    if !factor.refactorise(with_held) {
        return Err(UnitError::Numerical(
            "reduced section: its Newton matrix is singular".into(),
        ));
    }
    Ok((newton, factor))
}

/// The reduced motion's change under a unit load at full DOF `dof` with its
/// weight in the residual: S dz = weight T^T e_dof, the held coordinates
/// still; velocities and accelerations by Newmark.
fn load_change(
    r: &Reduction,
    (dof, weight): (usize, f64),
    factor: &BandLdlt,
    (beta, gamma, h): (f64, f64, f64),
    change: &mut Change,
) {
    let (n, m, free) = (r.n, r.m, r.m - r.held.len());
    change.clear(m);
    for (i, dz) in change.dq.iter_mut().enumerate().take(free) {
        *dz = weight * r.basis[i * n + dof];
    }
    factor.solve_in_place(&mut change.dq);
    for i in 0..m {
        change.da[i] = change.dq[i] / (beta * h * h);
        change.dv[i] = gamma / (beta * h) * change.dq[i];
    }
}
