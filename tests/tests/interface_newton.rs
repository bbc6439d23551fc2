//! Newton at the cuts with the units' interface Jacobians (issue 25): the
//! partitioned structures reproduce their monolithic twins to the coupling
//! tolerance as the fixed-point master does, in far fewer iterations; the
//! linear two-mass benchmark B3 matches its monolithic solution with one
//! Jacobian kept for a hundred steps.

use slender_coupling::settings::{Derivatives, JacobianUpdate, NewtonSettings, Scheme, Solver};
use slender_scene::Scene;
use slender_tests::{Series, impulsive, load, root, run, run_with};

/// `scene` (a path under the root, its text changed by `edit`) with its
/// `[master]` replaced by `master` and `[simulation] duration` by `duration`.
fn with_master(scene: &str, edit: fn(String) -> String, master: &str, duration: f64) -> Scene {
    let path = root().join(scene);
    let text = edit(impulsive(&std::fs::read_to_string(&path).unwrap()));
    let mut table: toml::Table = toml::from_str(&text).unwrap();
    table.insert(
        "master".into(),
        toml::Value::Table(toml::from_str(master).unwrap()),
    );
    table["simulation"]
        .as_table_mut()
        .unwrap()
        .insert("duration".into(), duration.into());
    Scene::parse(&path, toml::to_string(&table).unwrap()).unwrap_or_else(|e| panic!("{e}"))
}

/// The mooring line's same-mesh partition (both sections nonlinear) under
/// `master` for `duration` s; the run must complete.
fn mooring_same_mesh(master: &str, duration: f64) -> Series {
    let nonlinear = |text: String| text.replace("fidelity = \"cable\"", "fidelity = \"nonlinear\"");
    let s = run(&with_master(
        "examples/structure_mooring.toml",
        nonlinear,
        master,
        duration,
    ));
    assert!(s.error.is_none(), "{:?}", s.error);
    s
}

/// Iterative Jacobi with Newton on the units' Jacobians, every iteration.
fn newton_master(tolerances: &str) -> String {
    format!(
        "scheme = \"iterative_jacobi\"\nmax_iterations = 50\nextrapolation = \"linear\"\ntolerances = {tolerances}\nnewton = {{ derivatives = \"units\" }}"
    )
}

/// Today's fixed-point master of the same scene, for comparison.
fn iqn_master(tolerances: &str) -> String {
    format!(
        "scheme = \"iterative_gauss_seidel\"\nmax_iterations = 100\ntolerances = {tolerances}\nacceleration = {{ kind = \"iqn_ils\", reuse_steps = 0 }}"
    )
}

fn indicator(s: &Series, name: &str) -> f64 {
    assert!(s.error.is_none(), "{:?}", s.error);
    s.indicators
        .iter()
        .find(|i| i.name == name)
        .unwrap_or_else(|| panic!("no indicator {name}"))
        .relative_error
}

/// The mooring line cut at node 65 with both sections nonlinear at the whole
/// line's mesh; the angular velocity at the cut converged like the velocities.
#[test]
fn the_mooring_line_partition_matches_its_twin_in_two_iterations_per_step() {
    let tolerances = "{ velocity = 1e-6, force = 1.0, generic = 1e-6 }";
    let same_mesh = |master: String| mooring_same_mesh(&master, 10.0);
    let newton = same_mesh(newton_master(tolerances));
    let iqn = same_mesh(iqn_master(tolerances));
    let (e_newton, e_iqn) = (
        indicator(&newton, "top_force"),
        indicator(&iqn, "top_force"),
    );
    let (k_newton, k_iqn) = (
        newton.counters.mean_iterations(),
        iqn.counters.mean_iterations(),
    );
    println!(
        "mooring line, same mesh: Newton (unit Jacobians) epsilon {e_newton:.3e} in {k_newton:.2} iterations/step, IQN-ILS {e_iqn:.3e} in {k_iqn:.2}"
    );
    // The floor of the comparison (2.6e-6 over these 10 s) is the sections'
    // own (the cut node's force): both masters reach it.
    assert!(
        e_newton < 5e-6 && (e_newton - e_iqn).abs() < 1e-8,
        "{e_newton:e} {e_iqn:e}"
    );
    assert!(k_newton <= 2.1, "{k_newton}");
    assert!(k_iqn > 2.0 * k_newton, "{k_iqn}");
    let units = &newton.counters.units;
    let lower = units.iter().find(|u| u.name == "line_lower").unwrap();
    // Two sweeps a step and no probing steps: the Jacobian is the unit's own.
    assert!(lower.do_step_calls as f64 <= 2.1 * newton.counters.steps as f64);
}

