//! A seed 002 section's restoring force as a cubic polynomial of its free DOFs
//! (seed 002 P2 eqs. 55-57): g(V) = K0 V + K1(V) V + K2(V, V) V, K1 linear and
//! K2 bilinear in their arguments. Reduced bases and reduced forces are built
//! from these terms; `force` equals the section's own internal force.

use crate::contract::UnitError;
use crate::nonlinear::NonlinearSection;
use crate::nonlinear::element::Formulation;
use crate::nonlinear::model::{Model, element_dofs};
use nalgebra::{DMatrix, DVector};

/// The polynomial terms of a section about its stress-free state, on its free
/// DOFs (those no end or support condition holds).
#[derive(Clone, Debug)]
pub struct CubicSection {
    model: Model,
    /// Free DOFs of the model, in order; vectors here are indexed by them.
    free: Vec<usize>,
    /// K0 (N/m, N, N m) on the free DOFs.
    pub k0: DMatrix<f64>,
    /// The section's mass matrix (kg, kg m, kg m^2) on the free DOFs.
    pub mass: DMatrix<f64>,
}

impl CubicSection {
    /// The terms of `section`, which must use seed 002's element (the
    /// co-rotational element's force is not a polynomial).
    pub fn new(section: &NonlinearSection) -> Result<CubicSection, UnitError> {
        let model = section.model().clone();
        if model.formulation != Formulation::Seed002 {
            return Err(UnitError::parameter(
                "formulation",
                "corotational",
                "expected \"seed002\": reduced restoring forces need a polynomial force",
            ));
        }
        let held = section.held_dofs();
        let free: Vec<usize> = (0..model.dofs()).filter(|d| !held.contains(d)).collect();
        let mass = section.mass_matrix();
        let pick = |m: &dyn Fn(usize, usize) -> f64| {
            DMatrix::from_fn(free.len(), free.len(), |i, j| m(free[i], free[j]))
        };
        let mut cubic = CubicSection {
            mass: pick(&|i, j| mass.get(i, j)),
            k0: DMatrix::zeros(0, 0),
            model,
            free,
        };
        let n = cubic.size();
        let mut k0 = DMatrix::zeros(n, n);
        for j in 0..n {
            let unit = DVector::from_fn(n, |i, _| f64::from(u8::from(i == j)));
            k0.set_column(j, &cubic.terms(&unit, &unit, &unit)[0]);
        }
        cubic.k0 = k0;
        Ok(cubic)
    }

    /// Number of free DOFs.
    pub fn size(&self) -> usize {
        self.free.len()
    }

    /// The free DOFs of the section's model.
    pub fn free_dofs(&self) -> &[usize] {
        &self.free
    }

    /// The section's mesh.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// The rows of `basis` (free DOFs x N) at element `e`'s six DOFs (zero rows
    /// at held DOFs): V_e = rows s.
    pub fn element_rows(&self, basis: &DMatrix<f64>, e: usize) -> DMatrix<f64> {
        let mut rows = DMatrix::zeros(6, basis.ncols());
        for i in 0..6 {
            if let Ok(k) = self.free.binary_search(&(3 * e + i)) {
                rows.set_row(i, &basis.row(k));
            }
        }
        rows
    }

    /// A free-DOF vector as the model's full DOF vector (held DOFs zero).
    pub fn expand(&self, x: &DVector<f64>) -> Vec<f64> {
        let mut full = vec![0.0; self.model.dofs()];
        for (k, &d) in self.free.iter().enumerate() {
            full[d] = x[k];
        }
        full
    }

    /// `[K0 b, K1(a) b, K2(a, b) c]` on the free DOFs.
    pub fn terms(&self, a: &DVector<f64>, b: &DVector<f64>, c: &DVector<f64>) -> [DVector<f64>; 3] {
        let (a, b, c) = (self.expand(a), self.expand(b), self.expand(c));
        let mut full = [(); 3].map(|_| vec![0.0; self.model.dofs()]);
        for (e, element) in self.model.elements.iter().enumerate() {
            let parts = element.seed002_terms(
                &element_dofs(&a, e),
                &element_dofs(&b, e),
                &element_dofs(&c, e),
            );
            for (out, part) in full.iter_mut().zip(parts) {
                for (i, v) in part.iter().enumerate() {
                    out[3 * e + i] += v;
                }
            }
        }
        full.map(|f| DVector::from_iterator(self.free.len(), self.free.iter().map(|&d| f[d])))
    }

    /// K1(a) b.
    pub fn k1(&self, a: &DVector<f64>, b: &DVector<f64>) -> DVector<f64> {
        let [_, k1, _] = self.terms(a, b, b);
        k1
    }

    /// K2(a, b) c.
    pub fn k2(&self, a: &DVector<f64>, b: &DVector<f64>, c: &DVector<f64>) -> DVector<f64> {
        let [_, _, k2] = self.terms(a, b, c);
        k2
    }

    /// The restoring force g(v) = K0 v + K1(v) v + K2(v, v) v.
    pub fn force(&self, v: &DVector<f64>) -> DVector<f64> {
        let [k0, k1, k2] = self.terms(v, v, v);
        k0 + k1 + k2
    }

    /// The tangent's derivative along `a` at the stress-free state, applied to
    /// `b`: (dK_T / ds_a) b = K1(a) b + K1(b) a.
    pub fn tangent_derivative(&self, a: &DVector<f64>, b: &DVector<f64>) -> DVector<f64> {
        self.k1(a, b) + self.k1(b, a)
    }
}
