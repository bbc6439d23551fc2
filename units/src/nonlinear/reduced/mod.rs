//! The section reduced about its start state (`reduced_modes = N`): the cheap
//! fidelity of a section that starts from its static equilibrium (a mooring
//! line's lower part, an S-lay's laid pipe, a riser's sag bend), where seed
//! 002's reduction about the stress-free state does not apply.
//!
//! At `initialize`, after the static solve, the displacements are written
//! q = q_s + T z over a basis T formed once from the tangent stiffness K_t
//! (elements and seabed springs) and the mass M there:
//! - the N lowest modes of (K_t, M) with the held DOFs fixed;
//! - an attachment vector K_t^-1 e_j per end DOF loaded by a force (the
//!   static response to a coupled end force, which modes alone converge to
//!   slowly);
//! - a constraint mode per held DOF (1 there, the quasi-static response of
//!   the rest): its coordinate is that DOF's prescribed or coupled motion, so
//!   an end driven by a vessel or a neighbour moves the section exactly.
//!
//! The restoring force is evaluated through every element at q_s + T z
//! (co-rotational elements, drag, seabed contact: nothing is linearised) and
//! projected, g_r = T^T g; HHT-alpha steps the m = N + attachments + held
//! coordinates with Newton on the projected tangent, frozen at its start value
//! for the first iterations of a step and formed anew at the iterate after
//! that. The outputs (end forces as the balance at the held DOFs, stations,
//! touchdown) are the full section's at the reconstructed state. With every
//! mode the basis spans the whole space and the section is its full model.
//! Not reduced: the cost of the element loop (no hyper-reduction yet). Its
//! step Jacobian is exact at the step's end ([`jacobian`]).

mod basis;
mod checks;
mod jacobian;
mod products;
mod sampled;

pub(super) use checks::validate;
pub use sampled::Sampling;

use super::NonlinearSection;
use super::params::Integrator;
use crate::contract::UnitError;
use crate::integrators::hht::{
    HhtAlpha, Matrices, NewtonSettings, SecondOrderSystem, StepLoads, TangentScales,
};
use crate::numerics::banded::{BandLdlt, SymmetricBand};
use products::{column_largest, project, times, transpose_times};
use sampled::Hyper;

/// Newton iterations of a step on the tangent frozen at the start state
/// before the tangent is formed at each iterate.
const FROZEN_ITERATIONS: u32 = 8;

/// The Newton tangent of an iterate: the full one formed there (already
/// scaled, to project), the sample's (already projected into the work
/// buffer), or the frozen one.
enum Tangent {
    Full(SymmetricBand),
    Projected,
    Frozen,
}

/// A step's full loads at its start and end, and its held DOFs' motion
/// (DOF, [q, v, a]).
type FullLoads<'a> = (&'a [f64], &'a [f64], &'a [(usize, [f64; 3])]);

/// The basis and the reduced system's constant parts.
pub(super) struct Reduction {
    /// T, n x m column-major: free columns first, then one constraint column
    /// per held DOF.
    basis: Vec<f64>,
    n: usize,
    m: usize,
    /// The held DOF of each constraint coordinate (coordinates free..m).
    held: Vec<usize>,
    /// The largest |entry| of each column of T: a bound of a correction's
    /// full size without forming it.
    column_largest: Vec<f64>,
    /// q_s: the displacements the basis is formed at (m, rad).
    start: Vec<f64>,
    /// T^T M T and T^T C T (banded as dense, half-bandwidth m - 1).
    mass: SymmetricBand,
    damping: Option<SymmetricBand>,
    /// T^T K_t T and T^T C_t T (the drag's tangent damping, in a current
    /// not zero at rest) at the start state: the frozen Newton tangent.
    stiffness: Vec<f64>,
    drag_damping: Vec<f64>,
    hht: HhtAlpha,
    /// The forces through sampled terms (`reduced_sampling`): training, or
    /// trained.
    hyper: Option<Hyper>,
    work: Work,
    jacobian: jacobian::JacobianBuffers,
}

