//! The distribution of an expansion's output: the surrogate evaluated on a
//! large Sobol' sample of the inputs (cheap: no co-simulation), as quantiles
//! and a density histogram (seed 000's Fig. 9 shows the outputs' distribution).

use crate::UqError;
use crate::design::sobol;
use crate::marginal::Marginal;
use crate::pce::Pce;
use serde::Serialize;

/// Quantiles and a histogram of a surrogate's output.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Distribution {
    /// Surrogate evaluations the figures come from.
    pub samples: usize,
    /// The 5 %, 50 % and 95 % quantiles.
    pub quantiles: [f64; 3],
    /// Bins' lower edges; the last bin ends at `upper`.
    pub edges: Vec<f64>,
    /// The last bin's upper edge.
    pub upper: f64,
    /// Probability density in each bin (integrates to 1 over the bins).
    pub density: Vec<f64>,
}

/// `pce`'s output distribution over `n` Sobol' points (seeded) of the inputs
/// `marginals`, in `bins` equal bins between the smallest and largest value.
pub fn distribution(
    pce: &Pce,
    marginals: &[Marginal],
    n: usize,
    bins: usize,
    seed: u64,
) -> Result<Distribution, UqError> {
    if bins == 0 {
        return Err(UqError::input("distribution", "expected at least one bin"));
    }
    if marginals.len() != pce.families.len() {
        return Err(UqError::input(
            "distribution",
            format!(
                "{} marginals for an expansion in {} inputs",
                marginals.len(),
                pce.families.len()
            ),
        ));
    }
    let design = sobol(n, marginals.len(), seed)?;
    let mut values: Vec<f64> = design
        .iter()
        .map(|u| {
            let xi: Vec<f64> = marginals
                .iter()
                .zip(u)
                .map(|(m, &u)| m.to_standard(m.from_unit(u)))
                .collect();
            pce.eval(&xi)
        })
        .filter(|v| v.is_finite())
        .collect();
    if values.len() < 2 {
        return Err(UqError::input("distribution", "no finite surrogate values"));
    }
    values.sort_by(f64::total_cmp);
    let quantile = |p: f64| values[((p * (values.len() - 1) as f64).round()) as usize];
    let (lo, hi) = (values[0], values[values.len() - 1]);
    let width = ((hi - lo) / bins as f64).max(f64::MIN_POSITIVE);
    let mut counts = vec![0usize; bins];
    for v in &values {
        counts[(((v - lo) / width) as usize).min(bins - 1)] += 1;
    }
    Ok(Distribution {
        samples: values.len(),
        quantiles: [quantile(0.05), quantile(0.5), quantile(0.95)],
        edges: (0..bins).map(|k| lo + k as f64 * width).collect(),
        upper: hi,
        density: counts
            .iter()
            .map(|&c| c as f64 / (values.len() as f64 * width))
            .collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::basis::Family;

    fn linear(families: Vec<Family>, coefficients: Vec<f64>) -> Pce {
        let dims = families.len();
        let indices = (0..=dims)
            .map(|k| (0..dims).map(|j| usize::from(k == j + 1)).collect())
            .collect();
        Pce {
            families,
            indices,
            coefficients,
            degree: 1,
            loo_error: 0.0,
        }
    }

    #[test]
    fn a_linear_expansion_has_its_inputs_quantiles_and_a_normalised_density() {
        // y = 2 + 3 xi, xi standard normal (He_1 = xi): quantiles 2 -+ 3 x 1.645.
        let normal = Marginal::Normal {
            mean: 10.0,
            sd: 4.0,
        };
        let d = distribution(
            &linear(vec![Family::Hermite], vec![2.0, 3.0]),
            &[normal],
            4096,
            40,
            1,
        )
        .unwrap();
        let z95 = 1.6448536;
        let expected = [2.0 - 3.0 * z95, 2.0, 2.0 + 3.0 * z95];
        for (q, e) in d.quantiles.iter().zip(expected) {
            assert!((q - e).abs() < 0.02, "{:?} vs {expected:?}", d.quantiles);
        }
        let width = (d.upper - d.edges[0]) / 40.0;
        let total: f64 = d.density.iter().map(|p| p * width).sum();
        assert!((total - 1.0).abs() < 1e-12);
        // The peak bin holds the density of N(2, 3) at its centre, 0.133.
        let peak = d.density.iter().copied().fold(0.0, f64::max);
        assert!(
            (peak - 1.0 / (3.0 * (2.0 * std::f64::consts::PI).sqrt())).abs() < 0.01,
            "{peak}"
        );
        // Two uniform inputs, coefficients 1 on sqrt(3) P_1: y = sqrt(3) (xi1 +
        // xi2) with xi on [-1, 1]^2, a triangle.
        let uniform = Marginal::Uniform {
            low: 0.0,
            high: 1.0,
        };
        let s3 = 3f64.sqrt();
        let d = distribution(
            &linear(vec![Family::Legendre; 2], vec![0.0, 1.0, 1.0]),
            &[uniform.clone(), uniform],
            4096,
            20,
            2,
        )
        .unwrap();
        assert!(d.quantiles[1].abs() < 0.01);
        // P(y < q05) = 0.05 for the triangle on [-2 sqrt 3, 2 sqrt 3].
        let q05 = s3 * (-2.0 + (0.4f64).sqrt());
        assert!(
            (d.quantiles[0] - q05).abs() < 0.02,
            "{} vs {q05}",
            d.quantiles[0]
        );
        assert!(
            distribution(
                &linear(vec![Family::Legendre], vec![0.0, 1.0]),
                &[Marginal::Uniform {
                    low: 0.0,
                    high: 1.0
                }],
                100,
                0,
                1
            )
            .is_err()
        );
    }
}
