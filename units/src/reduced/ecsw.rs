//! Hyper-reduction by energy-conserving sampling and weighting (ECSW; Farhat,
//! Avery, Chapman and Cortial 2014), beyond seed 002: the reduced force is
//! summed over a sample of elements with positive weights,
//! g~(s) = sum_e w_e Phi_e^T g_e(Phi_e s),
//! so its cost grows with the sampled elements times N, not with N^4 as the
//! reduced tensors'. Each term is an element's own force (the gradient of its
//! strain energy) and the weights are positive, so the reduced model keeps a
//! positive strain energy and conserves it in free vibration.
//!
//! Training: for snapshots s_k of the reduced coordinates, column e of G holds
//! Phi_e^T g_e(Phi_e s_k) over all k, b = G 1 the exact projected forces;
//! non-negative least squares (Lawson and Hanson's active set) stopped as soon
//! as |G w - b| <= tolerance |b| picks few elements. (The `nnls` crate solves to
//! optimality and brings ndarray; the early stop is what makes the sample
//! sparse, so the active set is written here on nalgebra.)

use super::polynomial::CubicSection;
use crate::contract::UnitError;
use crate::nonlinear::element::Element;
use crate::nonlinear::model::element_dofs;
use nalgebra::{DMatrix, DVector};

/// Where a tangent goes: its scale, and a sink taking (row, column, value) for
/// the lower triangle.
pub type TangentSink<'a> = (f64, &'a mut dyn FnMut(usize, usize, f64));

/// Sampled elements with their weights and basis rows.
#[derive(Clone, Debug)]
pub struct SampledForce {
    elements: Vec<Element>,
    /// Element index in the mesh, for reports.
    indices: Vec<usize>,
    weights: Vec<f64>,
    /// Phi_e (6 x N) per sampled element.
    rows: Vec<DMatrix<f64>>,
    formulation: crate::nonlinear::element::Formulation,
    size: usize,
}

impl SampledForce {
    /// Every element with weight 1: the exact projection Phi^T g(Phi s).
    pub fn all(section: &CubicSection, basis: &DMatrix<f64>) -> SampledForce {
        let count = section.model().elements.len();
        SampledForce::with(section, basis, (0..count).map(|e| (e, 1.0)).collect())
    }

    /// Every `stride`-th element with weight `stride` (a uniform sample: a
    /// baseline for trained samples, and a sample of known size for timing).
    pub fn every(section: &CubicSection, basis: &DMatrix<f64>, stride: usize) -> SampledForce {
        let stride = stride.max(1);
        let count = section.model().elements.len();
        let sample = (0..count)
            .step_by(stride)
            .map(|e| (e, stride as f64))
            .collect();
        SampledForce::with(section, basis, sample)
    }

    fn with(
        section: &CubicSection,
        basis: &DMatrix<f64>,
        sample: Vec<(usize, f64)>,
    ) -> SampledForce {
        let model = section.model();
        SampledForce {
            elements: sample.iter().map(|&(e, _)| model.elements[e]).collect(),
            indices: sample.iter().map(|&(e, _)| e).collect(),
            weights: sample.iter().map(|&(_, w)| w).collect(),
            rows: sample
                .iter()
                .map(|&(e, _)| section.element_rows(basis, e))
                .collect(),
            formulation: model.formulation,
            size: basis.ncols(),
        }
    }

    /// The sample trained on `snapshots` (reduced coordinates) to `tolerance`
    /// (relative residual of the projected forces), at most `max_iterations`
    /// active-set iterations.
    pub fn train(
        section: &CubicSection,
        basis: &DMatrix<f64>,
        snapshots: &[DVector<f64>],
        tolerance: f64,
    ) -> Result<SampledForce, UnitError> {
        let all = SampledForce::all(section, basis);
        let (n, count) = (basis.ncols(), all.elements.len());
        if snapshots.is_empty() || snapshots.iter().any(|s| s.len() != n) {
            return Err(UnitError::parameter(
                "snapshots",
                snapshots.len(),
                &format!("expected at least one, each of the basis's {n} coordinates"),
            ));
        }
        let mut g = DMatrix::zeros(snapshots.len() * n, count);
        for (k, s) in snapshots.iter().enumerate() {
            for e in 0..count {
                let f = all.element_force(e, s.as_slice());
                g.view_mut((k * n, e), (n, 1)).copy_from(&f);
            }
        }
        let b = g.column_sum();
        let weights = nnls(&g, &b, tolerance, 3 * count)?;
        let sample = weights
            .iter()
            .enumerate()
            .filter(|(_, w)| **w > 0.0)
            .map(|(e, w)| (e, *w))
            .collect();
        Ok(SampledForce::with(section, basis, sample))
    }

