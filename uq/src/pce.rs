//! Sparse polynomial chaos expansions (Blatman and Sudret's degree-adaptive
//! hybrid LARS): for each total degree p, the candidate basis is the hyperbolic
//! set of multi-indices ((sum alpha_i^q)^(1/q) <= p); least-angle regression
//! orders the candidates; ordinary least squares on each leading subset gives a
//! corrected leave-one-out error; the subset and degree with the smallest one
//! win. Mean, variance and Sobol' indices follow from the coefficients of the
//! orthonormal basis.

use crate::UqError;
use crate::basis::Family;
use nalgebra::{DMatrix, DVector};

/// How an expansion is searched for.
#[derive(Copy, Clone, Debug)]
pub struct Settings {
    /// Highest total degree tried.
    pub max_degree: usize,
    /// Hyperbolic truncation q in (0, 1] (1: total degree).
    pub q: f64,
    /// Degrees tried past the best before the search stops.
    pub patience: usize,
}

impl Default for Settings {
    fn default() -> Settings {
        Settings {
            max_degree: 14,
            q: 0.75,
            patience: 2,
        }
    }
}

/// A fitted expansion.
#[derive(Clone, Debug)]
pub struct Pce {
    /// Each input's polynomial family (Legendre or Hermite).
    pub families: Vec<Family>,
    /// Multi-index of each basis function (the first is all zeros).
    pub indices: Vec<Vec<usize>>,
    /// Each basis function's coefficient.
    pub coefficients: Vec<f64>,
    /// The total degree whose basis won.
    pub degree: usize,
    /// Corrected leave-one-out error, relative to the output's variance.
    pub loo_error: f64,
}

impl Pce {
    /// E[Y].
    pub fn mean(&self) -> f64 {
        self.coefficients[0]
    }

    /// Var[Y].
    pub fn variance(&self) -> f64 {
        self.coefficients[1..].iter().map(|c| c * c).sum()
    }

    /// First-order Sobol' index of input `i`: the share of the variance from
    /// terms in input i alone.
    pub fn first_order(&self, i: usize) -> f64 {
        self.share(|a| a[i] > 0 && a.iter().enumerate().all(|(j, &n)| j == i || n == 0))
    }

    /// Total Sobol' index of input `i`: the share from every term in input i.
    pub fn total(&self, i: usize) -> f64 {
        self.share(|a| a[i] > 0)
    }

    fn share(&self, keep: impl Fn(&[usize]) -> bool) -> f64 {
        let part: f64 = self
            .indices
            .iter()
            .zip(&self.coefficients)
            .filter(|(a, _)| keep(a))
            .map(|(_, c)| c * c)
            .sum();
        // (+ 0.0: an empty sum is -0.0, which would print as "-0.000".)
        part / self.variance() + 0.0
    }

    /// The expansion at standard inputs `xi`.
    pub fn eval(&self, xi: &[f64]) -> f64 {
        let degree = self.indices.iter().flatten().copied().max().unwrap_or(0);
        let tables = tables(&self.families, xi, degree);
        self.indices
            .iter()
            .zip(&self.coefficients)
            .map(|(a, c)| {
                c * a
                    .iter()
                    .enumerate()
                    .map(|(j, &n)| tables[j][n])
                    .product::<f64>()
            })
            .sum()
    }
}

/// Fits a sparse expansion to outputs `y` at standard inputs `xi` (one row per
/// point, one family per input).
pub fn fit(
    families: &[Family],
    xi: &[Vec<f64>],
    y: &[f64],
    settings: Settings,
) -> Result<Pce, UqError> {
    check(families, xi, y, settings)?;
    let mut best: Option<Pce> = None;
    let mut since_best = 0;
    for degree in 1..=settings.max_degree {
        let indices = hyperbolic(families.len(), degree, settings.q);
        let psi = design_matrix(families, &indices, xi, degree);
        let candidate = best_subset(&psi, y).map(|(columns, coefficients, loo_error)| Pce {
            families: families.to_vec(),
            indices: columns.iter().map(|&c| indices[c].clone()).collect(),
            coefficients,
            degree,
            loo_error,
        });
        match (candidate, &best) {
            (Some(c), Some(b)) if c.loo_error >= b.loo_error => since_best += 1,
            (Some(c), _) => {
                best = Some(c);
                since_best = 0;
            }
            (None, _) => since_best += 1,
        }
        if since_best > settings.patience {
            break;
        }
    }
    best.ok_or_else(|| UqError::Singular("no basis fits the data".into()))
}

