//! Symmetric banded matrices and their LDL^T factorisation.
//!
//! FE matrices of a chain of elements (cables, beams) are banded with a small
//! half-bandwidth (3 for a 2-DOF-per-node bar chain). faer and nalgebra offer dense
//! and general sparse factorisations; for a bandwidth this small a band LDL^T is
//! both simpler and several times faster per solve, and it allocates nothing after
//! construction.

/// A symmetric n x n matrix stored by its lower band: `band[i * (w + 1) + k]` holds
/// entry (i, i - k) for k = 0..=w.
#[derive(Clone, Debug, PartialEq)]
pub struct SymmetricBand {
    n: usize,
    w: usize,
    band: Vec<f64>,
}

impl SymmetricBand {
    /// An n x n zero matrix with half-bandwidth `w`.
    pub fn zeros(n: usize, w: usize) -> SymmetricBand {
        SymmetricBand {
            n,
            w,
            band: vec![0.0; n * (w + 1)],
        }
    }

    /// Order of the matrix.
    pub fn size(&self) -> usize {
        self.n
    }

    /// Half-bandwidth.
    pub fn half_bandwidth(&self) -> usize {
        self.w
    }

    /// Entry (i, j); zero outside the band.
    pub fn get(&self, i: usize, j: usize) -> f64 {
        let (i, j) = if i >= j { (i, j) } else { (j, i) };
        if i - j > self.w {
            0.0
        } else {
            self.band[i * (self.w + 1) + (i - j)]
        }
    }

    /// Adds `value` to entry (i, j) (and so to (j, i)). Panics outside the band:
    /// that is a programming error of the assembly, not bad input.
    pub fn add(&mut self, i: usize, j: usize, value: f64) {
        let (i, j) = if i >= j { (i, j) } else { (j, i) };
        assert!(i - j <= self.w, "entry ({i}, {j}) is outside the band");
        self.band[i * (self.w + 1) + (i - j)] += value;
    }

    /// Replaces row and column `i` by those of the identity (a prescribed DOF).
    pub fn set_identity_row(&mut self, i: usize) {
        let w = self.w;
        for k in 1..=w.min(i) {
            self.band[i * (w + 1) + k] = 0.0;
        }
        for k in 1..=w.min(self.n - 1 - i) {
            self.band[(i + k) * (w + 1) + k] = 0.0;
        }
        self.band[i * (w + 1)] = 1.0;
    }

    /// Sets every entry to zero.
    pub fn fill_zero(&mut self) {
        self.band.fill(0.0);
    }

    /// Copies another matrix of the same shape.
    pub fn copy_from(&mut self, other: &SymmetricBand) {
        self.band.copy_from_slice(&other.band);
    }

    /// `self = a * x + b * y` entrywise (same shape).
    pub fn set_combination(&mut self, terms: &[(f64, &SymmetricBand)]) {
        self.band.fill(0.0);
        for (c, m) in terms {
            debug_assert_eq!((m.n, m.w), (self.n, self.w));
            for (a, b) in self.band.iter_mut().zip(&m.band) {
                *a += c * b;
            }
        }
    }

    /// `self = sum c_i X_i` over the terms whose matrix is present, in order
    /// (same shape): an absent damping or stiffness adds nothing.
    pub fn set_present_combination(&mut self, terms: &[(f64, Option<&SymmetricBand>)]) {
        self.band.fill(0.0);
        for (c, m) in terms {
            if let Some(m) = m {
                debug_assert_eq!((m.n, m.w), (self.n, self.w));
                for (a, b) in self.band.iter_mut().zip(&m.band) {
                    *a += c * b;
                }
            }
        }
    }

