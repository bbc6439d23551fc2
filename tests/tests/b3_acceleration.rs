//! B3: double mass-spring-damper in force/displacement coupling. Accuracy of
//! Jacobi, Gauss-Seidel and iterative schemes against the monolithic solution, and
//! iterations needed for a tolerance with and without acceleration.

use slender_coupling::settings::{Acceleration, JacobianUpdate, NewtonSettings, Scheme, Solver};
use slender_tests::{b3_chain, load, run_with};

const SCENE: &str = "examples/b3_force_displacement.toml";

/// Largest difference of both displacements to the monolithic solution (m).
fn difference(s: &slender_tests::Series, h: f64) -> f64 {
    let steps = s.time.len() - 1;
    let reference = b3_chain().monolithic(h, steps);
    let (u1, u2) = (s.get("a.displacement"), s.get("b.displacement"));
    (0..steps)
        .map(|i| {
            (u1[i + 1] - reference[i][0])
                .abs()
                .max((u2[i + 1] - reference[i][1]).abs())
        })
        .fold(0.0, f64::max)
}

/// Sets the force tolerance and the matching displacement and velocity ones: the
/// interface force changes by kc = 3e4 N per metre and dc = 10 N per m/s.
fn tighten(scene: &mut slender_scene::Scene, force: f64) {
    let t = &mut scene.spec.master.tolerances;
    t.force = force;
    t.displacement = force / 3e4;
    t.velocity = force / 10.0;
}

/// Every fixed-point acceleration and Newton, named.
fn accelerations() -> Vec<(&'static str, Solver)> {
    vec![
        ("none", Solver::FixedPoint(Acceleration::None)),
        (
            "constant 0.7",
            Solver::FixedPoint(Acceleration::Constant { factor: 0.7 }),
        ),
        (
            "aitken",
            Solver::FixedPoint(Acceleration::Aitken {
                initial_factor: 0.5,
            }),
        ),
        (
            "iqn_ils",
            Solver::FixedPoint(Acceleration::IqnIls {
                initial_factor: 0.5,
                reuse_steps: 0,
            }),
        ),
        (
            "iqn_ils reuse 8",
            Solver::FixedPoint(Acceleration::IqnIls {
                initial_factor: 0.5,
                reuse_steps: 8,
            }),
        ),
        (
            "newton",
            Solver::Newton(NewtonSettings {
                perturbation: 1e-7,
                jacobian: JacobianUpdate::EveryIteration,
                ..NewtonSettings::default()
            }),
        ),
    ]
}

#[test]
fn iterative_schemes_match_monolithic_where_explicit_ones_do_not() {
    let h = 0.001;
    eprintln!("B3 largest displacement difference to monolithic Newmark (h = {h} s)");
    let mut errors = Vec::new();
    for scheme in slender_tests::SCHEMES {
        let mut scene = load(SCENE);
        scene.spec.master.max_iterations = 200;
        tighten(&mut scene, 1e-9);
        let acc = if scheme.is_iterative() {
            Acceleration::Aitken {
                initial_factor: 0.5,
            }
        } else {
            Acceleration::None
        };
        let s = run_with(&mut scene, scheme, acc, h);
        let d = s
            .error
            .as_ref()
            .map_or(difference(&s, h), |_| f64::INFINITY);
        eprintln!(
            "  {:<24} {d:.3e} m ({:.2} iterations/step)",
            scheme.name(),
            s.counters.mean_iterations()
        );
        errors.push((scheme, d));
    }
    for (scheme, d) in errors {
        if scheme.is_iterative() {
            assert!(d < 1e-10, "{scheme:?}: {d}");
        } else {
            // The explicit coupling of this stiff interface is far off (or unstable).
            assert!(d > 1e-5, "{scheme:?}: {d}");
        }
    }
}

#[test]
fn acceleration_cuts_the_iterations_needed_for_a_tolerance() {
    let h = 0.01;
    eprintln!("B3 mean iterations per step (iterative Gauss-Seidel, h = {h} s) by force tolerance");
    eprintln!(
        "  {:<16} {:>8} {:>8} {:>8}   difference to monolithic at 1e-9 N",
        "acceleration", "1e-3 N", "1e-6 N", "1e-9 N"
    );
    let mut table = Vec::new();
    for (name, acc) in accelerations() {
        let mut means = Vec::new();
        let mut diff = 0.0;
        for tol in [1e-3, 1e-6, 1e-9] {
            let mut scene = load(SCENE);
            scene.spec.master.max_iterations = 200;
            tighten(&mut scene, tol);
            let s = run_with(&mut scene, Scheme::IterativeGaussSeidel, acc.clone(), h);
            assert!(s.error.is_none(), "{name} at {tol}: {:?}", s.error);
            assert_eq!(s.counters.non_converged_steps, 0);
            means.push(s.counters.mean_iterations());
            diff = difference(&s, h);
        }
        eprintln!(
            "  {name:<16} {:>8.2} {:>8.2} {:>8.2}   {diff:.2e} m",
            means[0], means[1], means[2]
        );
        assert!(diff < 1e-10, "{name}: {diff}");
        table.push((name, means));
    }
    let plain = &table[0].1;
    for (name, means) in &table[1..] {
        for (m, p) in means.iter().zip(plain) {
            assert!(
                m < p,
                "{name}: {m} iterations/step, not fewer than plain {p}"
            );
        }
    }
}

/// The scene's `exact` indicator (issue 28) is its error against the damped
/// modal solution, derived here from the chain's matrices; at the scene's 10 ms
/// the (1, -1) mode (245 rad/s, w h = 2.45) is poorly resolved, and with the
/// step the error falls as h^2 (Newmark's order).
#[test]
fn the_scene_s_exact_indicator_is_its_error_against_the_analytic_solution() {
    let pair = (
        ["a.displacement", "b.displacement"],
        ["exact_a.value", "exact_b.value"],
    );
    let epsilon = |s: &slender_tests::Series| {
        slender_tests::exact::check_exact_indicator(s, pair.0, pair.1, |t| b3_chain().exact(t))
    };
    let scene_as_written = epsilon(&slender_tests::run(&load(SCENE)));
    eprintln!("B3 (10 ms) against its analytic solution: epsilon {scene_as_written:.4e}");
    assert!(scene_as_written > 0.1, "{scene_as_written}");
    let at = |h: f64| {
        let mut scene = load(SCENE);
        scene.set_step(h).unwrap();
        epsilon(&slender_tests::run(&scene))
    };
    let (coarse, fine) = (at(1e-3), at(5e-4));
    let order = slender_tests::order(coarse, fine);
    eprintln!("B3: epsilon {coarse:.3e} at 1 ms, {fine:.3e} at 0.5 ms, order {order:.2}");
    assert!((1.8..2.2).contains(&order), "{order}");
    assert!(fine < 1e-2, "{fine}");
}
