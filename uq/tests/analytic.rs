//! Sparse PCE against functions whose moments and Sobol' indices are known
//! (issue 14): the Ishigami function (a = 7, b = 0.1) and Sobol's g-function,
//! each from a 500-point maximin Latin hypercube.

use slender_uq::basis::Family;
use slender_uq::bootstrap::intervals;
use slender_uq::design::latin_hypercube;
use slender_uq::pce::{Settings, fit};
use std::f64::consts::PI;

/// Ishigami's moments and indices (Sobol' and Levitan 1999).
fn ishigami_truth(a: f64, b: f64) -> (f64, f64, [f64; 3], [f64; 3]) {
    let d1 = b * PI.powi(4) / 5.0 + b * b * PI.powi(8) / 50.0 + 0.5;
    let d2 = a * a / 8.0;
    let d13 = b * b * PI.powi(8) * (1.0 / 18.0 - 1.0 / 50.0);
    let d = d1 + d2 + d13;
    (
        a / 2.0,
        d,
        [d1 / d, d2 / d, 0.0],
        [(d1 + d13) / d, d2 / d, d13 / d],
    )
}

#[test]
fn ishigami_moments_and_sobol_indices_from_500_lhs_points() {
    let (a, b) = (7.0, 0.1);
    let design = latin_hypercube(500, 3, 20, 2026).unwrap();
    let xi: Vec<Vec<f64>> = design
        .iter()
        .map(|u| u.iter().map(|u| 2.0 * u - 1.0).collect())
        .collect();
    let y: Vec<f64> = xi
        .iter()
        .map(|x| {
            let (x1, x2, x3) = (PI * x[0], PI * x[1], PI * x[2]);
            x1.sin() + a * x2.sin().powi(2) + b * x3.powi(4) * x1.sin()
        })
        .collect();
    let pce = fit(&[Family::Legendre; 3], &xi, &y, Settings::default()).unwrap();
    let (mean, variance, first, total) = ishigami_truth(a, b);
    println!(
        "degree {}, {} terms, LOO {:.2e}; mean {:.4} ({mean:.4}), variance {:.4} ({variance:.4})",
        pce.degree,
        pce.coefficients.len(),
        pce.loo_error,
        pce.mean(),
        pce.variance()
    );
    assert!((pce.mean() - mean).abs() < 0.01 * mean);
    assert!((pce.variance() - variance).abs() < 0.01 * variance);
    for i in 0..3 {
        println!(
            "x{}: S {:.4} ({:.4}), T {:.4} ({:.4})",
            i + 1,
            pce.first_order(i),
            first[i],
            pce.total(i),
            total[i]
        );
        assert!((pce.first_order(i) - first[i]).abs() < 0.01);
        assert!((pce.total(i) - total[i]).abs() < 0.01);
    }
    // The surrogate predicts a point it was not fitted on.
    let x = [0.3, -0.7, 0.55];
    let want = (PI * x[0]).sin()
        + a * (PI * x[1]).sin().powi(2)
        + b * (PI * x[2]).powi(4) * (PI * x[0]).sin();
    assert!(
        (pce.eval(&x) - want).abs() < 0.05 * variance.sqrt(),
        "{} {want}",
        pce.eval(&x)
    );
}

/// The g-function's variance and first-order and total indices.
fn g_truth(coefficients: &[f64]) -> (f64, Vec<f64>, Vec<f64>) {
    let vi: Vec<f64> = coefficients
        .iter()
        .map(|a| 1.0 / (3.0 * (1.0 + a) * (1.0 + a)))
        .collect();
    let v = vi.iter().map(|v| 1.0 + v).product::<f64>() - 1.0;
    let total = (0..vi.len())
        .map(|i| {
            let others: f64 = (0..vi.len())
                .filter(|&j| j != i)
                .map(|j| 1.0 + vi[j])
                .product();
            vi[i] * others / v
        })
        .collect();
    (v, vi.iter().map(|x| x / v).collect(), total)
}

#[test]
fn g_function_moments_and_sobol_indices_from_500_lhs_points() {
    // g = prod (|4 x_i - 2| + a_i) / (1 + a_i), x_i ~ U(0, 1): mean 1,
    // V_i = 1 / (3 (1 + a_i)^2), V = prod (1 + V_i) - 1.
    let coefficients = [1.0, 2.0, 5.0, 10.0];
    let design = latin_hypercube(500, 4, 20, 7).unwrap();
    let y: Vec<f64> = design
        .iter()
        .map(|u| {
            u.iter()
                .zip(coefficients)
                .map(|(x, a)| ((4.0 * x - 2.0).abs() + a) / (1.0 + a))
                .product()
        })
        .collect();
    let xi: Vec<Vec<f64>> = design
        .iter()
        .map(|u| u.iter().map(|u| 2.0 * u - 1.0).collect())
        .collect();
    let pce = fit(&[Family::Legendre; 4], &xi, &y, Settings::default()).unwrap();
    let (v, first, total) = g_truth(&coefficients);
    println!(
        "degree {}, {} terms, LOO {:.2e}; mean {:.4}, variance {:.5} ({v:.5})",
        pce.degree,
        pce.coefficients.len(),
        pce.loo_error,
        pce.mean(),
        pce.variance()
    );
    assert!((pce.mean() - 1.0).abs() < 0.01);
    assert!((pce.variance() - v).abs() < 0.01 * v);
    // 95 % bootstrap intervals (200 resamples): each holds its estimate, and
    // the truth lies within 0.005 of it.
    let ci = intervals(&pce, (&xi, &y), 200, 0.95, 11).unwrap();
    let near = |(lo, hi): (f64, f64), estimate: f64, truth: f64| {
        assert!(lo <= estimate && estimate <= hi, "{lo} {estimate} {hi}");
        assert!(
            truth >= lo - 0.005 && truth <= hi + 0.005,
            "{truth} outside [{lo}, {hi}]"
        );
    };
    for i in 0..4 {
        let (s, t) = (first[i], total[i]);
        let (si, ti) = (pce.first_order(i), pce.total(i));
        println!(
            "x{}: S {si:.4} ({s:.4}) in [{:.4}, {:.4}], T {ti:.4} ({t:.4}) in [{:.4}, {:.4}]",
            i + 1,
            ci.first_order[i].0,
            ci.first_order[i].1,
            ci.total[i].0,
            ci.total[i].1
        );
        assert!((si - s).abs() < 0.01 && (ti - t).abs() < 0.01);
        near(ci.first_order[i], si, s);
        near(ci.total[i], ti, t);
    }
}