    /// `y += alpha * A x`.
    pub fn mul_add(&self, alpha: f64, x: &[f64], y: &mut [f64]) {
        let w = self.w;
        let (x, y) = (&x[..self.n], &mut y[..self.n]);
        for (i, row) in self.band.chunks_exact(w + 1).enumerate() {
            // Row i's sub-diagonal entries (i, i - k), k = 1..=reach, against the
            // slices x[i - reach..i] and y[i - reach..i] (bounds checked once).
            let reach = w.min(i);
            let (xi, axi) = (x[i], alpha * x[i]);
            let mut sum = row[0] * xi;
            let xs = &x[i - reach..i];
            let ys = &mut y[i - reach..i];
            for k in 1..=reach {
                let a = row[k];
                sum += a * xs[reach - k];
                ys[reach - k] += a * axi;
            }
            y[i] += alpha * sum;
        }
    }

    /// Row `i` of [`Self::mul_add`]: `y_i + alpha (A x)_i`, summed in the
    /// order `mul_add` sums it (the same value to the bit), for a caller that
    /// needs a few rows of the product.
    pub fn mul_add_row(&self, alpha: f64, x: &[f64], i: usize, y_i: f64) -> f64 {
        let w = self.w;
        let row = &self.band[i * (w + 1)..(i + 1) * (w + 1)];
        let mut sum = row[0] * x[i];
        for k in 1..=w.min(i) {
            sum += row[k] * x[i - k];
        }
        let mut y = y_i + alpha * sum;
        let below = &x[i + 1..=(i + w).min(self.n - 1)];
        for (k, xj) in below.iter().enumerate() {
            let j = i + 1 + k;
            y += self.band[j * (w + 1) + k + 1] * (alpha * xj);
        }
        y
    }

    /// x^T A x, without allocating.
    pub fn quadratic_form(&self, x: &[f64]) -> f64 {
        let w = self.w;
        let mut sum = 0.0;
        for i in 0..self.n {
            let row = &self.band[i * (w + 1)..(i + 1) * (w + 1)];
            sum += row[0] * x[i] * x[i];
            for k in 1..=w.min(i) {
                sum += 2.0 * row[k] * x[i] * x[i - k];
            }
        }
        sum
    }

    /// The dense matrix (for eigenvalue analysis and tests).
    pub fn to_dense(&self) -> nalgebra::DMatrix<f64> {
        nalgebra::DMatrix::from_fn(self.n, self.n, |i, j| self.get(i, j))
    }
}

/// LDL^T factorisation of a symmetric banded matrix (no pivoting: for positive
/// definite matrices such as effective stiffnesses).
#[derive(Clone, Debug)]
pub struct BandLdlt {
    n: usize,
    w: usize,
    /// Unit lower factor L (diagonal not stored, slot 0 holds D).
    band: Vec<f64>,
}

impl BandLdlt {
    /// An empty factor of order `n` and half-bandwidth `w`, to be filled by a
    /// refactorisation.
    pub fn zeros(n: usize, w: usize) -> BandLdlt {
        BandLdlt {
            n,
            w,
            band: vec![0.0; n * (w + 1)],
        }
    }

    /// Factorises `a`; `None` when a pivot is not positive (the matrix is not
    /// positive definite).
    pub fn new(a: &SymmetricBand) -> Option<BandLdlt> {
        let mut f = BandLdlt {
            n: a.n,
            w: a.w,
            band: a.band.clone(),
        };
        f.factorise_in_place(false).then_some(f)
    }

    /// Refactorises for `a` (same shape) reusing this factor's memory; false when a
    /// pivot is not positive.
    pub fn refactorise(&mut self, a: &SymmetricBand) -> bool {
        if (self.n, self.w) != (a.n, a.w) {
            self.n = a.n;
            self.w = a.w;
        }
        self.band.clone_from(&a.band);
        self.factorise_in_place(false)
    }

    /// Refactorises for a symmetric `a` that may be indefinite (a Newton matrix of
    /// a structure past a limit point): negative pivots are kept; false when a
    /// pivot is zero to round-off (below 1e-13 of its diagonal entry) or not
    /// finite. Without pivoting, so meant for matrices dominated by a positive
    /// mass term.
    pub fn refactorise_nonsingular(&mut self, a: &SymmetricBand) -> bool {
        self.n = a.n;
        self.w = a.w;
        self.band.clone_from(&a.band);
        self.factorise_in_place(true)
    }