/// The S-lay (stinger rollers, seabed contact) in three nonlinear sections.
#[test]
fn the_slay_partition_matches_its_twin_with_newton_at_the_cuts() {
    let tolerances = "{ velocity = 1e-7, force = 1e-2, generic = 1e-7 }";
    let newton = run(&with_master(
        "examples/structure_slay.toml",
        |t| t,
        &newton_master(tolerances),
        10.0,
    ));
    let iqn = run(&with_master(
        "examples/structure_slay.toml",
        |t| t,
        &iqn_master(tolerances),
        10.0,
    ));
    let (k_newton, k_iqn) = (
        newton.counters.mean_iterations(),
        iqn.counters.mean_iterations(),
    );
    for name in ["top_force", "sagbend"] {
        let (a, b) = (indicator(&newton, name), indicator(&iqn, name));
        println!("S-lay {name}: Newton {a:.4e}, IQN-ILS {b:.4e}");
        assert!((a - b).abs() <= 0.01 * b, "{name}: {a:e} against {b:e}");
    }
    println!("S-lay iterations/step: Newton {k_newton:.2}, IQN-ILS {k_iqn:.2}");
    assert!(
        k_newton <= 3.1 && k_iqn > 2.0 * k_newton,
        "{k_newton} {k_iqn}"
    );
}

/// B3 (two masses, force/displacement coupling; linear, so the units'
/// Jacobians are exact and constant): Newton on them matches the monolithic
/// Newmark solution under both schemes, and one Jacobian serves a hundred
/// steps.
#[test]
fn b3_with_unit_jacobians_matches_monolithic_and_reuses_one_jacobian() {
    let h = 0.01;
    for scheme in [Scheme::IterativeJacobi, Scheme::IterativeGaussSeidel] {
        for jacobian in [JacobianUpdate::EveryIteration, JacobianUpdate::Reuse] {
            let mut scene = load("examples/b3_force_displacement.toml");
            let t = &mut scene.spec.master.tolerances;
            (t.force, t.displacement, t.velocity) = (1e-9, 1e-9 / 3e4, 1e-10);
            let settings = NewtonSettings {
                derivatives: Derivatives::Units,
                jacobian,
                ..NewtonSettings::default()
            };
            let s = run_with(&mut scene, scheme, Solver::Newton(settings), h);
            assert!(s.error.is_none(), "{:?}", s.error);
            let steps = s.counters.steps;
            let reference = slender_tests::b3_chain().monolithic(h, steps as usize);
            let (u1, u2) = (s.get("a.displacement"), s.get("b.displacement"));
            let worst = (0..steps as usize)
                .map(|i| {
                    (u1[i + 1] - reference[i][0])
                        .abs()
                        .max((u2[i + 1] - reference[i][1]).abs())
                })
                .fold(0.0, f64::max);
            let k = s.counters.mean_iterations();
            let jacobians = s.counters.jacobian_evaluations;
            println!(
                "B3 {} {jacobian:?}: {worst:.2e} m, {k:.2} iterations/step, {jacobians} Jacobians in {steps} steps",
                scheme.name()
            );
            assert!(worst < 1e-10, "{worst:e}");
            // Predicted and corrected (Gauss-Seidel compares its untorn
            // connections with the sweep before, so it needs a third sweep);
            // one step more than that.
            let sweeps = if scheme == Scheme::IterativeJacobi {
                2.0
            } else {
                3.0
            };
            assert!(k <= sweeps + 1.0 / steps as f64, "{k}");
            if jacobian == JacobianUpdate::Reuse {
                // At the initialisation (from sweeps), then every 100 steps.
                assert!(jacobians <= 2 + steps / 100, "{jacobians}");
            }
        }
    }
}

