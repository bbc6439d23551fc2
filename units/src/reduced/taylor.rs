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
//! step (N x N, Cholesky); the velocity terms see the half-step velocity.

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
    // Scratch.
    st: DVector<f64>,
    g: Vec<f64>,
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
        let n = modes.ncols();
        let pairs: Vec<[usize; 2]> = (0..n).flat_map(|i| (0..=i).map(move |j| [i, j])).collect();
        if derivatives.ncols() != pairs.len() || derivatives.nrows() != modes.nrows() {
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
        let mut basis = DMatrix::zeros(modes.nrows(), n + pairs.len());
        basis.columns_mut(0, n).copy_from(modes);
        basis.columns_mut(n, pairs.len()).copy_from(derivatives);
        let force = SampledForce::all(section, &basis);
        Ok(TaylorSection {
            mass: basis.transpose() * &section.mass * &basis,
            force,
            st: DVector::zeros(n + pairs.len()),
            g: vec![0.0; n + pairs.len()],
            basis,
            pairs,
            n,
            s: DVector::zeros(n),
            v: DVector::zeros(n),
            a: DVector::zeros(n),
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

    /// The modal coordinates s.
    pub fn coordinates(&self) -> &DVector<f64> {
        &self.s
    }

    /// The displacements V(s) on the free DOFs.
    pub fn displacements(&self) -> DVector<f64> {
        &self.basis * self.expanded(&self.s)
    }

    /// s_T = [s; s_H(s)].
    fn expanded(&self, s: &DVector<f64>) -> DVector<f64> {
        let mut st = DVector::zeros(self.n + self.pairs.len());
        st.rows_mut(0, self.n).copy_from(s);
        for (p, [i, j]) in self.pairs.iter().enumerate() {
            st[self.n + p] = s[*i] * s[*j];
        }
        st
    }

    /// U(s) = d s_T / d s (N_S x N).
    fn jacobian(&self, s: &DVector<f64>) -> DMatrix<f64> {
        let mut u = DMatrix::zeros(self.n + self.pairs.len(), self.n);
        for k in 0..self.n {
            u[(k, k)] = 1.0;
        }
        for (p, &[i, j]) in self.pairs.iter().enumerate() {
            u[(self.n + p, i)] += s[j];
            u[(self.n + p, j)] += s[i];
        }
        u
    }

    /// The acceleration at coordinates `s`, velocity `v`, under the projected
    /// load `load` (N_S values).
    fn acceleration(
        &mut self,
        s: &DVector<f64>,
        v: &DVector<f64>,
        load: &DVector<f64>,
    ) -> Result<DVector<f64>, UnitError> {
        let u = self.jacobian(s);
        self.st = self.expanded(s);
        self.force.force(self.st.as_slice(), &mut self.g, None);
        let mut rhs = load - DVector::from_column_slice(&self.g);
        let mut q = DVector::zeros(self.n + self.pairs.len());
        for (p, &[i, j]) in self.pairs.iter().enumerate() {
            q[self.n + p] = 2.0 * v[i] * v[j];
        }
        rhs -= &self.mass * q;
        let m = u.transpose() * &self.mass * &u;
        m.cholesky()
            .map(|c| c.solve(&u.tr_mul(&rhs)))
            .ok_or_else(|| {
                UnitError::Numerical(
                    "Taylor basis: the reduced mass is not positive definite".into(),
                )
            })
    }

    /// One central-difference step of `h` seconds, `load1` the projected load
    /// at the step's end (N_S values).
    pub fn step(&mut self, h: f64, load1: &DVector<f64>) -> Result<(), UnitError> {
        let v_half = &self.v + &self.a * (0.5 * h);
        let s1 = &self.s + &v_half * h;
        let a1 = self.acceleration(&s1, &v_half, load1)?;
        let v1 = v_half + &a1 * (0.5 * h);
        if !(s1.iter().chain(v1.iter()).all(|x| x.is_finite())) {
            return Err(UnitError::Numerical(format!(
                "Taylor basis: central differences became non-finite (is h = {h} s below 2 / omega_N?)"
            )));
        }
        self.s = s1;
        self.v = v1;
        self.a = a1;
        Ok(())
    }
}