    fn factorise_in_place(&mut self, indefinite: bool) -> bool {
        let (n, w) = (self.n, self.w);
        let f = &mut self.band;
        let s = w + 1;
        for j in 0..n {
            // d_j = a_jj - sum_k l_jk^2 d_k
            let mut d = f[j * s];
            let smallest = 1e-13 * d.abs();
            for k in 1..=w.min(j) {
                let l = f[j * s + k];
                d -= l * l * f[(j - k) * s];
            }
            let admissible = if indefinite {
                d.abs() > smallest
            } else {
                d > 0.0
            };
            if !(admissible && d.is_finite()) {
                return false;
            }
            f[j * s] = d;
            // l_ij = (a_ij - sum_k l_ik l_jk d_k) / d_j for i = j+1..j+w, over
            // the columns c = j - k within the band of both rows (k <= j and
            // i - c <= w), in increasing k: row i's entries are contiguous.
            for i in j + 1..(j + w + 1).min(n) {
                let (rows_before, rows_from_i) = f.split_at_mut(i * s);
                let row_j = &rows_before[j * s..(j + 1) * s];
                let row_i = &mut rows_from_i[..s];
                let offset = i - j;
                let reach = j.min(w - offset);
                let mut v = row_i[offset];
                for (k, l_ic) in row_i[offset + 1..=offset + reach].iter().enumerate() {
                    let k = k + 1;
                    v -= l_ic * row_j[k] * rows_before[(j - k) * s];
                }
                row_i[offset] = v / d;
            }
        }
        true
    }

    /// The number of negative pivots of D: by Sylvester's law of inertia, of
    /// an indefinite factor (`refactorise_nonsingular`) of K - sigma M, the
    /// number of eigenvalues of the pencil below sigma (a Sturm sequence check).
    pub fn negative_pivots(&self) -> usize {
        let s = self.w + 1;
        (0..self.n).filter(|&i| self.band[i * s] < 0.0).count()
    }

    /// Solves `A x = b` in place.
    pub fn solve_in_place(&self, b: &mut [f64]) {
        let (n, w, s) = (self.n, self.w, self.w + 1);
        // L^-1 b is zero above b's first non-zero entry (a load at a section's
        // far end: an interface Jacobian's column), so the forward pass starts there.
        let first = b.iter().position(|x| *x != 0.0).unwrap_or(n);
        for i in first..n {
            // Row i's entries (i, i - k), k = 1..=reach, against b[i - k].
            let reach = w.min(i);
            let row = &self.band[i * s + 1..=i * s + reach];
            let (done, rest) = b.split_at_mut(i);
            let mut v = rest[0];
            for (l, x) in row.iter().zip(done[i - reach..].iter().rev()) {
                v -= l * x;
            }
            rest[0] = v;
        }
        for (i, x) in b.iter_mut().enumerate().skip(first) {
            *x /= self.band[i * s];
        }
        for i in (0..n).rev() {
            let mut v = b[i];
            for k in 1..=w.min(n - 1 - i) {
                v -= self.band[(i + k) * s + k] * b[i + k];
            }
            b[i] = v;
        }
    }

    /// Solves `A X = B` in place for the columns of `b` (column-major, each
    /// of the matrix's size: a step Jacobian's columns, one per input): every
    /// column exactly as [`Self::solve_in_place`] solves it alone (the same
    /// values to the bit), several in one pass over the factor, so that the
    /// columns' independent sums overlap. An all-zero column stays zero.
    pub fn solve_columns_in_place(&self, b: &mut [f64]) {
        if self.n == 0 {
            return;
        }
        for chunk in b.chunks_mut(self.n * COLUMNS_AT_ONCE) {
            self.solve_chunk(chunk);
        }
    }

