//! The lowest eigenpairs of a banded symmetric pencil K phi = w^2 M phi by
//! subspace iteration (Bathe and Wilson) with a Sturm sequence check.
//!
//! An iteration costs O(n b q) for n DOFs, half-bandwidth b and q vectors,
//! where the dense reduction of [`super::modal`] costs O(n^3): at the 1 200
//! DOFs of a 400-element section the dense path took 1.4 s, most of a 10 s
//! run of a reduced section (BENCHMARKS.md). Where the iteration does not
//! settle (eigenvalues repeated to round-off) or the Sturm check finds a mode
//! it missed, it gives up and the caller takes the dense path.

use super::banded::{BandLdlt, SymmetricBand};
use super::modal::lowest_modes;
use nalgebra::DMatrix;

/// Iterations before the subspace is given up on.
const MAX_ITERATIONS: usize = 300;

/// The largest change, between two iterations, of a wanted vector (M-norm,
/// vectors M-normalised) at which the iteration has converged.
const VECTOR_TOLERANCE: f64 = 1e-10;

/// The Sturm check's shift above the last wanted eigenvalue, relative: a
/// next eigenvalue closer than this makes the check fail (the dense path then
/// decides).
const STURM_MARGIN: f64 = 1e-7;

/// The `count` lowest eigenpairs (w^2, phi) of K phi = w^2 M phi with the DOFs
/// `held` fixed (phi zero there), lowest first, each phi M-normalised with its
/// largest entry positive. `None` when K with the held DOFs fixed is not
/// positive definite, the iteration does not converge in `MAX_ITERATIONS`, or
/// the Sturm check counts other than `count` eigenvalues up to the last one.
pub fn lowest_banded_modes(
    k: &SymmetricBand,
    m: &SymmetricBand,
    held: &[usize],
    count: usize,
) -> Option<Vec<(f64, Vec<f64>)>> {
    let n = k.size();
    let mut is_held = vec![false; n];
    held.iter().for_each(|&d| is_held[d] = true);
    let free = is_held.iter().filter(|h| !**h).count();
    let p = count.min(free);
    if p == 0 {
        return Some(Vec::new());
    }
    let q = (2 * p).max(p + 8).min(free);
    let mut fixed = k.clone();
    held.iter().for_each(|&d| fixed.set_identity_row(d));
    let factor = BandLdlt::new(&fixed)?;
    let mut vectors = start_vectors(m, &is_held, q);
    let mut previous: Option<Vec<Vec<f64>>> = None;
    for _ in 0..MAX_ITERATIONS {
        let (values, next) = ritz_step(&factor, m, &is_held, &vectors)?;
        let settled = previous
            .as_ref()
            .is_some_and(|old| (0..p).all(|i| change(m, &old[i], &next[i]) <= VECTOR_TOLERANCE));
        if settled {
            let sigma = values[p - 1] * (1.0 + STURM_MARGIN);
            if eigenvalues_below(k, m, held, sigma)? != p {
                return None;
            }
            return Some(values.into_iter().zip(next).take(p).map(signed).collect());
        }
        previous = Some(next[..p].to_vec());
        vectors = next;
    }
    None
}

/// One iteration: X' = K^-1 M X, then Rayleigh-Ritz on X' (the q x q pencil
/// X'^T K X' = X'^T M X, X'^T M X'); the Ritz values, lowest first, and the
/// M-orthonormal Ritz vectors.
fn ritz_step(
    factor: &BandLdlt,
    m: &SymmetricBand,
    is_held: &[bool],
    vectors: &[Vec<f64>],
) -> Option<(Vec<f64>, Vec<Vec<f64>>)> {
    let q = vectors.len();
    let mut loads = Vec::with_capacity(q);
    let mut solved = Vec::with_capacity(q);
    for x in vectors {
        let load = times_mass(m, x, is_held);
        let mut s = load.clone();
        factor.solve_in_place(&mut s);
        loads.push(load);
        solved.push(s);
    }
    let mass_solved: Vec<Vec<f64>> = solved.iter().map(|s| times_mass(m, s, is_held)).collect();
    let symmetric = |a: &[Vec<f64>], b: &[Vec<f64>]| {
        DMatrix::from_fn(q, q, |i, j| 0.5 * (dot(&a[i], &b[j]) + dot(&a[j], &b[i])))
    };
    let stiffness = symmetric(&solved, &loads);
    let mass = symmetric(&solved, &mass_solved);
    let pairs = lowest_modes(&mass, &stiffness, q, "the subspace is degenerate").ok()?;
    let n = m.size();
    let mut values = Vec::with_capacity(q);
    let mut ritz = Vec::with_capacity(q);
    for (w2, c) in pairs {
        let mut x = vec![0.0; n];
        for (s, cj) in solved.iter().zip(c.iter()) {
            x.iter_mut().zip(s).for_each(|(xi, si)| *xi += cj * si);
        }
        if !(w2.is_finite() && x.iter().all(|v| v.is_finite())) {
            return None;
        }
        values.push(w2);
        ritz.push(x);
    }
    Some((values, ritz))
}

