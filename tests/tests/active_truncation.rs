//! Active truncation of the polyester line (seed 000): the substructured system
//! against the emulated one, convergence, the published signal-loss example,
//! stability of the hard cases and bad input.

use slender_scene::Scene;
use slender_tests::{Series, load, run};

const SUBSTRUCTURED: &str = "examples/truncation_substructured.toml";
const SIGNAL_LOSS: &str = "examples/truncation_signal_loss.toml";
const TABLE2: &str = "examples/truncation_table2.toml";
const FIG10: &str = "examples/truncation_fig10.toml";

fn indicator(s: &Series, name: &str) -> (f64, f64) {
    let i = s
        .indicators
        .iter()
        .find(|i| i.name == name)
        .expect("indicator");
    (i.fidelity, i.relative_error)
}

/// A scene with some `key = value` lines of its text replaced.
fn variant(path: &str, replacements: &[(&str, &str)]) -> Scene {
    let file = slender_tests::root().join(path);
    let mut text = std::fs::read_to_string(&file).unwrap();
    for (from, to) in replacements {
        assert!(text.contains(from), "{from} not in {path}");
        text = text.replace(from, to);
    }
    Scene::parse(&file, text).unwrap_or_else(|e| panic!("{e}"))
}

fn all_finite(s: &Series) -> bool {
    s.columns.iter().all(|c| c.iter().all(|v| v.is_finite()))
}

#[test]
fn without_artefacts_the_substructured_line_reproduces_the_emulated_one() {
    let s = run(&load(SUBSTRUCTURED));
    assert!(s.error.is_none(), "{:?}", s.error);
    let (phi1, e1) = indicator(&s, "phi1");
    let (phi2, e2) = indicator(&s, "phi2");
    eprintln!(
        "no artefacts, 200 s: phi1 = {phi1:.2} (eps {e1:.2e}), phi2 = {phi2:.2} (eps {e2:.2e}), {:.2} iterations/step",
        s.counters.mean_iterations()
    );
    assert!(phi1 > 5.0 && phi2 > 6.0);
    assert_eq!(s.counters.non_converged_steps, 0);
    assert!(s.counters.mean_iterations() < 3.5);
}

#[test]
fn the_difference_shrinks_with_the_synchronisation_step() {
    let mut previous = 0.0;
    for step in ["0.02", "0.01", "0.005"] {
        let scene = variant(
            SUBSTRUCTURED,
            &[
                ("duration = 200.0", "duration = 60.0"),
                ("step = 0.01", &format!("step = {step}")),
            ],
        );
        let s = run(&scene);
        let (phi1, _) = indicator(&s, "phi1");
        eprintln!("h = {step} s: phi1 = {phi1:.3}");
        assert!(
            phi1 > previous + 0.2,
            "phi1 {phi1} at h = {step} not above {previous}"
        );
        previous = phi1;
    }
}

#[test]
fn loose_tolerances_cost_accuracy() {
    let loose = variant(
        SUBSTRUCTURED,
        &[
            ("duration = 200.0", "duration = 60.0"),
            (
                "tolerances = { velocity = 1e-6, force = 0.1 }",
                "tolerances = { velocity = 1e-2, force = 1e4 }",
            ),
        ],
    );
    let nominal = variant(SUBSTRUCTURED, &[("duration = 200.0", "duration = 60.0")]);
    let (l, n) = (run(&loose), run(&nominal));
    let (phi_l, phi_n) = (indicator(&l, "phi1").0, indicator(&n, "phi1").0);
    eprintln!(
        "phi1: loose {phi_l:.2} ({:.2} it/step), nominal {phi_n:.2} ({:.2} it/step)",
        l.counters.mean_iterations(),
        n.counters.mean_iterations()
    );
    assert!(phi_l < phi_n - 0.5);
    assert!(l.counters.mean_iterations() < n.counters.mean_iterations());
}

#[test]
fn the_signal_loss_example_is_near_the_published_fidelity() {
    // Seed 000 sec. 3.4 reports one realisation: phi1 = 1.30, phi2 = 1.99. Signal loss
    // is random, so compare the mean of three seeds.
    let (mut sum1, mut sum2) = (0.0, 0.0);
    for (a, b) in [("11", "12"), ("31", "32"), ("41", "42")] {
        let scene = variant(
            SIGNAL_LOSS,
            &[
                ("seed = 11", &format!("seed = {a}")),
                ("seed = 12", &format!("seed = {b}")),
            ],
        );
        let s = run(&scene);
        assert!(s.error.is_none(), "{:?}", s.error);
        let (p1, p2) = (indicator(&s, "phi1").0, indicator(&s, "phi2").0);
        eprintln!("seeds {a}/{b}: phi1 = {p1:.3}, phi2 = {p2:.3}");
        sum1 += p1;
        sum2 += p2;
    }
    let (m1, m2) = (sum1 / 3.0, sum2 / 3.0);
    eprintln!("mean phi1 = {m1:.3} (published 1.30), phi2 = {m2:.3} (published 1.99)");
    assert!((m1 - 1.30).abs() < 0.25, "phi1 {m1}");
    assert!((m2 - 1.99).abs() < 0.35, "phi2 {m2}");
}