fn check(
    families: &[Family],
    xi: &[Vec<f64>],
    y: &[f64],
    settings: Settings,
) -> Result<(), UqError> {
    if xi.len() != y.len() || xi.len() < 3 {
        return Err(UqError::input(
            "data",
            format!(
                "{} points and {} outputs: expected as many, at least 3",
                xi.len(),
                y.len()
            ),
        ));
    }
    if xi.iter().any(|p| p.len() != families.len()) || families.is_empty() {
        return Err(UqError::input(
            "data",
            "every point needs one value per input family",
        ));
    }
    if xi.iter().flatten().chain(y).any(|v| !v.is_finite()) {
        return Err(UqError::input("data", "a value is not finite"));
    }
    if !(settings.q > 0.0 && settings.q <= 1.0) || settings.max_degree == 0 {
        return Err(UqError::input(
            "settings",
            format!(
                "q = {}, max_degree = {}: expected q in (0, 1], a degree >= 1",
                settings.q, settings.max_degree
            ),
        ));
    }
    Ok(())
}

/// Multi-indices of `dims` inputs with total degree <= p and
/// (sum alpha_i^q)^(1/q) <= p, the constant first.
pub fn hyperbolic(dims: usize, p: usize, q: f64) -> Vec<Vec<usize>> {
    let mut all = Vec::new();
    let mut current = vec![0; dims];
    fn walk(j: usize, left: usize, current: &mut Vec<usize>, all: &mut Vec<Vec<usize>>) {
        if j == current.len() {
            all.push(current.clone());
            return;
        }
        for n in 0..=left {
            current[j] = n;
            walk(j + 1, left - n, current, all);
        }
        current[j] = 0;
    }
    walk(0, p, &mut current, &mut all);
    let norm = |a: &[usize]| {
        a.iter()
            .map(|&n| (n as f64).powf(q))
            .sum::<f64>()
            .powf(1.0 / q)
    };
    let mut kept: Vec<Vec<usize>> = all
        .into_iter()
        .filter(|a| norm(a) <= p as f64 + 1e-9)
        .collect();
    kept.sort_by_key(|a| (a.iter().sum::<usize>(), std::cmp::Reverse(a.clone())));
    kept
}

/// Per input, the orthonormal polynomials 0..=degree at one point.
fn tables(families: &[Family], xi: &[f64], degree: usize) -> Vec<Vec<f64>> {
    families
        .iter()
        .zip(xi)
        .map(|(f, &x)| {
            let mut v = Vec::with_capacity(degree + 1);
            f.eval_into(degree, x, &mut v);
            v
        })
        .collect()
}

pub(crate) fn design_matrix(
    families: &[Family],
    indices: &[Vec<usize>],
    xi: &[Vec<f64>],
    degree: usize,
) -> DMatrix<f64> {
    let mut psi = DMatrix::zeros(xi.len(), indices.len());
    for (i, point) in xi.iter().enumerate() {
        let t = tables(families, point, degree);
        for (c, a) in indices.iter().enumerate() {
            psi[(i, c)] = a.iter().enumerate().map(|(j, &n)| t[j][n]).product();
        }
    }
    psi
}

/// The best leading subset of the LARS path (with the constant): its columns,
/// least-squares coefficients and corrected LOO error.
fn best_subset(psi: &DMatrix<f64>, y: &[f64]) -> Option<(Vec<usize>, Vec<f64>, f64)> {
    let path = lars_path(psi, y);
    let y = DVector::from_column_slice(y);
    let mut best: Option<(Vec<usize>, Vec<f64>, f64)> = None;
    for k in 1..=path.len() {
        let mut columns = vec![0];
        columns.extend_from_slice(&path[..k]);
        if columns.len() + 1 >= y.len() {
            break;
        }
        let Some((coefficients, loo)) = ols_loo(psi, &columns, &y) else {
            continue;
        };
        if best.as_ref().is_none_or(|b| loo < b.2) {
            best = Some((columns, coefficients, loo));
        }
    }
    best
}