/// Buffers of a reduced step.
#[derive(Default)]
struct Work {
    q: Vec<f64>,
    v: Vec<f64>,
    full: Vec<f64>,
    /// The full tangent and T times it, column by column.
    tangent: Option<SymmetricBand>,
    tangent_times_basis: Vec<f64>,
    /// The projected Newton tangent at the iterate (m x m).
    projected: Vec<f64>,
    f0: Vec<f64>,
    f1: Vec<f64>,
    g0: Vec<f64>,
    held: Vec<(usize, [f64; 3])>,
    motion: [Vec<f64>; 3],
    iteration: u32,
    /// Whether the last tangent added was the frozen one.
    frozen: bool,
    /// A Newton correction in the full DOFs (`limit_correction` has `&self`).
    correction: std::cell::RefCell<Vec<f64>>,
}

impl NonlinearSection {
    /// Before a step of a reduced section: the basis about the start, formed
    /// the first time, and the reduced start where the state has none (the
    /// first step, or a step from a state saved before it).
    pub(super) fn ensure_reduced(&mut self) -> Result<(), UnitError> {
        if self.params.reduced_modes.is_none() {
            return Ok(());
        }
        if self.reduction.is_none() {
            // About the start, whatever state was restored since.
            let mut origin = self.reduced_origin.take().ok_or_else(|| {
                UnitError::State("a reduced section stepped before it was initialised".into())
            })?;
            std::mem::swap(&mut self.state, &mut origin);
            let formed = self.reduce();
            std::mem::swap(&mut self.state, &mut origin);
            self.reduced_origin = Some(origin);
            formed?;
        }
        if self.state.reduced.is_empty() {
            let mut rhs = self.reduced_start_rhs.clone();
            self.reduced_start(&mut rhs)?;
        }
        Ok(())
    }

    /// Forms the basis about the current state (after the statics), with `m`
    /// and `c` the dynamics' mass and damping.
    pub(super) fn reduce(&mut self) -> Result<(), UnitError> {
        self.reduction = None;
        let Some(count) = self.params.reduced_modes else {
            return Ok(());
        };
        self.check_reduced_size()?;
        let n = self.model.dofs();
        let held = self.held_dofs();
        let k = self.tangent_stiffness();
        let basis = basis::columns(self, &k, count, &held)?;
        let m = basis.len() / n;
        let project = |b: &SymmetricBand| {
            let mut out = Vec::new();
            project(&basis, (n, m), b, &mut Vec::new(), &mut out);
            out
        };
        let band = |dense: Vec<f64>| {
            let mut out = SymmetricBand::zeros(m, m - 1);
            for i in 0..m {
                for j in i..m {
                    out.add(i, j, dense[i * m + j]);
                }
            }
            out
        };
        let mass = band(project(&self.m));
        let damping = self.c.as_ref().map(|c| band(project(c)));
        let stiffness = project(&k);
        let mut drag = SymmetricBand::zeros(n, super::model::BAND);
        self.add_drag_damping(&mut drag, &mut Vec::new());
        let drag_damping = project(&drag);
        let alpha = match self.params.integrator {
            Integrator::Hht { alpha, .. } => alpha,
            _ => 0.0,
        };
        self.reduction = Some(Box::new(Reduction {
            n,
            m,
            held,
            start: self.state.q.clone(),
            mass,
            damping,
            stiffness,
            drag_damping,
            hht: HhtAlpha::new(alpha, m, m - 1),
            hyper: (self.params.reduced_sampling.as_ref()).map(|p| Hyper::new(p, self.state.t)),
            work: Work::default(),
            jacobian: jacobian::JacobianBuffers::default(),
            column_largest: column_largest(&basis, (n, m)),
            basis,
        }));
        Ok(())
    }

