//! Reduced restoring forces by global reduced tensors (seed 002's RBF, "LRBF":
//! Nash 1977, Shi and Mei 1996; notes sec. 4.7). For V = Phi s the projected
//! force Phi^T g(Phi s) is a cubic polynomial in s with constant coefficient
//! vectors, projected once:
//! g~(s) = Q1 s + Q2 s_q + Q3 s_c, s_q and s_c the monomials of degree 2 and 3
//! with sorted indices (i >= j >= k), each coefficient the sum over the
//! monomial's distinct index permutations (the product symmetry: C(N + 1, 2)
//! and C(N + 2, 3) columns instead of N^2 and N^3).
//! Evaluating costs about N^4 / 6 multiply-adds; the tangent as much again.

use super::polynomial::CubicSection;
use nalgebra::{DMatrix, DVector};

/// The reduced tensors of a section on a basis.
#[derive(Clone, Debug)]
pub struct ReducedForce {
    /// Phi^T K0 Phi (N x N).
    pub q1: DMatrix<f64>,
    /// Quadratic coefficients (N x pairs), one column per sorted pair.
    pub q2: DMatrix<f64>,
    /// Cubic coefficients (N x triples), one column per sorted triple.
    pub q3: DMatrix<f64>,
    pairs: Vec<[usize; 2]>,
    triples: Vec<[usize; 3]>,
    /// Monomials at the current evaluation (scratch).
    sq: DVector<f64>,
    sc: DVector<f64>,
}

/// The distinct permutations of `index`.
fn permutations<const K: usize>(index: [usize; K]) -> Vec<[usize; K]> {
    let mut all = vec![index];
    if K == 2 {
        all.push(std::array::from_fn(|p| index[1 - p]));
    } else if K == 3 {
        let [a, b, c] = [index[0], index[1], index[2]];
        for p in [[a, c, b], [b, a, c], [b, c, a], [c, a, b], [c, b, a]] {
            all.push(std::array::from_fn(|i| p[i]));
        }
    }
    all.sort_unstable();
    all.dedup();
    all
}

impl ReducedForce {
    /// Projects `section`'s polynomial on the columns of `basis` (n x N).
    pub fn new(section: &CubicSection, basis: &DMatrix<f64>) -> ReducedForce {
        let n = basis.ncols();
        let phi: Vec<DVector<f64>> = (0..n).map(|i| basis.column(i).into_owned()).collect();
        let project = |v: DVector<f64>| basis.tr_mul(&v);
        let mut pairs = Vec::new();
        let mut triples = Vec::new();
        for i in 0..n {
            for j in 0..=i {
                pairs.push([i, j]);
                for k in 0..=j {
                    triples.push([i, j, k]);
                }
            }
        }
        let mut q2 = DMatrix::zeros(n, pairs.len());
        for (p, &pair) in pairs.iter().enumerate() {
            let sum = permutations(pair)
                .iter()
                .map(|[a, b]| section.k1(&phi[*a], &phi[*b]))
                .fold(DVector::zeros(section.size()), |s, v| s + v);
            q2.set_column(p, &project(sum));
        }
        let mut q3 = DMatrix::zeros(n, triples.len());
        for (t, &triple) in triples.iter().enumerate() {
            let sum = permutations(triple)
                .iter()
                .map(|[a, b, c]| section.k2(&phi[*a], &phi[*b], &phi[*c]))
                .fold(DVector::zeros(section.size()), |s, v| s + v);
            q3.set_column(t, &project(sum));
        }
        ReducedForce {
            q1: basis.transpose() * &section.k0 * basis,
            sq: DVector::zeros(pairs.len()),
            sc: DVector::zeros(triples.len()),
            q2,
            q3,
            pairs,
            triples,
        }
    }

    /// Number of reduced coordinates N.
    pub fn size(&self) -> usize {
        self.q1.nrows()
    }

    /// The nonlinear part Q2 s_q + Q3 s_c at `s` into `out` (sized N).
    pub fn nonlinear(&mut self, s: &[f64], out: &mut [f64]) {
        for (m, [i, j]) in self.sq.iter_mut().zip(&self.pairs) {
            *m = s[*i] * s[*j];
        }
        for (m, [i, j, k]) in self.sc.iter_mut().zip(&self.triples) {
            *m = s[*i] * s[*j] * s[*k];
        }
        let mut out = nalgebra::DVectorViewMut::from_slice(out, self.size());
        out.gemv(1.0, &self.q2, &self.sq, 0.0);
        out.gemv(1.0, &self.q3, &self.sc, 1.0);
    }

    /// The whole reduced force g~(s) = Q1 s + Q2 s_q + Q3 s_c.
    pub fn force(&mut self, s: &[f64]) -> DVector<f64> {
        let mut out = vec![0.0; self.size()];
        self.nonlinear(s, &mut out);
        DVector::from_vec(out) + &self.q1 * DVector::from_column_slice(s)
    }

    /// Adds `scale` times the nonlinear part's tangent at `s` to `add(i, j,
    /// value)`, entry by entry (column j: the derivative along s_j).
    pub fn add_nonlinear_tangent(
        &self,
        s: &[f64],
        scale: f64,
        mut add: impl FnMut(usize, usize, f64),
    ) {
        let n = self.size();
        for (p, &[i, j]) in self.pairs.iter().enumerate() {
            for r in 0..n {
                let c = scale * self.q2[(r, p)];
                add(r, i, c * s[j]);
                add(r, j, c * s[i]);
            }
        }
        for (t, &[i, j, k]) in self.triples.iter().enumerate() {
            let (di, dj, dk) = (s[j] * s[k], s[i] * s[k], s[i] * s[j]);
            for r in 0..n {
                let c = scale * self.q3[(r, t)];
                add(r, i, c * di);
                add(r, j, c * dj);
                add(r, k, c * dk);
            }
        }
    }

    /// The whole tangent dg~/ds at `s`.
    pub fn tangent(&self, s: &[f64]) -> DMatrix<f64> {
        let mut k = self.q1.clone();
        self.add_nonlinear_tangent(s, 1.0, |i, j, v| k[(i, j)] += v);
        k
    }
}