/// Fig. 10's scene with the artefacts' seeds and extra replacements: (phi1, phi2).
fn fig10(seeds: (&str, &str), replacements: &[(&str, &str)]) -> (f64, f64) {
    let seeds = [
        ("seed = 21", format!("seed = {}", seeds.0)),
        ("seed = 22", format!("seed = {}", seeds.1)),
    ];
    let all: Vec<(&str, &str)> = seeds
        .iter()
        .map(|(a, b)| (*a, b.as_str()))
        .chain(replacements.iter().copied())
        .collect();
    let s = run(&variant(FIG10, &all));
    assert!(s.error.is_none(), "{:?}", s.error);
    (indicator(&s, "phi1").0, indicator(&s, "phi2").0)
}

#[test]
fn the_fig10_realisation_gives_the_published_phi1_with_delays_at_full_scale() {
    // Seed 000 Fig. 10: phi1 = 1.33 (the median of Table 2's phi1). Its losses
    // and noise are random: two seed pairs differ by about 0.01, so 0.05 (0.4 of
    // the paper's sd of phi1 over Table 2, 0.13) is the tolerance.
    let runs = [fig10(("21", "22"), &[]), fig10(("1", "2"), &[])];
    for (p1, p2) in runs {
        eprintln!("Fig. 10: phi1 = {p1:.3} (published 1.33), phi2 = {p2:.3} (published 1.62)");
        assert!((p1 - 1.33).abs() < 0.05, "phi1 {p1}");
    }
    // The caption's delays (2.6 ms, 1.3 ms) read in model scale (x 60^1/2 at
    // full scale) lose that agreement: this is why the scene reads them at full
    // scale, as Table 2's U(0, 5 dt).
    let model_scale = [
        ("delay = 0.0026 ", "delay = 0.02014 "),
        ("delay = 0.0013 ", "delay = 0.01007 "),
    ];
    let (p1, _) = fig10(("21", "22"), &model_scale);
    eprintln!("delays read in model scale: phi1 = {p1:.3}");
    assert!((p1 - 1.33).abs() > 0.2, "phi1 {p1}");
}

#[test]
#[ignore = "known gap: Fig. 10's phi2 is 1.98 here against the published 1.62 (phi1 agrees); see docs/active-truncation.md"]
fn the_fig10_realisation_gives_the_published_phi2() {
    let (_, p2) = fig10(("21", "22"), &[]);
    // Within the paper's sd of phi2 over Table 2 (0.17).
    assert!((p2 - 1.62).abs() < 0.17, "phi2 {p2}");
}

#[test]
fn hard_cases_run_the_full_duration_with_finite_values() {
    let cases: Vec<(&str, Scene)> = vec![
        (
            "losses with mean 10 s",
            variant(
                SIGNAL_LOSS,
                &[
                    (
                        "loss_duration_mean = 0.1\nseed = 11",
                        "loss_duration_mean = 10.0\nseed = 11",
                    ),
                    (
                        "loss_duration_mean = 0.1\nseed = 12",
                        "loss_duration_mean = 10.0\nseed = 12",
                    ),
                ],
            ),
        ),
        (
            "h = 100 ms",
            variant(SUBSTRUCTURED, &[("step = 0.01", "step = 0.1")]),
        ),
    ];
    for (label, scene) in cases {
        let s = run(&scene);
        let (phi1, _) = indicator(&s, "phi1");
        eprintln!(
            "{label}: {:?}, phi1 = {phi1:.2}, {:.2} iterations/step, {} non-converged",
            s.error,
            s.counters.mean_iterations(),
            s.counters.non_converged_steps
        );
        assert!(s.error.is_none(), "{label}: {:?}", s.error);
        assert!(
            (s.time.last().unwrap() - 200.0).abs() < 1e-9,
            "{label} stopped early"
        );
        assert!(all_finite(&s), "{label}: non-finite values");
    }
}

