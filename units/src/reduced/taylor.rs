//! The Taylor basis with N unknowns (seed 002's TRBF idea, P3 sec. 3): the
//! displacement is the second-order Taylor expansion in the modal coordinates,
//! V(s) = Phi_L s + Phi_H s_H(s), s_H = [s1 s1, s2 s1, s2 s2, s3 s1, ...] and
//! Phi_H's columns the modal derivatives x_ii and 2 x_ij. Only the N modal
//! coordinates are unknowns; the derivatives follow them. With U(s) = d s_T / d s
//! (s_T = [s; s_H]) and J = Phi_T U, virtual work gives
//!
//! (U^T m U) s'' = U^T (Phi_T^T F - Phi_T^T g(V) - m [0; q(s')]),
//!
//! m = Phi_T^T M Phi_T and q_ij = 2 s'_i s'_j (the part of d2 s_H / dt2 without
//! s''). Linearised at s = 0 only the N modes remain, so central differences are
//! stable up to about 2 / omega_N, where the linear basis with the same columns
//! is limited by the derivatives' far higher frequencies (seed 002 P3 Fig. 7).
//!
//! Beyond the source, Phi_T^T g(V) is evaluated through the elements (the exact
//! projection, or a trained sample: [`SampledForce`]) instead of the degree-6
//! polynomial tensors, whose size grows as C(N + 6, 6).
//!
//! Stepping: explicit, velocity-Verlet form with the state's mass solved every
//! step (N x N, Cholesky); the velocity terms see the half-step velocity. A
//! step allocates nothing (its buffers are sized once).

use super::ecsw::SampledForce;
use super::polynomial::CubicSection;
use crate::contract::UnitError;
use nalgebra::{DMatrix, DVector};

/// A section on a Taylor basis, and its motion.
pub struct TaylorSection {
    /// Phi_T = [Phi_L, Phi_H] (free DOFs x N_S).
    basis: DMatrix<f64>,
    /// Phi_T^T M Phi_T.
    mass: DMatrix<f64>,
    force: SampledForce,
    /// Sorted pairs (i >= j) of s_H, in column order of Phi_H.
    pairs: Vec<[usize; 2]>,
    n: usize,
    s: DVector<f64>,
    v: DVector<f64>,
    a: DVector<f64>,
    work: Work,
}

/// A step's buffers, sized once: a step allocates nothing.
struct Work {
    /// s_T at the step's end, and the velocity terms' [0; q].
    st: DVector<f64>,
    q: DVector<f64>,
    g: Vec<f64>,
    /// U (N_S x N), m U, U^T m U (its Cholesky factor after a solve).
    u: DMatrix<f64>,
    mu: DMatrix<f64>,
    reduced: DMatrix<f64>,
    rhs: DVector<f64>,
    v_half: DVector<f64>,
    s1: DVector<f64>,
    a1: DVector<f64>,
}

impl TaylorSection {
    /// The Taylor basis of the `modes` (free DOFs x N) and their derivative
    /// columns `derivatives` (x_ii and 2 x_ij in s_H's order), with the force of
    /// every element, at rest.
    pub fn new(
        section: &CubicSection,
        modes: &DMatrix<f64>,
        derivatives: &DMatrix<f64>,
    ) -> Result<TaylorSection, UnitError> {
        let none = DMatrix::zeros(modes.nrows(), 0);
        TaylorSection::with_static_columns(section, modes, derivatives, &none)
    }

