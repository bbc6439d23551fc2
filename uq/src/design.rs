//! Latin hypercube designs on the unit cube [0, 1)^d.
//!
//! In an LHS of n points every one-dimensional projection has exactly one point
//! in each of the n strata [k / n, (k + 1) / n). [`latin_hypercube`] draws
//! `candidates` random ones from a seed and keeps the one whose closest pair of
//! points is farthest apart (maximin: space filling); [`double`] adds n points
//! to an n-point LHS so that the 2n points are again an LHS, keeping the first n
//! (the runs already done stay useful when a study grows). [`sobol`] takes the
//! first n points of a seeded Owen-scrambled Sobol' sequence instead: nested by
//! construction (a larger design starts with the smaller one), and its first 2^m
//! points put one point in each of the 2^m strata of every projection.

use crate::UqError;
use rand::{Rng, SeedableRng, seq::SliceRandom};
use rand_chacha::ChaCha8Rng;

/// A design: `points[i][j]` is coordinate j of point i, in [0, 1).
pub type Design = Vec<Vec<f64>>;

/// An n-point LHS in `dims` dimensions, the maximin best of `candidates` drawn
/// from `seed`.
pub fn latin_hypercube(
    n: usize,
    dims: usize,
    candidates: usize,
    seed: u64,
) -> Result<Design, UqError> {
    if n < 2 || dims == 0 || candidates == 0 {
        return Err(UqError::input(
            "latin hypercube",
            format!(
                "{n} points in {dims} dimensions from {candidates} candidates: expected n >= 2, dims >= 1, candidates >= 1"
            ),
        ));
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut best: Option<(f64, Design)> = None;
    for _ in 0..candidates {
        let design = random_lhs(n, dims, &mut rng);
        let spread = min_distance(&design);
        if best.as_ref().is_none_or(|(s, _)| spread > *s) {
            best = Some((spread, design));
        }
    }
    Ok(best.map(|(_, d)| d).unwrap_or_default())
}

/// One random LHS: per dimension a random permutation of the strata, a random
/// point within each.
fn random_lhs(n: usize, dims: usize, rng: &mut ChaCha8Rng) -> Design {
    let mut points = vec![vec![0.0; dims]; n];
    let mut strata: Vec<usize> = (0..n).collect();
    for j in 0..dims {
        strata.shuffle(rng);
        for (p, &k) in points.iter_mut().zip(&strata) {
            p[j] = (k as f64 + rng.random::<f64>()) / n as f64;
        }
    }
    points
}

/// The smallest distance between two points of a design.
pub fn min_distance(design: &Design) -> f64 {
    let mut best = f64::INFINITY;
    for (i, a) in design.iter().enumerate() {
        for b in &design[i + 1..] {
            let d: f64 = a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum();
            best = best.min(d);
        }
    }
    best.sqrt()
}

/// The design `design` (an n-point LHS) with n more points, drawn from `seed`,
/// such that the 2n points form an LHS: each stratum of width 1 / n splits in
/// two, the old point holds one half, a new point takes the other.
pub fn double(design: &Design, seed: u64) -> Result<Design, UqError> {
    let n = design.len();
    let dims = design.first().map_or(0, Vec::len);
    check_lhs(design).map_err(|why| UqError::input("design to double", why))?;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut added = vec![vec![0.0; dims]; n];
    for j in 0..dims {
        // The empty half-stratum of each old stratum, in the new 2n strata.
        let mut empty: Vec<usize> = design
            .iter()
            .map(|p| {
                let fine = ((p[j] * (2 * n) as f64) as usize).min(2 * n - 1);
                fine ^ 1
            })
            .collect();
        empty.shuffle(&mut rng);
        for (p, &k) in added.iter_mut().zip(&empty) {
            p[j] = (k as f64 + rng.random::<f64>()) / (2 * n) as f64;
        }
    }
    let mut out = design.clone();
    out.extend(added);
    Ok(out)
}

/// Most points of a Sobol' design (the sequence's limit).
pub const SOBOL_MAX_POINTS: usize = 1 << 16;
/// Most dimensions of a Sobol' design.
pub const SOBOL_MAX_DIMS: usize = sobol_burley::NUM_DIMENSIONS as usize;

/// The first `n` points of the Owen-scrambled Sobol' sequence `seed` in `dims`
/// dimensions (Burley's hash-based scrambling, Joe-Kuo direction numbers).
pub fn sobol(n: usize, dims: usize, seed: u64) -> Result<Design, UqError> {
    if !(2..=SOBOL_MAX_POINTS).contains(&n) || !(1..=SOBOL_MAX_DIMS).contains(&dims) {
        return Err(UqError::input(
            "sobol design",
            format!(
                "{n} points in {dims} dimensions: expected 2 to {SOBOL_MAX_POINTS} points in 1 to {SOBOL_MAX_DIMS} dimensions"
            ),
        ));
    }
    let seed = (seed ^ (seed >> 32)) as u32;
    Ok((0..n as u32)
        .map(|i| {
            (0..dims as u32)
                .map(|j| f64::from(sobol_burley::sample(i, j, seed)))
                .collect()
        })
        .collect())
}

/// Whether every one-dimensional projection has one point per stratum; the
/// error names the first dimension and stratum that does not.
pub fn check_lhs(design: &Design) -> Result<(), String> {
    let n = design.len();
    let dims = design.first().map_or(0, Vec::len);
    if n == 0 || design.iter().any(|p| p.len() != dims) {
        return Err(format!(
            "{n} points of unequal or zero dimension: expected an LHS"
        ));
    }
    for j in 0..dims {
        let mut seen = vec![false; n];
        for p in design {
            if !(0.0..1.0).contains(&p[j]) {
                return Err(format!("coordinate {j} = {} is outside [0, 1)", p[j]));
            }
            let k = ((p[j] * n as f64) as usize).min(n - 1);
            if std::mem::replace(&mut seen[k], true) {
                return Err(format!(
                    "dimension {j}: stratum {k} of {n} holds two points"
                ));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_projection_has_one_point_per_stratum_and_doubling_keeps_the_points() {
        let d = latin_hypercube(13, 4, 20, 7).unwrap();
        check_lhs(&d).unwrap();
        let twice = double(&d, 8).unwrap();
        check_lhs(&twice).unwrap();
        assert_eq!(&twice[..13], &d[..]);
        let four = double(&twice, 9).unwrap();
        check_lhs(&four).unwrap();
        assert_eq!(four.len(), 52);
        // Seeded: the same design again; maximin: no worse than one draw.
        assert_eq!(d, latin_hypercube(13, 4, 20, 7).unwrap());
        assert!(min_distance(&d) >= min_distance(&latin_hypercube(13, 4, 1, 7).unwrap()));
        let bad = vec![vec![0.1], vec![0.2]];
        assert!(check_lhs(&bad).unwrap_err().contains("stratum 0"));
        assert!(double(&bad, 1).is_err());
    }

    #[test]
    fn sobol_designs_are_nested_and_their_power_of_two_prefixes_stratified() {
        let d = sobol(256, 12, 3).unwrap();
        for m in 1..=8 {
            check_lhs(&d[..1 << m].to_vec()).unwrap();
        }
        assert_eq!(&sobol(64, 12, 3).unwrap()[..], &d[..64]);
        assert_ne!(sobol(64, 12, 4).unwrap(), d[..64]);
        // A quadrature rule: the mean of prod(2 x_j) over [0, 1)^4 is 1. Over
        // ten seeds, 256 Sobol' points miss it by 0.008 on average, random
        // LHS by 0.056 (quasi-Monte Carlo converges faster than 1 / sqrt(n)).
        let error = |d: &Design| {
            let sum: f64 = d
                .iter()
                .map(|p| p[..4].iter().map(|x| 2.0 * x).product::<f64>())
                .sum();
            (sum / d.len() as f64 - 1.0).abs()
        };
        let (mut qmc, mut lhs) = (0.0, 0.0);
        for seed in 0..10 {
            qmc += error(&sobol(256, 4, seed).unwrap()) / 10.0;
            lhs += error(&latin_hypercube(256, 4, 1, seed).unwrap()) / 10.0;
        }
        assert!(qmc < lhs / 3.0, "Sobol' {qmc}, LHS {lhs}");
        assert!(
            sobol(10, 257, 1)
                .unwrap_err()
                .to_string()
                .contains("256 dimensions")
        );
        assert!(sobol(1 << 17, 2, 1).is_err());
    }
}