/// Table 2's largest delays, 50 ms on the force and on the velocity: a 100 ms
/// round trip in the coupling loop. The delay's negative damping makes the
/// truncated line's motion grow (no delay compensation yet, issue 15) until the
/// lower cable's drag iterations cannot follow; the run must stop there with the
/// unit, the time and the reason, every recorded value finite. (With losses
/// read as 0.3 s freezes the loop was broken often enough to reach 200 s, which
/// hid this; with losses of 3 steps it is not.)
#[test]
fn the_largest_table2_delays_grow_until_the_run_stops_with_the_reason() {
    let scene = variant(
        TABLE2,
        &[
            (
                "delay = 0.026                      # theta7: 2.6 ms x 10, inside U(0, 50 ms)",
                "delay = 0.05",
            ),
            (
                "delay = 0.026                      # theta10",
                "delay = 0.05",
            ),
        ],
    );
    let s = run(&scene);
    let (phi1, _) = indicator(&s, "phi1");
    eprintln!("largest delays: {:?}, phi1 = {phi1:.2}", s.error);
    assert!(all_finite(&s), "non-finite values recorded");
    match &s.error {
        Some(e) => assert!(
            e.contains("unit `n`")
                && e.contains("do_step failed at t =")
                && e.contains("did not converge"),
            "{e}"
        ),
        None => panic!("the 100 ms loop delay no longer grows: phi1 = {phi1}; update this test"),
    }
    // The growth shows before the stop: the top motion is far from the emulated one.
    assert!(phi1 < 0.0, "phi1 {phi1}");
}

#[test]
fn tolerances_beyond_reach_are_counted_or_stop_with_the_reason() {
    let tight = |policy: &str| {
        variant(
            SUBSTRUCTURED,
            &[
                ("duration = 200.0", "duration = 20.0"),
                (
                    "tolerances = { velocity = 1e-6, force = 0.1 }",
                    &format!(
                        "tolerances = {{ velocity = 1e-16, force = 1e-12 }}\non_max_iterations = \"{policy}\""
                    ),
                ),
                ("max_iterations = 100", "max_iterations = 8"),
            ],
        )
    };
    let accepted = run(&tight("accept"));
    assert!(accepted.error.is_none(), "{:?}", accepted.error);
    assert!(accepted.counters.non_converged_steps > 1000);
    assert!(all_finite(&accepted));
    let stopped = run(&tight("error"));
    let e = stopped.error.expect("must stop");
    assert!(
        e.contains("did not converge in 8 iterations") && e.contains("->"),
        "{e}"
    );
}

fn cable_error(replacements: &[(&str, &str)]) -> String {
    let file = slender_tests::root().join(SUBSTRUCTURED);
    let mut text = std::fs::read_to_string(&file).unwrap();
    for (from, to) in replacements {
        assert!(text.contains(from), "{from}");
        text = text.replace(from, to);
    }
    match Scene::parse(&file, text) {
        Ok(scene) => run(&scene)
            .error
            .unwrap_or_else(|| panic!("the run must fail: {replacements:?}")),
        Err(e) => e.to_string(),
    }
}

#[test]
fn bad_line_data_gets_a_clear_error() {
    let e = cable_error(&[("length = 1934.0", "length = 900.0")]);
    eprintln!("{e}");
    assert!(
        e.contains("does not reach the truncation height") || e.contains("static equilibrium"),
        "{e}"
    );
    let e = cable_error(&[("truncation_ratio = 0.8", "truncation_ratio = 1.5")]);
    assert!(
        e.contains("truncation_ratio") && e.contains("(0, 1)"),
        "{e}"
    );
    let e = cable_error(&[("drag_normal = 1.6", "drag_normal = -1.6")]);
    assert!(e.contains("drag_normal") && e.contains(">= 0"), "{e}");
    let e = cable_error(&[("mass_per_length = 44.7", "mass_per_length = nan")]);
    assert!(e.contains("mass_per_length") && e.contains("NaN"), "{e}");
    let e = cable_error(&[("elements = 80", "elements = 1")]);
    assert!(e.contains("elements"), "{e}");
    // A top force pulling down cannot hold the line up off the seabed.
    let e = cable_error(&[(
        "static_angle_from_vertical_deg = 50.0",
        "static_angle_from_vertical_deg = 170.0",
    )]);
    eprintln!("{e}");
    assert!(
        e.contains("static equilibrium") && e.contains("below the seabed"),
        "{e}"
    );
    let e = cable_error(&[(
        "effects = [\"weight\", \"added_mass\", \"drag\", \"current\"",
        "effects = [\"weight\", \"added_mass\", \"current\"",
    )]);
    assert!(e.contains("add the `drag` effect"), "{e}");
}
