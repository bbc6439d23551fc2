//! B6: an algebraic loop across two stateless units. Newton on the interface
//! solves it; plain fixed-point iteration cannot reach the root it repels.

use slender_coupling::settings::{Acceleration, JacobianUpdate, NewtonSettings, Scheme, Solver};
use slender_tests::{load, run_with};

const SCENE: &str = "examples/b6_algebraic_loop.toml";
/// Roots of c^2 - 1.8 c + 0.74 = 0.
fn roots() -> (f64, f64) {
    let d = (1.8f64 * 1.8 - 4.0 * 0.74).sqrt();
    ((1.8 - d) / 2.0, (1.8 + d) / 2.0)
}

fn newton() -> NewtonSettings {
    NewtonSettings {
        perturbation: 1e-7,
        jacobian: JacobianUpdate::EveryIteration,
        ..NewtonSettings::default()
    }
}

fn solve(scheme: Scheme, solver: impl Into<Solver>, first_guess: f64) -> slender_tests::Series {
    let mut scene = load(SCENE);
    start_at(&mut scene, first_guess);
    run_with(&mut scene, scheme, solver, 1.0)
}

/// Start values of every torn input consistent with the first guess of c (Jacobi
/// tears a and b as well).
fn start_at(scene: &mut slender_scene::Scene, c: f64) {
    scene.spec.units[0].inputs.insert("c".into(), c);
    scene.spec.units[1].inputs.insert("a".into(), 1.8 - c);
    scene.spec.units[1].inputs.insert("b".into(), -1.8);
}

#[test]
fn newton_finds_the_root_next_to_the_first_guess() {
    let (small, large) = roots();
    for scheme in [Scheme::IterativeJacobi, Scheme::IterativeGaussSeidel] {
        for (guess, root) in [(0.6, small), (1.0, large)] {
            let s = solve(scheme, newton(), guess);
            assert!(s.error.is_none(), "{scheme:?} from {guess}: {:?}", s.error);
            let (a, b, c) = (s.last("pair.a"), s.last("pair.b"), s.last("sphere.c"));
            eprintln!(
                "{} newton from c = {guess}: c = {c:.12} (exact {root:.12}), {} iterations at t = 0, {} Jacobians",
                scheme.name(),
                s.counters.initialization_iterations,
                s.counters.jacobian_evaluations
            );
            assert!(
                (c - root).abs() < 1e-10,
                "{scheme:?}: c = {c}, expected {root}"
            );
            assert!((a + b + c).abs() < 1e-10);
            assert!((2.0 * a - 3.0 * b + 2.0 * c - 9.0).abs() < 1e-10);
            assert!((a * a + b * b + c * c - 5.0).abs() < 1e-9);
            assert!(s.counters.initialization_iterations <= 8);
        }
    }
}

#[test]
fn plain_fixed_point_is_reported_as_not_converging_to_the_repelling_root() {
    let (small, large) = roots();
    for scheme in [Scheme::IterativeJacobi, Scheme::IterativeGaussSeidel] {
        // From c = 0.6 the map c -> sphere(pair(c)) moves away from 0.635 (slope
        // 1.83) until a^2 + b^2 > 5: the sphere unit then has no real c.
        let s = solve(scheme, Acceleration::None, 0.6);
        let error = s.error.expect("fixed point must fail from 0.6");
        eprintln!("{} fixed point from 0.6: {error}", scheme.name());
        assert!(
            error.contains("sphere") && error.contains("no real c"),
            "{error}"
        );
        assert!(
            s.time.is_empty(),
            "nothing is recorded before a consistent start"
        );
        // It does converge, but only to the attracting root (slope 0.55 per loop,
        // so about 0.74 per Jacobi sweep: allow enough iterations for 1e-12).
        let mut scene = load(SCENE);
        start_at(&mut scene, 1.0);
        scene.spec.master.max_iterations = 200;
        let s = run_with(&mut scene, scheme, Acceleration::None, 1.0);
        assert!(s.error.is_none(), "{:?}", s.error);
        assert!((s.last("sphere.c") - large).abs() < 1e-10);
        assert!((s.last("sphere.c") - small).abs() > 0.5);
    }
}

#[test]
fn a_cap_on_iterations_is_reported_with_the_connection_that_did_not_settle() {
    let mut scene = load(SCENE);
    start_at(&mut scene, 1.0);
    scene.spec.master.max_iterations = 3;
    let s = run_with(
        &mut scene,
        Scheme::IterativeGaussSeidel,
        Acceleration::None,
        1.0,
    );
    let error = s.error.expect("3 iterations cannot reach 1e-12");
    assert!(
        error.contains("did not converge in 3 iterations"),
        "{error}"
    );
    assert!(error.contains("->"), "{error}");
}

#[test]
fn the_scene_s_exact_indicator_finds_the_root_newton_reaches() {
    let s = slender_tests::run(&load(SCENE));
    assert!(s.error.is_none(), "{:?}", s.error);
    let exact = s
        .indicators
        .iter()
        .find(|i| i.name == "exact")
        .expect("the scene's exact indicator");
    assert!((s.last("exact_c.value") - roots().0).abs() < 1e-15);
    assert!(exact.relative_error < 1e-10, "{}", exact.relative_error);
}
