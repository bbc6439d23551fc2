//! A reduced section as a [`SecondOrderSystem`]: m s'' + g~(s) = Phi^T F(t) on
//! the coordinates s of a basis Phi, so the shared integrators (central
//! differences, HHT-alpha) step it as they step the full section. m = Phi^T M
//! Phi is dense (a full band). The restoring force comes from the reduced
//! tensors (Q1 as the stiffness matrix, the rest as the nonlinear force) or from
//! sampled elements (all of it nonlinear).

use super::ecsw::SampledForce;
use super::lrbf::ReducedForce;
use super::polynomial::CubicSection;
use crate::contract::UnitError;
use crate::integrators::hht::{Matrices, SecondOrderSystem, TangentScales, motion_fields};
use crate::numerics::banded::SymmetricBand;
use nalgebra::{DMatrix, DVector};

/// How a reduced section evaluates its restoring force.
pub enum RestoringForce {
    /// Global reduced tensors (seed 002's RBF): cost about N^4 / 6.
    Tensors(ReducedForce),
    /// Sampled, weighted elements (ECSW): cost about 12 N per element.
    Sampled(SampledForce),
}

/// The reduced model and its motion.
pub struct ReducedSection {
    basis: DMatrix<f64>,
    force: RestoringForce,
    mass: SymmetricBand,
    /// Q1 with the reduced tensors; none with sampled elements.
    stiffness: Option<SymmetricBand>,
    q: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
}

/// A dense symmetric matrix as a full band.
fn full_band(m: &DMatrix<f64>) -> SymmetricBand {
    let n = m.nrows();
    let mut band = SymmetricBand::zeros(n, n.saturating_sub(1));
    for i in 0..n {
        for j in 0..=i {
            band.add(i, j, 0.5 * (m[(i, j)] + m[(j, i)]));
        }
    }
    band
}

impl ReducedSection {
    /// The reduction of `section` on the columns of `basis` (free DOFs x N) by
    /// reduced tensors, at rest in its stress-free state.
    pub fn new(section: &CubicSection, basis: DMatrix<f64>) -> ReducedSection {
        let force = ReducedForce::new(section, &basis);
        let stiffness = Some(full_band(&force.q1));
        ReducedSection::with(section, basis, RestoringForce::Tensors(force), stiffness)
    }

    /// The same with the restoring force of sampled elements.
    pub fn sampled(
        section: &CubicSection,
        basis: DMatrix<f64>,
        force: SampledForce,
    ) -> ReducedSection {
        ReducedSection::with(section, basis, RestoringForce::Sampled(force), None)
    }

    fn with(
        section: &CubicSection,
        basis: DMatrix<f64>,
        force: RestoringForce,
        stiffness: Option<SymmetricBand>,
    ) -> ReducedSection {
        let n = basis.ncols();
        ReducedSection {
            mass: full_band(&(basis.transpose() * &section.mass * &basis)),
            stiffness,
            force,
            basis,
            q: vec![0.0; n],
            v: vec![0.0; n],
            a: vec![0.0; n],
        }
    }

    /// Number of coordinates N.
    pub fn size(&self) -> usize {
        self.q.len()
    }

    /// The basis Phi (free DOFs x N).
    pub fn basis(&self) -> &DMatrix<f64> {
        &self.basis
    }

    /// Phi^T f: a load on the free DOFs as the reduced load.
    pub fn project(&self, f: &DVector<f64>) -> DVector<f64> {
        self.basis.tr_mul(f)
    }

    /// The same into `out` (sized as the basis's columns), allocating nothing.
    pub fn project_into(&self, f: &DVector<f64>, out: &mut DVector<f64>) {
        self.basis.tr_mul_to(f, out);
    }

    /// The coordinates s at the current time.
    pub fn coordinates(&self) -> &[f64] {
        &self.q
    }

    /// The displacements Phi s on the free DOFs.
    pub fn displacements(&self) -> DVector<f64> {
        &self.basis * DVector::from_column_slice(&self.q)
    }

    /// The displacements and velocities Phi s, Phi s' on the free DOFs into
    /// `d` and `v`, allocating nothing.
    pub fn displacements_and_velocities_into(&self, d: &mut DVector<f64>, v: &mut DVector<f64>) {
        self.basis_times(&self.q, d);
        self.basis_times(&self.v, v);
    }

    /// The accelerations Phi s'' on the free DOFs into `out`, allocating
    /// nothing.
    pub fn accelerations_into(&self, out: &mut DVector<f64>) {
        self.basis_times(&self.a, out);
    }

    /// Phi x into `out` (x in coordinates, `out` on the free DOFs).
    fn basis_times(&self, x: &[f64], out: &mut DVector<f64>) {
        let x = nalgebra::DVectorView::from_slice(x, x.len());
        out.gemv(1.0, &self.basis, &x, 0.0);
    }

    /// Sets the acceleration that balances the projected load `f` at the
    /// current coordinates and velocities: m a = f - Q1 s - g~_nl(s) (the start
    /// of an explicit run; allocates, so not for every step).
    pub fn set_initial_acceleration(&mut self, f: &DVector<f64>) -> Result<(), UnitError> {
        let (q, v) = (self.q.clone(), self.v.clone());
        let mut g = Vec::new();
        self.nonlinear_force(&q, &v, 0.0, None, &mut g);
        let mut rhs = f - DVector::from_vec(g);
        if let Some(k) = &self.stiffness {
            k.mul_add(-1.0, &q, rhs.as_mut_slice());
        }
        let a = self
            .mass
            .to_dense()
            .cholesky()
            .map(|c| c.solve(&rhs))
            .ok_or_else(|| {
                UnitError::Numerical(
                    "reduced section: the reduced mass is not positive definite".into(),
                )
            })?;
        self.a.copy_from_slice(a.as_slice());
        Ok(())
    }

    /// How the restoring force is evaluated.
    pub fn restoring_force(&mut self) -> &mut RestoringForce {
        &mut self.force
    }
}

impl SecondOrderSystem for ReducedSection {
    fn label(&self) -> &str {
        "reduced section"
    }

    fn matrices(&self) -> Matrices<'_> {
        Matrices {
            mass: &self.mass,
            damping: None,
            stiffness: self.stiffness.as_ref(),
            varies: false,
        }
    }

    motion_fields!();

    fn is_linear(&self) -> bool {
        false
    }

    fn nonlinear_force(
        &mut self,
        q: &[f64],
        _v: &[f64],
        _t: f64,
        tangent: Option<(&mut SymmetricBand, TangentScales)>,
        force: &mut Vec<f64>,
    ) {
        force.resize(self.size(), 0.0);
        match &mut self.force {
            RestoringForce::Tensors(tensors) => {
                tensors.nonlinear(q, force);
                if let Some((band, scales)) = tangent {
                    // The tangent is symmetric: its lower triangle fills the band.
                    tensors.add_nonlinear_tangent(q, scales.stiffness, |i, j, value| {
                        if j <= i {
                            band.add(i, j, value);
                        }
                    });
                }
            }
            RestoringForce::Sampled(sampled) => match tangent {
                Some((band, scales)) => {
                    let mut add = |i: usize, j: usize, value: f64| band.add(i, j, value);
                    sampled.force(q, force, Some((scales.stiffness, &mut add)));
                }
                None => sampled.force(q, force, None),
            },
        }
    }
}
