//! B2: undamped two-DOF oscillator with a stiff and a soft side; energy drift per
//! scheme and step size over 10 s (exact energy: 1e4 J, constant).

use slender_coupling::settings::{Acceleration, Scheme};
use slender_tests::{Chain, SCHEMES, load, run_with};

const SCENE: &str = "examples/b2_stiff_oscillator.toml";

fn chain() -> Chain {
    Chain {
        m: [1.0, 1.0],
        k: [10.0, 1000.0],
        c: [0.0, 0.0],
        kc: 100.0,
        dc: 0.0,
        u0: [0.0, 0.0],
        v0: [100.0, -100.0],
    }
}

/// Relative energy drift (E(T) - E(0)) / E(0) at T = 10 s.
fn drift(scheme: Scheme, step: f64) -> f64 {
    let mut scene = load(SCENE);
    scene.spec.master.tolerances.displacement = 1e-12;
    scene.spec.output.every = 1;
    let s = run_with(&mut scene, scheme, Acceleration::None, step);
    assert!(s.error.is_none(), "{scheme:?} at {step}: {:?}", s.error);
    let state = |name: &str| s.last(name);
    let end = [
        state("soft.displacement"),
        state("stiff.displacement"),
        state("soft.velocity"),
        state("stiff.velocity"),
    ];
    let e0 = chain().energy([0.0, 0.0, 100.0, -100.0]);
    (chain().energy(end) - e0) / e0
}

#[test]
fn iterative_schemes_conserve_energy_and_non_iterative_ones_drift_at_first_order() {
    let steps = [0.01, 0.005, 0.0025, 0.001];
    eprintln!("B2 relative energy drift after 10 s");
    eprint!("{:<24}", "scheme");
    for h in steps {
        eprint!(" {:>11}", format!("h={h}"));
    }
    eprintln!();
    for scheme in SCHEMES {
        let d: Vec<f64> = steps.iter().map(|&h| drift(scheme, h)).collect();
        eprint!("{:<24}", scheme.name());
        for x in &d {
            eprint!(" {x:>11.3e}");
        }
        eprintln!();
        if scheme.is_iterative() {
            // Trapezoidal rule conserves the energy of the linear system exactly;
            // what is left is the interface tolerance (1e-12 m).
            for (x, h) in d.iter().zip(steps) {
                assert!(x.abs() < 1e-8, "{scheme:?} at h = {h}: drift {x}");
            }
        } else {
            // Explicit coupling injects or removes energy; the drift shrinks with h.
            assert!(
                d[3].abs() > 1e-4,
                "{scheme:?}: drift {} unexpectedly small",
                d[3]
            );
            for w in d.windows(2) {
                assert!(
                    w[1].abs() < w[0].abs(),
                    "{scheme:?}: drift does not shrink: {d:?}"
                );
            }
        }
    }
}

#[test]
fn the_monolithic_reference_conserves_energy() {
    let c = chain();
    let states = c.monolithic(0.01, 1000);
    let e0 = c.energy([0.0, 0.0, 100.0, -100.0]);
    let last = *states.last().unwrap();
    assert!(((c.energy(last) - e0) / e0).abs() < 1e-12);
}

/// The scene's `exact` indicator (issue 28) is its error against the modal
/// solution, derived here from the chain's matrices (not the scene's numbers);
/// with the coupling iterated to convergence it falls as h^2 (Newmark's order).
#[test]
fn the_scene_s_exact_indicator_is_its_error_against_the_analytic_solution() {
    let pair = (
        ["soft.displacement", "stiff.displacement"],
        ["exact_soft.value", "exact_stiff.value"],
    );
    let epsilon = |s: &slender_tests::Series| {
        slender_tests::exact::check_exact_indicator(s, pair.0, pair.1, |t| chain().exact(t))
    };
    let scene_as_written = epsilon(&slender_tests::run(&load(SCENE)));
    eprintln!(
        "B2 (Gauss-Seidel, 1 ms) against its analytic solution: epsilon {scene_as_written:.4e}"
    );
    assert!(
        scene_as_written > 0.0 && scene_as_written < 0.1,
        "{scene_as_written}"
    );
    let converged = |h: f64| {
        let mut scene = load(SCENE);
        scene.spec.master.tolerances.displacement = 1e-13;
        epsilon(&run_with(
            &mut scene,
            Scheme::IterativeGaussSeidel,
            Acceleration::None,
            h,
        ))
    };
    let (coarse, fine) = (converged(2e-3), converged(1e-3));
    let order = slender_tests::order(coarse, fine);
    eprintln!("B2 iterated: epsilon {coarse:.3e} at 2 ms, {fine:.3e} at 1 ms, order {order:.2}");
    assert!((1.8..2.2).contains(&order), "{order}");
}