    /// The same with further linear coordinates that carry no derivatives
    /// (`statics`, free DOFs x R: attachment vectors at loaded ends, whose
    /// coupling with the modes the elements' force still holds exactly): N =
    /// modes + R unknowns, s_H from the modal coordinates only.
    pub fn with_static_columns(
        section: &CubicSection,
        modes: &DMatrix<f64>,
        derivatives: &DMatrix<f64>,
        statics: &DMatrix<f64>,
    ) -> Result<TaylorSection, UnitError> {
        let carried = modes.ncols();
        let n = carried + statics.ncols();
        let pairs: Vec<[usize; 2]> = (0..carried)
            .flat_map(|i| (0..=i).map(move |j| [i, j]))
            .collect();
        let ns = n + pairs.len();
        if derivatives.ncols() != pairs.len()
            || derivatives.nrows() != modes.nrows()
            || statics.nrows() != modes.nrows()
        {
            return Err(UnitError::parameter(
                "derivatives",
                derivatives.ncols(),
                &format!(
                    "expected N (N + 1) / 2 = {} columns of {} DOFs",
                    pairs.len(),
                    modes.nrows()
                ),
            ));
        }
        let mut basis = DMatrix::zeros(modes.nrows(), ns);
        basis.columns_mut(0, carried).copy_from(modes);
        basis
            .columns_mut(carried, statics.ncols())
            .copy_from(statics);
        basis.columns_mut(n, pairs.len()).copy_from(derivatives);
        let force = SampledForce::all(section, &basis);
        Ok(TaylorSection {
            mass: basis.transpose() * &section.mass * &basis,
            force,
            basis,
            pairs,
            n,
            s: DVector::zeros(n),
            v: DVector::zeros(n),
            a: DVector::zeros(n),
            work: Work {
                st: DVector::zeros(ns),
                q: DVector::zeros(ns),
                g: vec![0.0; ns],
                u: DMatrix::zeros(ns, n),
                mu: DMatrix::zeros(ns, n),
                reduced: DMatrix::zeros(n, n),
                rhs: DVector::zeros(ns),
                v_half: DVector::zeros(n),
                s1: DVector::zeros(n),
                a1: DVector::zeros(n),
            },
        })
    }

    /// Number of unknowns N.
    pub fn size(&self) -> usize {
        self.n
    }

    /// Phi_T^T f: a load on the free DOFs in the basis (N_S values).
    pub fn project(&self, f: &DVector<f64>) -> DVector<f64> {
        self.basis.tr_mul(f)
    }

    /// The same into `out` (sized as the basis's columns), allocating nothing.
    pub fn project_into(&self, f: &DVector<f64>, out: &mut DVector<f64>) {
        self.basis.tr_mul_to(f, out);
    }

    /// The modal coordinates s.
    pub fn coordinates(&self) -> &DVector<f64> {
        &self.s
    }

    /// Coordinates, velocities and accelerations (for saving a state).
    pub fn motion(&self) -> [&[f64]; 3] {
        [self.s.as_slice(), self.v.as_slice(), self.a.as_slice()]
    }

    /// Sets the motion (restoring a saved state).
    pub fn set_motion(&mut self, s: &[f64], v: &[f64], a: &[f64]) {
        self.s.copy_from_slice(s);
        self.v.copy_from_slice(v);
        self.a.copy_from_slice(a);
    }

    /// Basis size N_S = N + M (M + 1) / 2 (M the modes carrying derivatives).
    pub fn basis_size(&self) -> usize {
        self.n + self.pairs.len()
    }

    /// The displacements and velocities on the free DOFs into `d` and `v`,
    /// allocating nothing (the step's buffers are used).
    pub fn displacements_and_velocities_into(
        &mut self,
        d: &mut DVector<f64>,
        v: &mut DVector<f64>,
    ) {
        let w = &mut self.work;
        expand(&self.pairs, self.n, &self.s, &mut w.st);
        d.gemv(1.0, &self.basis, &w.st, 0.0);
        jacobian(&self.pairs, self.n, &self.s, &mut w.u);
        w.u.mul_to(&self.v, &mut w.q);
        v.gemv(1.0, &self.basis, &w.q, 0.0);
    }

    /// The accelerations V'' = Phi_T (U s'' + [0; q(s')]) on the free DOFs
    /// into `out`, allocating nothing.
    pub fn accelerations_into(&mut self, out: &mut DVector<f64>) {
        let (n, w) = (self.n, &mut self.work);
        jacobian(&self.pairs, n, &self.s, &mut w.u);
        w.u.mul_to(&self.a, &mut w.q);
        for (p, &[i, j]) in self.pairs.iter().enumerate() {
            w.q[n + p] += 2.0 * self.v[i] * self.v[j];
        }
        out.gemv(1.0, &self.basis, &w.q, 0.0);
    }