/// q start vectors, zero at the held DOFs: M's diagonal, then a fixed
/// pseudo-random sequence (every mode present in it).
fn start_vectors(m: &SymmetricBand, is_held: &[bool], q: usize) -> Vec<Vec<f64>> {
    let n = m.size();
    (0..q)
        .map(|j| {
            (0..n)
                .map(|i| match (is_held[i], j) {
                    (true, _) => 0.0,
                    (false, 0) => m.get(i, i),
                    (false, _) => pseudo_random(i, j),
                })
                .collect()
        })
        .collect()
}

/// A number in [-0.5, 0.5) from (i, j), the same on every run.
fn pseudo_random(i: usize, j: usize) -> f64 {
    let mut h = (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ (j as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F);
    h ^= h >> 29;
    h = h.wrapping_mul(0xBF58_476D_1CE4_E5B9);
    h ^= h >> 32;
    (h >> 11) as f64 / (1u64 << 53) as f64 - 0.5
}

/// M x with the held rows zero.
fn times_mass(m: &SymmetricBand, x: &[f64], is_held: &[bool]) -> Vec<f64> {
    let mut y = vec![0.0; x.len()];
    m.mul_add(1.0, x, &mut y);
    y.iter_mut()
        .zip(is_held)
        .filter(|(_, h)| **h)
        .for_each(|(v, _)| *v = 0.0);
    y
}

/// The M-norm of the difference of two M-normalised vectors, either sign.
fn change(m: &SymmetricBand, old: &[f64], new: &[f64]) -> f64 {
    let sign = if dot(old, new) < 0.0 { -1.0 } else { 1.0 };
    let d: Vec<f64> = new.iter().zip(old).map(|(a, b)| a - sign * b).collect();
    m.quadratic_form(&d).max(0.0).sqrt()
}

/// The eigenvalues of the pencil (held DOFs fixed) below `sigma`: the negative
/// pivots of K - sigma M; `None` when that factor does not exist.
fn eigenvalues_below(
    k: &SymmetricBand,
    m: &SymmetricBand,
    held: &[usize],
    sigma: f64,
) -> Option<usize> {
    let n = k.size();
    let w = k.half_bandwidth().max(m.half_bandwidth());
    let mut shifted = SymmetricBand::zeros(n, w);
    for i in 0..n {
        for j in i.saturating_sub(w)..=i {
            shifted.add(i, j, k.get(i, j) - sigma * m.get(i, j));
        }
    }
    held.iter().for_each(|&d| shifted.set_identity_row(d));
    let mut factor = BandLdlt::zeros(n, w);
    factor
        .refactorise_nonsingular(&shifted)
        .then(|| factor.negative_pivots())
}

/// The pair with phi's largest entry positive.
fn signed((w2, mut phi): (f64, Vec<f64>)) -> (f64, Vec<f64>) {
    let largest = phi
        .iter()
        .fold(0.0f64, |a, &v| if v.abs() > a.abs() { v } else { a });
    if largest < 0.0 {
        phi.iter_mut().for_each(|v| *v = -*v);
    }
    (w2, phi)
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

#[cfg(test)]
#[path = "subspace_tests.rs"]
mod tests;