    /// [`Self::solve_columns_in_place`] for at most `COLUMNS_AT_ONCE` columns.
    fn solve_chunk(&self, b: &mut [f64]) {
        let (n, w, s) = (self.n, self.w, self.w + 1);
        let mut first = [n; COLUMNS_AT_ONCE];
        for (c, column) in b.chunks_exact(n).enumerate() {
            first[c] = column.iter().position(|x| *x != 0.0).unwrap_or(n);
        }
        let first = &first[..b.len() / n];
        let start = first.iter().copied().min().unwrap_or(n);
        for i in start..n {
            let reach = w.min(i);
            let row = &self.band[i * s + 1..=i * s + reach];
            for (column, _) in b.chunks_exact_mut(n).zip(first).filter(|(_, f)| **f <= i) {
                let (done, rest) = column.split_at_mut(i);
                let mut v = rest[0];
                for (l, x) in row.iter().zip(done[i - reach..].iter().rev()) {
                    v -= l * x;
                }
                rest[0] = v;
            }
        }
        for (column, &f) in b.chunks_exact_mut(n).zip(first) {
            for (i, x) in column.iter_mut().enumerate().skip(f) {
                *x /= self.band[i * s];
            }
        }
        for i in (0..n).rev() {
            let reach = w.min(n - 1 - i);
            for (column, _) in b.chunks_exact_mut(n).zip(first).filter(|(_, f)| **f < n) {
                let mut v = column[i];
                for k in 1..=reach {
                    v -= self.band[(i + k) * s + k] * column[i + k];
                }
                column[i] = v;
            }
        }
    }
}