    /// The displacements V(s) on the free DOFs.
    pub fn displacements(&self) -> DVector<f64> {
        let mut st = DVector::zeros(self.n + self.pairs.len());
        expand(&self.pairs, self.n, &self.s, &mut st);
        &self.basis * st
    }

    /// The acceleration at the work's s1 with velocity v_half into a1, under
    /// the projected load `load` (N_S values).
    fn acceleration(&mut self, load: &DVector<f64>) -> Result<(), UnitError> {
        let (n, w) = (self.n, &mut self.work);
        expand(&self.pairs, n, &w.s1, &mut w.st);
        jacobian(&self.pairs, n, &w.s1, &mut w.u);
        self.force.force(w.st.as_slice(), &mut w.g, None);
        w.q.fill(0.0);
        for (p, &[i, j]) in self.pairs.iter().enumerate() {
            w.q[n + p] = 2.0 * w.v_half[i] * w.v_half[j];
        }
        // rhs = load - g - m q.
        w.rhs.copy_from(load);
        for (r, g) in w.rhs.iter_mut().zip(&w.g) {
            *r -= g;
        }
        w.rhs.gemv(-1.0, &self.mass, &w.q, 1.0);
        self.mass.mul_to(&w.u, &mut w.mu);
        w.u.tr_mul_to(&w.mu, &mut w.reduced);
        w.u.tr_mul_to(&w.rhs, &mut w.a1);
        let factor = nalgebra::Cholesky::new(std::mem::take(&mut w.reduced)).ok_or_else(|| {
            UnitError::Numerical("Taylor basis: the reduced mass is not positive definite".into())
        })?;
        factor.solve_mut(&mut w.a1);
        w.reduced = factor.unpack();
        Ok(())
    }

    /// Sets the acceleration that balances the projected load `load` (N_S
    /// values) at the current coordinates and velocities (the start of a run).
    pub fn set_initial_acceleration(&mut self, load: &DVector<f64>) -> Result<(), UnitError> {
        self.work.s1.copy_from(&self.s);
        self.work.v_half.copy_from(&self.v);
        self.acceleration(load)?;
        self.a.copy_from(&self.work.a1);
        Ok(())
    }

    /// One central-difference step of `h` seconds, `load1` the projected load
    /// at the step's end (N_S values).
    pub fn step(&mut self, h: f64, load1: &DVector<f64>) -> Result<(), UnitError> {
        let w = &mut self.work;
        w.v_half.copy_from(&self.v);
        w.v_half.axpy(0.5 * h, &self.a, 1.0);
        w.s1.copy_from(&self.s);
        w.s1.axpy(h, &w.v_half, 1.0);
        self.acceleration(load1)?;
        let w = &mut self.work;
        w.v_half.axpy(0.5 * h, &w.a1, 1.0);
        if !(w.s1.iter().chain(w.v_half.iter()).all(|x| x.is_finite())) {
            return Err(UnitError::Numerical(format!(
                "Taylor basis: central differences became non-finite (is h = {h} s below 2 / omega_N?)"
            )));
        }
        self.s.copy_from(&w.s1);
        self.v.copy_from(&w.v_half);
        self.a.copy_from(&w.a1);
        Ok(())
    }
}

/// s_T = [s; s_H(s)] into `st`.
fn expand(pairs: &[[usize; 2]], n: usize, s: &DVector<f64>, st: &mut DVector<f64>) {
    st.rows_mut(0, n).copy_from(s);
    for (p, [i, j]) in pairs.iter().enumerate() {
        st[n + p] = s[*i] * s[*j];
    }
}

/// U(s) = d s_T / d s (N_S x N) into `u`.
fn jacobian(pairs: &[[usize; 2]], n: usize, s: &DVector<f64>, u: &mut DMatrix<f64>) {
    u.fill(0.0);
    for k in 0..n {
        u[(k, k)] = 1.0;
    }
    for (p, &[i, j]) in pairs.iter().enumerate() {
        u[(n + p, i)] += s[j];
        u[(n + p, j)] += s[i];
    }
}
