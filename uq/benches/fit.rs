//! Criterion benchmark: the sparse PCE fit of a twelve-input study of Table 2's
//! size (issue 14: 12 inputs, 832 points, degree up to 4, under 10 s), against
//! the same fit on the first 208 points (the baseline, same run), and the 200
//! bootstrap refits `slender uq` adds. Inputs: six normal (Hermite), six uniform
//! (Legendre); the output is smooth with a few interactions, like phi over
//! Table 2's artefacts. Run with `cargo bench -p slender-uq --bench fit`.

use criterion::{Criterion, criterion_group, criterion_main};
use slender_uq::basis::Family;
use slender_uq::bootstrap::intervals;
use slender_uq::design::latin_hypercube;
use slender_uq::marginal::Marginal;
use slender_uq::pce::{Settings, fit};
use std::hint::black_box;

const INPUTS: usize = 12;

/// (families, standard inputs, outputs) of `n` LHS points.
fn study(n: usize) -> (Vec<Family>, Vec<Vec<f64>>, Vec<f64>) {
    let marginals: Vec<Marginal> = (0..INPUTS)
        .map(|i| {
            if i < 6 {
                Marginal::Normal { mean: 0.0, sd: 1.0 }
            } else {
                Marginal::Uniform {
                    low: -1.0,
                    high: 1.0,
                }
            }
        })
        .collect();
    let design = latin_hypercube(n, INPUTS, 20, 5).expect("design");
    let xi: Vec<Vec<f64>> = design
        .iter()
        .map(|u| {
            marginals
                .iter()
                .zip(u)
                .map(|(m, &u)| m.to_standard(m.from_unit(u)))
                .collect()
        })
        .collect();
    let y = xi
        .iter()
        .map(|x| {
            let linear: f64 = x
                .iter()
                .enumerate()
                .map(|(i, v)| v / (1.0 + i as f64))
                .sum();
            1.3 + 0.1 * linear
                + 0.05 * x[0] * x[1]
                + 0.03 * x[8] * x[8]
                + 0.02 * (x[2] * x[8]).sin()
        })
        .collect();
    (marginals.iter().map(Marginal::family).collect(), xi, y)
}

fn settings() -> Settings {
    Settings {
        max_degree: 4,
        ..Settings::default()
    }
}

fn bench_fit(c: &mut Criterion) {
    let mut group = c.benchmark_group("pce_fit_12_inputs");
    group.sample_size(10);
    for n in [208, 832] {
        let (families, xi, y) = study(n);
        group.bench_function(format!("{n}_points"), |b| {
            b.iter(|| fit(black_box(&families), &xi, &y, settings()).expect("fit"))
        });
    }
    let (families, xi, y) = study(832);
    let pce = fit(&families, &xi, &y, settings()).expect("fit");
    group.bench_function("832_points_200_bootstrap_refits", |b| {
        b.iter(|| intervals(black_box(&pce), (&xi, &y), 200, 0.95, 1).expect("intervals"))
    });
    group.finish();
}

criterion_group!(benches, bench_fit);
criterion_main!(benches);