    /// The reduced coordinates of the current state's held DOFs (the free ones
    /// zero: the start) and the accelerations from `rhs` (f - C v - g, the
    /// held accelerations at the held DOFs); the state then follows them.
    /// Called at the start, after the held DOFs are set; false when the
    /// section is not reduced.
    pub(super) fn reduced_start(&mut self, rhs: &mut [f64]) -> Result<bool, UnitError> {
        let Some(r) = self.reduction.as_deref() else {
            return Ok(false);
        };
        let (n, m, free) = (r.n, r.m, r.m - r.held.len());
        let mut z = vec![0.0; 3 * m];
        // rhs: f - C v - g, with the held accelerations at the held DOFs.
        let mut accelerations = vec![0.0; m];
        for (j, &d) in r.held.iter().enumerate() {
            z[free + j] = self.state.q[d] - r.start[d];
            z[m + free + j] = self.state.v[d];
            accelerations[free + j] = rhs[d];
            rhs[d] = 0.0;
        }
        let mut projected = vec![0.0; m];
        transpose_times(&r.basis, (n, m), rhs, &mut projected);
        let mut mass = r.mass.clone();
        for j in free..m {
            mass.set_identity_row(j);
            projected[j] = accelerations[j];
        }
        let factor = BandLdlt::new(&mass).ok_or_else(|| {
            UnitError::Numerical("reduced section: the reduced mass is singular".into())
        })?;
        // Held accelerations are zero at rest here, as for the full section.
        factor.solve_in_place(&mut projected);
        z[2 * m..].copy_from_slice(&projected);
        self.state.reduced = z;
        self.expand_reduced();
        Ok(true)
    }

    /// With `reduced_sampling`, once trained: the terms in the sample and
    /// the terms it was picked from (elements, and nodes on a contact
    /// surface).
    pub fn sample_size(&self) -> Option<(usize, usize)> {
        self.reduction.as_ref()?.hyper.as_ref()?.size()
    }

    /// The coordinates a step solves for: the reduced ones, or the
    /// displacements of the full section.
    pub(super) fn stepped_coordinates(&self) -> &[f64] {
        match &self.reduction {
            Some(r) => &self.state.reduced[..r.m],
            None => &self.state.q,
        }
    }

    /// q = q_s + T z, v = T z', a = T z'' from the state's reduced coordinates.
    fn expand_reduced(&mut self) {
        let Some(r) = self.reduction.as_deref() else {
            return;
        };
        let m = r.m;
        let z = &self.state.reduced;
        self.state.q.copy_from_slice(&r.start);
        times(&r.basis, (r.n, m), &z[..m], &mut self.state.q);
        self.state.v.fill(0.0);
        times(&r.basis, (r.n, m), &z[m..2 * m], &mut self.state.v);
        self.state.a.fill(0.0);
        times(&r.basis, (r.n, m), &z[2 * m..], &mut self.state.a);
    }

    /// A step's loads projected, the reduced restoring force at its start
    /// (t0, s; the sample's once trained), its held coordinates' motion and
    /// its start motion, into `r`'s buffers.
    fn reduced_loads(&self, r: &mut Reduction, (f0, f1, held): FullLoads<'_>, t0: f64) {
        let (n, m, free) = (r.n, r.m, r.m - r.held.len());
        let w = &mut r.work;
        for (out, full) in [(&mut w.f0, f0), (&mut w.f1, f1)] {
            out.resize(m, 0.0);
            transpose_times(&r.basis, (n, m), full, out);
        }
        w.g0.resize(m, 0.0);
        let z = &self.state.reduced;
        match r.hyper.as_mut() {
            Some(Hyper::Sampled(sample)) => {
                sample.force(self, (&z[..m], &z[m..2 * m], t0), 1.0, None, &mut w.g0);
            }
            _ => transpose_times(&r.basis, (n, m), &self.state.force, &mut w.g0),
        }
        w.held.clear();
        for &(d, [q, v, a]) in held {
            if let Some(j) = r.held.iter().position(|&h| h == d) {
                w.held.push((free + j, [q - r.start[d], v, a]));
            }
        }
        for (k, part) in w.motion.iter_mut().enumerate() {
            part.clear();
            part.extend_from_slice(&z[k * m..(k + 1) * m]);
        }
        w.iteration = 0;
    }