/// The hanging pipe in three nonlinear sections at its twin's mesh.
#[test]
fn the_hanging_pipe_partition_matches_its_twin_with_newton_at_the_cuts() {
    let tolerances = "{ velocity = 1e-9, force = 1e-4, generic = 1e-9 }";
    let scene = "examples/structure_hanging_pipe.toml";
    let newton = run(&with_master(scene, |t| t, &newton_master(tolerances), 5.0));
    let iqn = run(&with_master(scene, |t| t, &iqn_master(tolerances), 5.0));
    let (a, b) = (indicator(&newton, "bottom"), indicator(&iqn, "bottom"));
    let (k_newton, k_iqn) = (
        newton.counters.mean_iterations(),
        iqn.counters.mean_iterations(),
    );
    println!(
        "hanging pipe bottom: Newton {a:.4e} in {k_newton:.2} iterations/step, IQN-ILS {b:.4e} in {k_iqn:.2}"
    );
    // Both at the coupling tolerance (1e-9 m/s over 5 s): the sections are the
    // twin's mesh.
    assert!(a < 1e-9 && b < 1e-9, "{a:e} against {b:e}");
    assert!(
        k_newton <= 3.5 && k_iqn > 2.0 * k_newton,
        "{k_newton} {k_iqn}"
    );
}

/// A Jacobi sweep's units stepped on two or three threads give the same bits
/// as stepped one after another.
#[test]
fn parallel_sweeps_are_bit_identical_to_sequential_ones() {
    let tolerances = "{ velocity = 1e-6, force = 1.0, generic = 1e-6 }";
    let run_on = |threads: u32| {
        mooring_same_mesh(
            &(newton_master(tolerances) + &format!("\nthreads = {threads}")),
            3.0,
        )
    };
    let one = run_on(1);
    for threads in [2, 3] {
        let many = run_on(threads);
        assert_eq!(one.names, many.names);
        for (a, b) in one.columns.iter().zip(&many.columns) {
            let same = a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits());
            assert!(same, "{threads} threads differ");
        }
        assert_eq!(one.counters.iterations, many.counters.iterations);
    }
}

/// A section repeating its step starts its Newton from its first attempt moved
/// by its Jacobian (`warm_start`, the default): the same results to the
/// sections' own Newton tolerance, in fewer Newton iterations.
#[test]
fn warm_started_repeats_save_section_newton_iterations() {
    let tolerances = "{ velocity = 1e-6, force = 1.0, generic = 1e-6 }";
    let run_with_warm = |warm: bool| {
        let master = newton_master(tolerances).replace(
            "derivatives = \"units\"",
            &format!("derivatives = \"units\", warm_start = {warm}"),
        );
        mooring_same_mesh(&master, 10.0)
    };
    let (warm, cold) = (run_with_warm(true), run_with_warm(false));
    let newton_iterations = |s: &Series| {
        let u = s
            .counters
            .units
            .iter()
            .find(|u| u.name == "line_lower")
            .unwrap();
        u.solver_iterations as f64 / u.do_step_calls as f64
    };
    let (w, c) = (newton_iterations(&warm), newton_iterations(&cold));
    let (ew, ec) = (indicator(&warm, "top_force"), indicator(&cold, "top_force"));
    println!(
        "lower section's Newton iterations per step: warm {w:.2}, cold {c:.2}; epsilon {ew:.4e} / {ec:.4e}"
    );
    assert!(w < 0.75 * c, "{w} against {c}");
    assert!((ew - ec).abs() < 1e-9, "{ew:e} against {ec:e}");
    assert_eq!(warm.counters.iterations, cold.counters.iterations);
}