    /// The sampled elements' mesh indices and weights.
    pub fn sample(&self) -> Vec<(usize, f64)> {
        self.indices
            .iter()
            .copied()
            .zip(self.weights.iter().copied())
            .collect()
    }

    /// Unweighted Phi_e^T g_e(Phi_e s) of sampled element `k`.
    fn element_force(&self, k: usize, s: &[f64]) -> DVector<f64> {
        let v = &self.rows[k] * DVector::from_column_slice(s);
        let p = element_dofs(v.as_slice(), 0);
        let (f, _) = self.elements[k].force(self.formulation, &p, false);
        self.rows[k].tr_mul(&DVector::from_column_slice(&f))
    }

    /// The reduced force at `s` into `out`, and with `tangent` the reduced
    /// tangent sum_e w_e Phi_e^T K_e Phi_e times its scale, lower triangle
    /// entry by entry. Without a tangent it allocates nothing.
    pub fn force(&self, s: &[f64], out: &mut [f64], tangent: Option<TangentSink<'_>>) {
        out.fill(0.0);
        let mut tangent = tangent;
        for (k, element) in self.elements.iter().enumerate() {
            let rows = &self.rows[k];
            // V_e = Phi_e s, column by column (Phi_e is stored by columns).
            let mut p = [0.0; 6];
            for (i, &si) in s.iter().enumerate() {
                let column = rows.column(i);
                for a in 0..6 {
                    p[a] += column[a] * si;
                }
            }
            let (f, ke) = element.force(self.formulation, &p, tangent.is_some());
            let w = self.weights[k];
            for (i, o) in out.iter_mut().enumerate() {
                let column = rows.column(i);
                *o += w * (0..6).map(|a| column[a] * f[a]).sum::<f64>();
            }
            if let Some((scale, add)) = tangent.as_mut() {
                let ke = DMatrix::from_fn(6, 6, |a, b| ke[a][b]);
                let projected = rows.transpose() * ke * rows;
                for i in 0..self.size {
                    for j in 0..=i {
                        add(i, j, *scale * w * projected[(i, j)]);
                    }
                }
            }
        }
    }
}

/// Non-negative least squares min |G w - b|, w >= 0, by Lawson and Hanson's
/// active set, stopped once |G w - b| <= tolerance |b|. It works on the Gram
/// matrix G^T G and G^T b (formed once): each least-squares subproblem is a
/// Cholesky solve of the active block, whatever the number of rows of G.
pub(crate) fn nnls(
    g: &DMatrix<f64>,
    b: &DVector<f64>,
    tolerance: f64,
    max_iterations: usize,
) -> Result<DVector<f64>, UnitError> {
    let n = g.ncols();
    let gram = g.tr_mul(g);
    let gb = g.tr_mul(b);
    let bb = b.norm_squared();
    let mut w = DVector::zeros(n);
    let mut active: Vec<usize> = Vec::new();
    let target = (tolerance * tolerance * bb).max(0.0);
    for _ in 0..max_iterations {
        // |G w - b|^2 = b.b - 2 w.Gtb + w.GtG w; the gradient G^T (b - G w).
        let gw = &gram * &w;
        if bb - 2.0 * w.dot(&gb) + w.dot(&gw) <= target {
            return Ok(w);
        }
        let gradient = &gb - gw;
        let entering = (0..n)
            .filter(|j| !active.contains(j))
            .max_by(|&a, &c| gradient[a].total_cmp(&gradient[c]));
        match entering {
            Some(j) if gradient[j] > 0.0 => active.push(j),
            _ => return Ok(w),
        }
        // Least squares on the active set, stepping back to keep w >= 0.
        for _ in 0..=n {
            let block = DMatrix::from_fn(active.len(), active.len(), |i, k| {
                gram[(active[i], active[k])]
            });
            let rhs = DVector::from_fn(active.len(), |i, _| gb[active[i]]);
            let z = block.cholesky().map(|c| c.solve(&rhs)).ok_or_else(|| {
                UnitError::Numerical(
                    "ECSW: the sampled elements' forces are linearly dependent".into(),
                )
            })?;
            if z.iter().all(|&v| v > 0.0) {
                for (k, &j) in active.iter().enumerate() {
                    w[j] = z[k];
                }
                break;
            }
            let step = active
                .iter()
                .enumerate()
                .filter(|(k, _)| z[*k] <= 0.0)
                .map(|(k, &j)| w[j] / (w[j] - z[k]))
                .fold(1.0, f64::min);
            for (k, &j) in active.iter().enumerate() {
                w[j] += step * (z[k] - w[j]);
            }
            active.retain(|&j| w[j] > 1e-14);
            for j in 0..n {
                if !active.contains(&j) {
                    w[j] = 0.0;
                }
            }
        }
    }
    Err(UnitError::Numerical(format!(
        "ECSW: the sample did not reach the tolerance {tolerance:e} in {max_iterations} iterations"
    )))
}
