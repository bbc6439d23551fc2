//! B1: two masses and three springs cut at the middle spring, against the analytic
//! solution and against the monolithic solution of the same integrator.

use slender_coupling::settings::{Acceleration, Scheme};
use slender_tests::{Chain, SCHEMES, b1_exact, load, order, run_with};

const SCENE: &str = "examples/b1_two_masses.toml";
const PI: f64 = std::f64::consts::PI;

fn chain() -> Chain {
    Chain {
        m: [1.0, 1.0],
        k: [4.0 * PI * PI, 4.0 * PI * PI],
        c: [0.0, 0.0],
        kc: 16.0 * PI * PI,
        dc: 0.0,
        u0: [1.0, 0.0],
        v0: [0.0, 0.0],
    }
}

/// Largest displacement error against the analytic solution over the run.
fn max_error(scheme: Scheme, step: f64) -> f64 {
    let mut scene = load(SCENE);
    let s = run_with(&mut scene, scheme, Acceleration::None, step);
    assert!(s.error.is_none(), "{scheme:?} at {step}: {:?}", s.error);
    s.time
        .iter()
        .zip(
            s.get("left.displacement")
                .iter()
                .zip(s.get("right.displacement")),
        )
        .map(|(&t, (&u1, &u2))| {
            let (e1, e2) = b1_exact(t);
            (u1 - e1).abs().max((u2 - e2).abs())
        })
        .fold(0.0, f64::max)
}

#[test]
fn error_order_is_one_for_non_iterative_and_two_for_iterative_schemes() {
    let steps = [0.01, 0.005, 0.0025];
    eprintln!("B1 max displacement error over 1 s against the analytic solution");
    eprintln!(
        "{:<24} {:>10} {:>10} {:>10} {:>6}",
        "scheme", "h=0.01", "h=0.005", "h=0.0025", "order"
    );
    for scheme in SCHEMES {
        let e: Vec<f64> = steps.iter().map(|&h| max_error(scheme, h)).collect();
        let p = order(e[1], e[2]);
        eprintln!(
            "{:<24} {:>10.3e} {:>10.3e} {:>10.3e} {:>6.2}",
            scheme.name(),
            e[0],
            e[1],
            e[2],
            p
        );
        if scheme.is_iterative() {
            assert!((p - 2.0).abs() < 0.1, "{scheme:?}: order {p}, errors {e:?}");
        } else {
            assert!(
                (p - 1.0).abs() < 0.15,
                "{scheme:?}: order {p}, errors {e:?}"
            );
        }
    }
}

#[test]
fn iterative_schemes_converge_to_the_monolithic_newmark_solution() {
    let h = 0.01;
    let reference = chain().monolithic(h, 100);
    for scheme in [Scheme::IterativeJacobi, Scheme::IterativeGaussSeidel] {
        let mut scene = load(SCENE);
        let s = run_with(&mut scene, scheme, Acceleration::None, h);
        let (u1, u2) = (s.get("left.displacement"), s.get("right.displacement"));
        let worst = (0..100)
            .map(|i| {
                (u1[i + 1] - reference[i][0])
                    .abs()
                    .max((u2[i + 1] - reference[i][1]).abs())
            })
            .fold(0.0, f64::max);
        eprintln!(
            "{}: largest difference to monolithic Newmark {worst:.2e} m",
            scheme.name()
        );
        // Tolerance 1e-10 m per step, accumulated over 100 steps.
        assert!(worst < 1e-8, "{scheme:?}: {worst}");
        assert_eq!(s.counters.non_converged_steps, 0);
    }
}

#[test]
fn tighter_tolerance_brings_the_coupled_solution_closer_to_monolithic() {
    let reference = chain().monolithic(0.01, 100);
    let mut previous = f64::INFINITY;
    for tol in [1e-4, 1e-7, 1e-10] {
        let mut scene = load(SCENE);
        scene.spec.master.tolerances.displacement = tol;
        let s = run_with(
            &mut scene,
            Scheme::IterativeGaussSeidel,
            Acceleration::None,
            0.01,
        );
        let u1 = s.get("left.displacement");
        let worst = (0..100)
            .map(|i| (u1[i + 1] - reference[i][0]).abs())
            .fold(0.0, f64::max);
        eprintln!(
            "tolerance {tol:.0e} m: difference to monolithic {worst:.2e} m, {:.2} iterations/step",
            s.counters.mean_iterations()
        );
        assert!(
            worst < previous,
            "tolerance {tol}: {worst} not below {previous}"
        );
        previous = worst;
    }
}

#[test]
fn the_scene_s_exact_indicator_is_its_error_against_the_analytic_solution() {
    // The scene carries the analytic solution as signals; its `exact`
    // indicator must be what the formula gives from the recorded motion.
    let s = slender_tests::run(&load(SCENE));
    let reported = slender_tests::exact::check_exact_indicator(
        &s,
        ["left.displacement", "right.displacement"],
        ["exact_left.value", "exact_right.value"],
        |t| b1_exact(t).into(),
    );
    eprintln!("B1 against its analytic solution: epsilon {reported:.4e}");
    assert!(reported > 0.0 && reported < 0.05, "{reported}");
}