/// How many columns [`BandLdlt::solve_columns_in_place`] carries through
/// one pass (a section's coupled inputs: six for two ends).
const COLUMNS_AT_ONCE: usize = 8;

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(n: usize, w: usize) -> SymmetricBand {
        let mut a = SymmetricBand::zeros(n, w);
        for i in 0..n {
            a.add(i, i, 10.0 + i as f64);
            for k in 1..=w.min(i) {
                a.add(i, i - k, 1.0 / (1.0 + k as f64 + (i % 3) as f64));
            }
        }
        a
    }

    #[test]
    fn columns_solved_together_are_each_solved_alone_to_the_bit() {
        let n = 23;
        let a = sample(n, 3);
        let f = BandLdlt::new(&a).unwrap();
        // Ten columns (two passes), one all zero, most zero above an entry
        // further down, one with a negative zero above its first entry.
        let mut columns = vec![0.0; n * 10];
        for (c, column) in columns.chunks_exact_mut(n).enumerate() {
            if c != 4 {
                for (i, x) in column.iter_mut().enumerate().skip(2 * c) {
                    *x = ((i * 7 + c) as f64).cos();
                }
            }
        }
        columns[6 * n + 3] = -0.0;
        let mut alone = columns.clone();
        alone.chunks_exact_mut(n).for_each(|c| f.solve_in_place(c));
        f.solve_columns_in_place(&mut columns);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&columns), bits(&alone));
        assert!(columns[4 * n..5 * n].iter().all(|x| x.to_bits() == 0));
    }

    #[test]
    fn solves_like_a_dense_factorisation() {
        let a = sample(17, 3);
        let dense = a.to_dense();
        let b: Vec<f64> = (0..17).map(|i| (i as f64).sin()).collect();
        let mut x = b.clone();
        BandLdlt::new(&a).unwrap().solve_in_place(&mut x);
        let reference = dense
            .clone()
            .lu()
            .solve(&nalgebra::DVector::from_vec(b.clone()))
            .unwrap();
        for i in 0..17 {
            assert!((x[i] - reference[i]).abs() < 1e-13, "{i}");
        }
        let mut y = vec![0.0; 17];
        a.mul_add(1.0, &x, &mut y);
        for i in 0..17 {
            assert!((y[i] - b[i]).abs() < 1e-12);
        }
    }

    #[test]
    fn a_load_at_the_far_end_solves_like_a_dense_factorisation() {
        let a = sample(17, 3);
        let mut b = vec![0.0; 17];
        b[15] = 1.0;
        b[16] = -2.0;
        let reference = (a.to_dense().lu())
            .solve(&nalgebra::DVector::from_vec(b.clone()))
            .unwrap();
        BandLdlt::new(&a).unwrap().solve_in_place(&mut b);
        for i in 0..17 {
            assert!((b[i] - reference[i]).abs() < 1e-13, "{i}");
        }
    }

    #[test]
    fn a_row_of_the_product_is_the_whole_product_s_to_the_bit() {
        let a = sample(11, 3);
        let x: Vec<f64> = (0..11).map(|i| (1.3 * i as f64).cos()).collect();
        let y0: Vec<f64> = (0..11).map(|i| 0.1 * i as f64 - 0.4).collect();
        let mut y = y0.clone();
        a.mul_add(-0.7, &x, &mut y);
        for i in 0..11 {
            assert_eq!(
                a.mul_add_row(-0.7, &x, i, y0[i]).to_bits(),
                y[i].to_bits(),
                "{i}"
            );
        }
    }

    #[test]
    fn refactorising_in_place_equals_a_fresh_factorisation() {
        let (a, mut b) = (sample(12, 3), sample(12, 3));
        b.add(5, 5, 3.0);
        let mut f = BandLdlt::new(&a).unwrap();
        assert!(f.refactorise(&b));
        let (mut x, mut y) = (vec![1.0; 12], vec![1.0; 12]);
        f.solve_in_place(&mut x);
        BandLdlt::new(&b).unwrap().solve_in_place(&mut y);
        assert_eq!(x, y);
    }

    #[test]
    fn an_indefinite_nonsingular_matrix_factorises_and_a_singular_one_is_refused() {
        // [[1, 2], [2, 1]] (eigenvalues 3, -1) next to an identity row and a large
        // entry: the pivots are checked against their own diagonal.
        let mut a = SymmetricBand::zeros(3, 1);
        a.add(0, 0, 1.0);
        a.add(1, 0, 2.0);
        a.add(1, 1, 1.0);
        a.add(2, 2, 1e12);
        assert!(BandLdlt::new(&a).is_none(), "not positive definite");
        let mut f = BandLdlt::zeros(3, 1);
        assert!(f.refactorise_nonsingular(&a));
        let mut x = vec![3.0, 3.0, 2e12];
        f.solve_in_place(&mut x);
        for (got, want) in x.iter().zip([1.0, 1.0, 2.0]) {
            assert!((got - want).abs() < 1e-12, "{x:?}");
        }
        let mut singular = SymmetricBand::zeros(2, 1);
        singular.add(0, 0, 1.0);
        singular.add(1, 0, 1.0);
        singular.add(1, 1, 1.0);
        assert!(!BandLdlt::zeros(2, 1).refactorise_nonsingular(&singular));
    }

    #[test]
    fn the_quadratic_form_equals_x_dot_a_x() {
        let a = sample(9, 3);
        let x: Vec<f64> = (0..9).map(|i| (i as f64 * 0.7).cos()).collect();
        let mut ax = vec![0.0; 9];
        a.mul_add(1.0, &x, &mut ax);
        let direct: f64 = ax.iter().zip(&x).map(|(p, q)| p * q).sum();
        assert!((a.quadratic_form(&x) - direct).abs() < 1e-12 * direct.abs());
    }

    #[test]
    fn an_indefinite_matrix_is_refused() {
        let mut a = SymmetricBand::zeros(2, 1);
        a.add(0, 0, 1.0);
        a.add(1, 1, 1.0);
        a.add(1, 0, 2.0);
        assert!(BandLdlt::new(&a).is_none());
    }
}