/// Least-angle regression (the LAR variant) on the non-constant columns of
/// `psi`, centred and scaled: the order in which columns enter.
fn lars_path(psi: &DMatrix<f64>, y: &[f64]) -> Vec<usize> {
    let (n, m) = (psi.nrows(), psi.ncols());
    let mut x = psi.columns(1, m - 1).clone_owned();
    for mut col in x.column_iter_mut() {
        let mean = col.mean();
        col.add_scalar_mut(-mean);
        let norm = col.norm();
        if norm > 0.0 {
            col /= norm;
        }
    }
    let ymean = y.iter().sum::<f64>() / n as f64;
    let yc = DVector::from_iterator(n, y.iter().map(|v| v - ymean));
    let mut mu = DVector::zeros(n);
    // At most a third of the points' worth of terms: beyond, the least-squares
    // fits are too close to interpolation for their LOO error to mean much, and
    // each step costs O(n k^2).
    let limit = (m - 1).min(n / 3);
    let c0 = x.tr_mul(&yc);
    let Some(first) = (0..m - 1).max_by(|&a, &b| c0[a].abs().total_cmp(&c0[b].abs())) else {
        return Vec::new();
    };
    let mut active = vec![first];
    while active.len() <= limit {
        let c = x.tr_mul(&(&yc - &mu));
        let big_c = active.iter().map(|&j| c[j].abs()).fold(0.0, f64::max);
        if big_c <= 1e-14 * yc.norm() {
            break;
        }
        let xa = DMatrix::from_fn(n, active.len(), |i, k| {
            x[(i, active[k])] * c[active[k]].signum()
        });
        let Some(chol) = xa.tr_mul(&xa).cholesky() else {
            active.pop();
            break;
        };
        let z = chol.solve(&DVector::from_element(active.len(), 1.0));
        let aa = 1.0 / z.sum().sqrt();
        let u = &xa * (z * aa);
        let a = x.tr_mul(&u);
        let mut step = big_c / aa;
        let mut entering = None;
        for j in (0..m - 1).filter(|j| !active.contains(j)) {
            for g in [(big_c - c[j]) / (aa - a[j]), (big_c + c[j]) / (aa + a[j])] {
                if g > 1e-12 && g < step {
                    step = g;
                    entering = Some(j);
                }
            }
        }
        mu += u * step;
        match entering {
            Some(j) if active.len() < limit => active.push(j),
            _ => break,
        }
    }
    // Columns of psi (the constant is column 0).
    active.into_iter().map(|j| j + 1).collect()
}

/// Least squares on `columns` of psi, and the corrected leave-one-out error
/// relative to the output's variance (Chapelle's factor n / (n - P) (1 +
/// tr((Psi^T Psi / n)^-1) / n)); None when the fit is singular.
fn ols_loo(psi: &DMatrix<f64>, columns: &[usize], y: &DVector<f64>) -> Option<(Vec<f64>, f64)> {
    let n = y.len();
    let a = DMatrix::from_fn(n, columns.len(), |i, k| psi[(i, columns[k])]);
    let qr = a.clone().qr();
    let (q, r) = (qr.q(), qr.r());
    if r.diagonal()
        .iter()
        .any(|d| d.abs() < 1e-12 * r[(0, 0)].abs())
    {
        return None;
    }
    let qty = q.tr_mul(y);
    let beta = r.solve_upper_triangular(&qty)?;
    let fitted = &a * &beta;
    let mean = y.mean();
    let variance = y.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n as f64;
    let mut loo = 0.0;
    for i in 0..n {
        let h: f64 = q.row(i).iter().map(|v| v * v).sum();
        if h >= 1.0 - 1e-12 {
            return None;
        }
        loo += ((y[i] - fitted[i]) / (1.0 - h)).powi(2);
    }
    let p = columns.len();
    let r_inv = r.clone().try_inverse()?;
    let trace = n as f64 * r_inv.iter().map(|v| v * v).sum::<f64>();
    let correction = n as f64 / (n - p) as f64 * (1.0 + trace / n as f64);
    Some((
        beta.iter().copied().collect(),
        correction * loo / n as f64 / variance,
    ))
}
