//! Products of the dense basis T (n x m, column-major) with vectors and a
//! banded matrix: the reduced section's only dense algebra.

use crate::numerics::banded::SymmetricBand;

pub(super) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// out += T z.
pub(super) fn times(basis: &[f64], (n, m): (usize, usize), z: &[f64], out: &mut [f64]) {
    for (column, &zj) in basis.chunks_exact(n).take(m).zip(z) {
        if zj != 0.0 {
            out.iter_mut().zip(column).for_each(|(o, t)| *o += t * zj);
        }
    }
}

/// out[i] += (T z)[i] for the rows i in `rows` only.
pub(super) fn times_rows(
    basis: &[f64],
    (n, m): (usize, usize),
    z: &[f64],
    rows: &[std::ops::Range<usize>],
    out: &mut [f64],
) {
    for (column, &zj) in basis.chunks_exact(n).take(m).zip(z) {
        for range in rows {
            let (o, t) = (&mut out[range.clone()], &column[range.clone()]);
            o.iter_mut().zip(t).for_each(|(o, t)| *o += t * zj);
        }
    }
}

/// The largest |entry| of each column of T.
pub(super) fn column_largest(basis: &[f64], (n, m): (usize, usize)) -> Vec<f64> {
    (basis.chunks_exact(n).take(m))
        .map(|c| c.iter().fold(0.0f64, |a, t| a.max(t.abs())))
        .collect()
}

/// out = T^T x.
pub(super) fn transpose_times(basis: &[f64], (n, m): (usize, usize), x: &[f64], out: &mut [f64]) {
    for (o, column) in out.iter_mut().zip(basis.chunks_exact(n).take(m)) {
        *o = dot(column, x);
    }
}

/// T^T B T into `projected` (m x m, row-major), with `scratch` for B T.
pub(super) fn project(
    basis: &[f64],
    (n, m): (usize, usize),
    b: &SymmetricBand,
    scratch: &mut Vec<f64>,
    projected: &mut Vec<f64>,
) {
    scratch.clear();
    scratch.resize(n * m, 0.0);
    for (column, out) in basis.chunks_exact(n).zip(scratch.chunks_exact_mut(n)) {
        b.mul_add(1.0, column, out);
    }
    projected.clear();
    projected.resize(m * m, 0.0);
    // B is symmetric: the upper triangle, mirrored.
    for i in 0..m {
        for j in i..m {
            let value = dot(&basis[i * n..(i + 1) * n], &scratch[j * n..(j + 1) * n]);
            projected[i * m + j] = value;
            projected[j * m + i] = value;
        }
    }
}