    /// One HHT-alpha step of the reduced coordinates under the full loads
    /// `f0`, `f1` and held motions `held` (absolute, per held DOF).
    pub(super) fn reduced_step(
        &mut self,
        (f0, f1, held): FullLoads<'_>,
        (t0, t1, h): (f64, f64, f64),
        newton: NewtonSettings,
    ) -> Result<u32, UnitError> {
        let Some(mut r) = self.reduction.take() else {
            return Err(UnitError::Numerical(
                "reduced section stepped before its basis was formed".into(),
            ));
        };
        if let Err(e) = self.advance_sampling(&mut r, t0, h) {
            self.reduction = Some(r);
            return Err(e);
        }
        self.reduced_loads(&mut r, (f0, f1, held), t0);
        let m = r.m;
        let mut hht = std::mem::take(&mut r.hht);
        let (f0, f1, g0, held) = (
            std::mem::take(&mut r.work.f0),
            std::mem::take(&mut r.work.f1),
            std::mem::take(&mut r.work.g0),
            std::mem::take(&mut r.work.held),
        );
        let loads = StepLoads {
            t0,
            t1,
            h,
            f0: &f0,
            f1: &f1,
            g0: Some(&g0),
            held: &held,
        };
        let result = hht.step(
            &mut ReducedSystem {
                section: &*self,
                reduction: &mut r,
            },
            &loads,
            newton,
        );
        r.hht = hht;
        (r.work.f0, r.work.f1, r.work.g0, r.work.held) = (f0, f1, g0, held);
        if result.is_ok() {
            let z = &mut self.state.reduced;
            for (k, part) in r.work.motion.iter().enumerate() {
                z[k * m..(k + 1) * m].copy_from_slice(part);
            }
        }
        self.reduction = Some(r);
        if result.is_ok() {
            self.expand_reduced();
        }
        result
    }
}

impl Reduction {
    /// The first Newton iterate of the next step (reduced coordinates).
    pub(super) fn guess_next(&mut self, z: &[f64]) {
        self.hht.guess_next(z);
    }
}

/// The reduced section as the integrator steps it.
struct ReducedSystem<'a> {
    section: &'a NonlinearSection,
    reduction: &'a mut Reduction,
}

impl SecondOrderSystem for ReducedSystem<'_> {
    fn label(&self) -> &str {
        "reduced section"
    }

    fn matrices(&self) -> Matrices<'_> {
        Matrices {
            mass: &self.reduction.mass,
            damping: self.reduction.damping.as_ref(),
            stiffness: None,
            varies: false,
        }
    }

    fn motion(&self) -> [&[f64]; 3] {
        let [q, v, a] = &self.reduction.work.motion;
        [q, v, a]
    }

    fn motion_mut(&mut self) -> [&mut [f64]; 3] {
        let [q, v, a] = &mut self.reduction.work.motion;
        [q, v, a]
    }

    fn is_linear(&self) -> bool {
        false
    }

    fn tangent_is_frozen(&self) -> bool {
        self.reduction.work.frozen
    }

    /// As the full section: a correction moving a node by more than the
    /// shortest element or turning it by more than 0.5 rad is scaled down.
    fn limit_correction(&self, dz: &mut [f64]) -> f64 {
        let r = &*self.reduction;
        let bound: f64 = dz
            .iter()
            .zip(&r.column_largest)
            .map(|(d, t)| d.abs() * t)
            .sum();
        if self.section.model.surely_within_correction_limit(bound) {
            return 1.0;
        }
        let mut dq = r.work.correction.borrow_mut();
        dq.clear();
        dq.resize(r.n, 0.0);
        times(&r.basis, (r.n, r.m), dz, &mut dq);
        let factor = self.section.model.correction_limit(&dq);
        if factor < 1.0 {
            dz.iter_mut().for_each(|d| *d *= factor);
        }
        factor
    }

    /// The reduced force at (z, z'): through the sample once trained, else
    /// the full force at q_s + T z, v = T z' projected; the tangent frozen at
    /// the start for the first iterations, then formed at the iterate.
    fn nonlinear_force(
        &mut self,
        z: &[f64],
        zv: &[f64],
        t: f64,
        tangent: Option<(&mut SymmetricBand, TangentScales)>,
        force: &mut Vec<f64>,
    ) {
        let r = &mut *self.reduction;
        let scales = tangent.as_ref().map(|(_, s)| *s);
        let scale = scales.map_or(1.0, |s| s.stiffness);
        r.work.iteration += u32::from(tangent.is_some());
        let fresh = scales.filter(|_| r.work.iteration > FROZEN_ITERATIONS);
        r.work.frozen = tangent.is_some() && fresh.is_none();
        force.resize(r.m, 0.0);
        let formed = match r.hyper.as_mut() {
            Some(Hyper::Sampled(sample)) => {
                let projected = fresh.map(|f| (f, &mut r.work.projected));
                sample.force(self.section, (z, zv, t), scale, projected, force);
                match fresh {
                    Some(_) => Tangent::Projected,
                    None => Tangent::Frozen,
                }
            }
            _ => match r.full_force(self.section, (z, zv, t), (scale, fresh), force) {
                Some(k) => Tangent::Full(k),
                None => Tangent::Frozen,
            },
        };
        if let Some((band, scales)) = tangent {
            r.add_tangent(band, scales, formed);
        }
    }
}

