//! Factorise-and-solve time of the nonlinear section's Newton matrix (seed 002's
//! cable in motion, 1 ms HHT step) with slender's band LDL^T and with faer's
//! sparse Cholesky (symbolic analysis once, numeric factorisation per matrix, as
//! a Newton iteration would), from 29 to 29 999 DOFs. Prints a Markdown table.

use faer::Side;
use faer::linalg::solvers::SolveCore;
use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
use faer::sparse::{SparseColMat, Triplet};
use slender_units::nonlinear::{NonlinearParams, NonlinearSection};
use slender_units::numerics::banded::{BandLdlt, SymmetricBand};
use slender_units::{Driver, Time};
use std::time::Instant;

fn newton_matrix(elements: usize) -> SymmetricBand {
    let text = format!(
        r#"
formulation = "corotational"
segments = [{{ length = 20.0, elements = {elements}, axial_stiffness = 4.1233e8, bending_stiffness = 6.4427e4, mass_per_length = 15.315 }}]
ends.start = {{ kind = "pinned" }}
ends.end = {{ kind = "pinned" }}
integrator = {{ kind = "hht", alpha = 0.05, tolerance = 1e-8 }}
loads = [{{ z = {{ amplitude = 300.0, angular_frequency = 1.6 }} }}]
"#
    );
    let params: NonlinearParams = toml::from_str(&text).expect("parameters");
    let mut driver = Driver::new(NonlinearSection::new(params).expect("section"));
    driver.initialize(Time::ZERO).expect("initialize");
    let h = Time::from_secs(1e-3).expect("step");
    let mut t = Time::ZERO;
    for _ in 0..200 {
        driver.do_step(t, h).expect("step");
        t += h;
    }
    driver.unit().newton_matrix().clone()
}

/// Median of `runs` timings (s) of `f`.
fn median(runs: usize, mut f: impl FnMut()) -> f64 {
    let mut times: Vec<f64> = (0..runs)
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed().as_secs_f64()
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[runs / 2]
}

/// The symmetric eigendecomposition (all pairs) of the dense Newton matrix, as
/// `slender modes` does after its Cholesky reduction: nalgebra against faer.
fn eigen_comparison() {
    println!();
    println!(
        "| DOFs | nalgebra SymmetricEigen (ms) | faer self_adjoint_eigen (ms) | faer / nalgebra | largest eigenvalue difference (relative) |"
    );
    println!("|---|---|---|---|---|");
    for elements in [10, 100, 400] {
        let a = newton_matrix(elements);
        let n = a.size();
        let dense = nalgebra::DMatrix::from_fn(n, n, |i, j| a.get(i.max(j), i.min(j)));
        let f = faer::Mat::<f64>::from_fn(n, n, |i, j| a.get(i.max(j), i.min(j)));
        let runs = if n < 1000 { 21 } else { 5 };
        let mut top_n = 0.0;
        let t_n = median(runs, || {
            let e = nalgebra::SymmetricEigen::new(dense.clone());
            top_n = e.eigenvalues.max();
        });
        let mut top_f = 0.0;
        let t_f = median(runs, || {
            let e = f.self_adjoint_eigen(Side::Lower).expect("evd");
            top_f = e
                .S()
                .column_vector()
                .iter()
                .fold(f64::NEG_INFINITY, |m, v| m.max(*v));
        });
        println!(
            "| {n} | {:.2} | {:.2} | {:.2} | {:.1e} |",
            t_n * 1e3,
            t_f * 1e3,
            t_f / t_n,
            ((top_f - top_n) / top_n).abs()
        );
    }
}

fn main() {
    println!(
        "| DOFs | band LDL^T (us) | faer sparse LLT (us) | faer / band | max difference of x |"
    );
    println!("|---|---|---|---|---|");
    for elements in [10, 100, 1000, 10_000] {
        let a = newton_matrix(elements);
        let n = a.size();
        let w = a.half_bandwidth();
        let rhs: Vec<f64> = (0..n).map(|i| 1.0 + (i % 7) as f64).collect();
        // Band LDL^T: refactorise in place and solve, as the integrator does.
        let mut band = BandLdlt::new(&a).expect("positive definite");
        let mut x_band = rhs.clone();
        let runs = if n < 1000 { 2001 } else { 201 };
        let t_band = median(runs, || {
            assert!(band.refactorise(&a));
            x_band.copy_from_slice(&rhs);
            band.solve_in_place(&mut x_band);
        });
        // faer: the lower triangle as a sparse matrix, symbolic once.
        let mut triplets = Vec::new();
        for i in 0..n {
            for j in i.saturating_sub(w)..=i {
                let v = a.get(i, j);
                if v != 0.0 {
                    triplets.push(Triplet::new(i, j, v));
                }
            }
        }
        let sparse =
            SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &triplets).expect("sparse");
        let symbolic = SymbolicLlt::try_new(sparse.symbolic(), Side::Lower).expect("symbolic");
        let mut x_faer = faer::Mat::<f64>::zeros(n, 1);
        let t_faer = median(runs, || {
            let llt = Llt::try_new_with_symbolic(symbolic.clone(), sparse.as_ref(), Side::Lower)
                .expect("llt");
            for i in 0..n {
                x_faer[(i, 0)] = rhs[i];
            }
            llt.solve_in_place_with_conj(faer::Conj::No, x_faer.as_mut());
        });
        let diff = (0..n).fold(0.0f64, |m, i| m.max((x_faer[(i, 0)] - x_band[i]).abs()));
        let scale = x_band.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        println!(
            "| {n} | {:.1} | {:.1} | {:.2} | {:.1e} |",
            t_band * 1e6,
            t_faer * 1e6,
            t_faer / t_band,
            diff / scale
        );
    }
    eigen_comparison();
}