impl Reduction {
    /// `scale` times the full force at q_s + T z, v = T z' (time t, s)
    /// projected into `force`; with `fresh`, the full tangent at the iterate
    /// with its scales.
    fn full_force(
        &mut self,
        s: &NonlinearSection,
        (z, zv, t): (&[f64], &[f64], f64),
        (scale, fresh): (f64, Option<TangentScales>),
        force: &mut [f64],
    ) -> Option<SymmetricBand> {
        let (n, m) = (self.n, self.m);
        let w = &mut self.work;
        w.q.clone_from(&self.start);
        times(&self.basis, (n, m), z, &mut w.q);
        w.v.clear();
        w.v.resize(n, 0.0);
        times(&self.basis, (n, m), zv, &mut w.v);
        w.full.clear();
        w.full.resize(n, 0.0);
        let mut full_tangent = fresh.map(|_| {
            let mut k = w
                .tangent
                .take()
                .unwrap_or_else(|| SymmetricBand::zeros(n, super::model::BAND));
            k.fill_zero();
            k
        });
        s.model.add_internal_force(
            &w.q,
            scale,
            full_tangent
                .as_mut()
                .zip(fresh)
                .map(|(k, f)| (k, f.stiffness)),
            &mut w.full,
        );
        if !s.environment.is_empty() {
            s.environment.add_force(
                &s.model,
                (&w.q, &w.v, t),
                &s.state.lambda,
                scale,
                true,
                full_tangent
                    .as_mut()
                    .zip(fresh)
                    .map(|(k, f)| (k, f.stiffness, f.damping)),
                &mut w.full,
            );
        }
        transpose_times(&self.basis, (n, m), &w.full, force);
        full_tangent
    }

    /// Adds the projected Newton tangent to `band`: the full tangent formed
    /// at the iterate, projected; the sample's, already in `work.projected`;
    /// or the frozen one.
    fn add_tangent(&mut self, band: &mut SymmetricBand, scales: TangentScales, formed: Tangent) {
        let (n, m) = (self.n, self.m);
        let w = &mut self.work;
        match formed {
            Tangent::Projected => {}
            Tangent::Full(k) => {
                project(
                    &self.basis,
                    (n, m),
                    &k,
                    &mut w.tangent_times_basis,
                    &mut w.projected,
                );
                w.tangent = Some(k);
            }
            Tangent::Frozen => {
                w.projected.clear();
                let frozen = self.stiffness.iter().zip(&self.drag_damping);
                (w.projected)
                    .extend(frozen.map(|(k, c)| scales.stiffness * k + scales.damping * c));
            }
        }
        for i in 0..m {
            for j in i..m {
                band.add(i, j, w.projected[i * m + j]);
            }
        }
    }
}
