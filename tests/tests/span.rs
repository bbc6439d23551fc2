//! The span transfer function (seed 004 ch. 5): the general transfer matrix against
//! eq. 5.9 and the FE beam, robustness for large |beta L|, resonances at the
//! cantilever eigenvalues, and the printed order-8 approximations.

use nalgebra::{Complex, DMatrix, DVector};
use slender_units::beam::elements;
use slender_units::span::rational::{
    RationalX, function_pade_u2_u5, taylor_u2_u5, term_pade_u2_u5,
};
use slender_units::span::transfer::{C64, Span};

fn bode_span(cd: f64) -> Span {
    // Seed 004 Fig. 5.1: EI = 1e4, mu = 1e2, c_d in {0, 5}, L = 10.
    Span {
        flexural_rigidity: 1e4,
        mass_per_length: 1e2,
        damping_per_length: cd,
        length: 10.0,
        tension: 0.0,
    }
}

const U2_TO_U5: ([usize; 4], [usize; 4]) = ([1, 2, 7, 8], [3, 4, 5, 6]);

fn h25(span: &Span, omega: f64) -> C64 {
    let h = span
        .transfer(C64::new(0.0, omega), U2_TO_U5.0, U2_TO_U5.1)
        .unwrap();
    h[2][1] // output U5 (third output) from input U2 (second input)
}

#[test]
fn the_general_transfer_matrix_reproduces_eq_5_9() {
    for cd in [0.0, 5.0] {
        let span = bode_span(cd);
        for omega in [0.01, 0.1, 0.3, 1.0, 3.0, 10.0, 30.0] {
            let (general, closed) = (
                h25(&span, omega),
                span.h_u2_u5_closed_form(C64::new(0.0, omega)),
            );
            let rel = (general - closed).norm() / closed.norm();
            assert!(rel < 1e-8, "c_d {cd}, omega {omega}: {general} vs {closed}");
        }
    }
}

#[test]
fn large_beta_l_stays_finite_where_the_closed_form_overflows() {
    let span = bode_span(5.0);
    let s = C64::new(0.0, 2.0e5);
    let h = span.transfer(s, U2_TO_U5.0, U2_TO_U5.1).unwrap();
    assert!(
        h.iter()
            .flatten()
            .all(|v| v.re.is_finite() && v.im.is_finite())
    );
    let closed = span.h_u2_u5_closed_form(s);
    eprintln!(
        "|beta L| = {:.0}: general {:.3e}, closed form {closed}",
        (span.beta4(s).norm().powf(0.25)) * 10.0,
        h[2][1].norm()
    );
    assert!(
        !(closed.re.is_finite() && closed.im.is_finite())
            || (closed - h[2][1]).norm() < 1e-6 * h[2][1].norm()
    );
}

/// FE frequency response y(L) for a unit rotation at x = 0 with y(0) = 0 and a free
/// end (same model as the beam unit: consistent mass, C = c_d / mu M).
fn fe_h25(span: &Span, elements_count: usize, omega: f64) -> C64 {
    let lengths = vec![span.length / elements_count as f64; elements_count];
    let m = elements::mass(span.mass_per_length, &lengths).to_dense();
    let k = elements::stiffness(span.flexural_rigidity, &lengths).to_dense();
    let n = m.nrows();
    let c = &m * (span.damping_per_length / span.mass_per_length);
    let i = Complex::new(0.0, 1.0);
    let a: DMatrix<C64> = DMatrix::from_fn(n, n, |r, col| {
        Complex::from(k[(r, col)]) + i * omega * c[(r, col)]
            - Complex::from(omega * omega * m[(r, col)])
    });
    // Held DOFs 0 (y = 0) and 1 (theta = 1): move to the right-hand side.
    let free: Vec<usize> = (2..n).collect();
    let af = DMatrix::from_fn(free.len(), free.len(), |r, col| a[(free[r], free[col])]);
    let rhs = DVector::from_fn(free.len(), |r, _| -a[(free[r], 1)]);
    let q = af.lu().solve(&rhs).unwrap();
    q[n - 4] // y at the last node (DOF n - 2, index n - 4 among the free ones)
}

#[test]
fn the_transfer_function_matches_the_fe_span_below_the_third_resonance() {
    let span = bode_span(5.0);
    // Third resonance: (7.85476 / L)^2 sqrt(EI / mu) = 6.17 rad/s.
    for omega in [0.05, 0.2, 0.5, 1.0, 2.0, 4.0, 5.5] {
        let (exact, fe) = (h25(&span, omega), fe_h25(&span, 25, omega));
        let rel = (exact - fe).norm() / exact.norm();
        eprintln!(
            "omega {omega:>5}: |H| exact {:.5e}, FE (25 el) {:.5e}, relative difference {rel:.2e}",
            exact.norm(),
            fe.norm()
        );
        assert!(rel < 1e-3, "omega {omega}: {rel}");
    }
}

#[test]
fn undamped_resonances_are_the_cantilever_eigenvalues() {
    let span = bode_span(0.0);
    for nu_l in [1.8751, 4.69409, 7.85476, 10.9955] {
        let omega = (nu_l / 10.0f64).powi(2) * (1e4f64 / 1e2).sqrt();
        let near = h25(&span, omega * (1.0 + 1e-6)).norm();
        let away = h25(&span, omega * 0.8).norm();
        assert!(
            near > 1e4 * away,
            "nu L {nu_l}: |H| {near} near, {away} away"
        );
    }
}

/// Significant digits printed in a number.
fn printed_tolerance(text: &str) -> f64 {
    let mantissa = text
        .split(['e', 'E'])
        .next()
        .unwrap()
        .trim_start_matches('-');
    let digits = mantissa
        .chars()
        .filter(|c| c.is_ascii_digit())
        .collect::<String>();
    let significant = digits.trim_start_matches('0').len().max(1);
    0.5 * 10f64.powi(1 - significant as i32) * 1.0001
}

fn compare(label: &str, got: &RationalX, num: &[(&str, f64)], den: &[&str], scale: f64) {
    for (i, (text, factor)) in num.iter().enumerate() {
        let printed: f64 = text.parse::<f64>().unwrap() * factor * scale;
        let rel = ((got.num[i] - printed) / printed).abs();
        assert!(
            rel <= printed_tolerance(text),
            "{label} numerator x^{i}: {} vs printed {printed} ({rel:.1e})",
            got.num[i]
        );
    }
    for (i, text) in den.iter().enumerate() {
        let printed: f64 = text.parse::<f64>().unwrap() * scale;
        let rel = ((got.den[i] - printed) / printed).abs();
        assert!(
            rel <= printed_tolerance(text),
            "{label} denominator x^{i}: {} vs printed {printed} ({rel:.1e})",
            got.den[i]
        );
    }
    eprintln!(
        "{label}: all {} coefficients within their printed digits",
        num.len() + den.len()
    );
}

#[test]
fn order_8_approximations_match_the_printed_coefficients() {
    // Eq. 5.11: 2.7095e7 (x + 120) / (x^4 + 224 x^3 + 645120 x^2 - 2.7095e8 x + 3.2514e9).
    let t = taylor_u2_u5(8).unwrap();
    compare(
        "Taylor (5.11)",
        &t,
        &[("2.7095e7", 120.0), ("2.7095e7", 1.0)],
        &["3.2514e9", "-2.7095e8", "645120", "224", "1"],
        1.0,
    );
    // Eq. 5.14.
    let p = term_pade_u2_u5(8).unwrap();
    compare(
        "term Pade (5.14)",
        &p,
        &[
            ("1.33127e9", 1.0),
            ("1.08373e7", 1.0),
            ("-1075.58", 1.0),
            ("8.19418", 1.0),
        ],
        &["1.33127e9", "-1.11196e8", "291170", "-391.102", "1"],
        1.0,
    );
    // Eq. 5.15: 0.00252093 (x^4 + 29576.5 x^3 + ...) / (x^4 - 16464.3 x^3 + ...).
    let f = function_pade_u2_u5(8).unwrap();
    let c = 0.00252093;
    let num: Vec<(&str, f64)> = ["1.10323e14", "9.236e11", "3.39367e8", "29576.5", "1"]
        .iter()
        .map(|t| (*t, c))
        .collect();
    for (i, (text, factor)) in num.iter().enumerate() {
        let printed = text.parse::<f64>().unwrap() * factor;
        let rel = ((f.num[i] - printed) / printed).abs();
        // The printed factor 0.00252093 has 6 digits too.
        assert!(
            rel <= printed_tolerance(text) + printed_tolerance("0.00252093"),
            "function Pade numerator x^{i}: {} vs {printed}",
            f.num[i]
        );
    }
    compare(
        "function Pade (5.15) denominator",
        &RationalX {
            num: vec![],
            den: f.den.clone(),
        },
        &[],
        &["2.78118e11", "-2.31658e10", "5.42916e7", "-16464.3", "1"],
        1.0,
    );
}

#[test]
fn function_pade_is_the_best_order_8_approximation_undamped() {
    let span = bode_span(0.0);
    let approximations = [
        ("Taylor", taylor_u2_u5(8).unwrap()),
        ("term Pade", term_pade_u2_u5(8).unwrap()),
        ("function Pade", function_pade_u2_u5(8).unwrap()),
    ];
    // Mean log-magnitude error over the Fig. 5.2 band 1e-2..2.5e2 rad/s.
    let omegas: Vec<f64> = (0..400)
        .map(|k| 10f64.powf(-2.0 + 4.398 * k as f64 / 399.0))
        .collect();
    let mut errors = Vec::new();
    for (name, a) in &approximations {
        let e: f64 = omegas
            .iter()
            .map(|&w| {
                let s = C64::new(0.0, w);
                (a.eval(&span, s).norm().log10() - span.h_u2_u5_closed_form(s).norm().log10()).abs()
            })
            .sum::<f64>()
            / omegas.len() as f64;
        eprintln!("{name:<14} mean |log10 |H_approx| - log10 |H||| over the band: {e:.3}");
        errors.push(e);
    }
    assert!(errors[2] < errors[1] && errors[1] < errors[0], "{errors:?}");
}

#[test]
fn bad_span_input_is_refused() {
    let mut span = bode_span(0.0);
    assert!(
        span.transfer(C64::new(0.0, 1.0), [1, 1, 7, 8], [2, 3, 5, 6])
            .is_err()
    );
    assert!(
        span.transfer(C64::new(0.0, 1.0), [1, 2, 7, 9], [3, 4, 5, 6])
            .is_err()
    );
    span.flexural_rigidity = 0.0;
    assert!(span.validate().is_err());
    assert!(taylor_u2_u5(7).is_err() && function_pade_u2_u5(0).is_err());
    // Every choice of four distinct quantities determines the span away from s = 0:
    // the solution map is invertible for all of them.
    let span = bode_span(5.0);
    let mut count = 0;
    for a in 1..=8 {
        for b in a + 1..=8 {
            for c in b + 1..=8 {
                for d in c + 1..=8 {
                    if span.check_admissible([a, b, c, d]).is_ok() {
                        count += 1;
                    }
                }
            }
        }
    }
    eprintln!("{count} of 70 input choices admissible");
    assert_eq!(count, 70);
    // At s = 0 (statics) forces and moments alone leave the rigid-body motions free.
    let e = span
        .transfer(C64::new(0.0, 0.0), [3, 4, 7, 8], [1, 2, 5, 6])
        .unwrap_err();
    assert!(e.to_string().contains("do not determine the span"), "{e}");
}

mod unit {
    use slender_units::span::unit::{Approximation, SpanParams, SpanUnit};
    use slender_units::{Driver, Time};

    fn params(approximation: Approximation, order: usize, cd: f64) -> SpanParams {
        SpanParams {
            flexural_rigidity: 1e4,
            mass_per_length: 1e2,
            damping_per_length: cd,
            length: 10.0,
            tension: 0.0,
            approximation,
            order,
            band: 2.0 * std::f64::consts::PI * 10.0,
        }
    }

    #[test]
    fn with_tension_only_the_fit_is_offered() {
        for a in [
            Approximation::Taylor,
            Approximation::TermPade,
            Approximation::FunctionPade,
        ] {
            let mut p = params(a, 8, 5.0);
            p.tension = 1e5;
            let e = SpanUnit::new(p).err().expect("refused");
            assert!(e.to_string().contains("`fit` with a tension"), "{e}");
        }
        let mut p = params(Approximation::Fit, 12, 5.0);
        p.tension = 1e5;
        let mut unit = Driver::new(SpanUnit::new(p).expect("fit with tension"));
        unit.set_inputs(&[1e-3]).unwrap();
        unit.initialize(Time::ZERO).unwrap();
        // A rotation at the upper end against the tension: a stiff, bounded answer.
        let mut out = [0.0];
        for k in 0..1000 {
            unit.do_step(
                Time::from_secs(1e-3).unwrap() * k,
                Time::from_secs(1e-3).unwrap(),
            )
            .unwrap();
            unit.outputs(&mut out).unwrap();
            assert!(out[0].is_finite());
        }
    }

    const ALL: [Approximation; 4] = [
        Approximation::Taylor,
        Approximation::TermPade,
        Approximation::FunctionPade,
        Approximation::Fit,
    ];

    #[test]
    fn the_steady_state_gain_is_the_static_solution() {
        // A rotation theta at the held end of a free span tilts it rigidly: y(L) = theta L.
        for a in ALL {
            for order in [2, 4, 8, 12, 16] {
                let Ok(u) = SpanUnit::new(params(a, order, 5.0)) else {
                    assert!(
                        a == Approximation::TermPade && order % 4 != 0,
                        "{a:?} {order} refused"
                    );
                    continue;
                };
                let mut u = Driver::new(u);
                u.set_inputs(&[0.01]).unwrap();
                u.initialize(Time::ZERO).unwrap();
                let mut y = [0.0];
                u.outputs(&mut y).unwrap();
                assert!((y[0] - 0.1).abs() < 1e-7, "{a:?} order {order}: {}", y[0]);
            }
        }
    }

    #[test]
    fn white_noise_for_1000_s_stays_bounded_for_every_order() {
        let h = Time::from_secs(0.01).unwrap();
        for a in ALL {
            for order in [2, 4, 6, 8, 10, 12, 14, 16] {
                let Ok(u) = SpanUnit::new(params(a, order, 5.0)) else {
                    assert!(
                        a == Approximation::TermPade && order % 4 != 0,
                        "{a:?} {order} refused"
                    );
                    continue;
                };
                let mut u = Driver::new(u);
                let repaired = u.system().repaired;
                assert!(u.system().is_stable(), "{a:?} {order}");
                u.set_inputs(&[0.0]).unwrap();
                u.initialize(Time::ZERO).unwrap();
                let mut seed = 12345u64;
                let mut peak = 0.0f64;
                for k in 0..100_000 {
                    seed = seed
                        .wrapping_mul(6364136223846793005)
                        .wrapping_add(1442695040888963407);
                    let noise = ((seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 0.02;
                    u.set_inputs(&[noise]).unwrap();
                    u.do_step(h * k, h).unwrap();
                    let mut y = [0.0];
                    u.outputs(&mut y).unwrap();
                    peak = peak.max(y[0].abs());
                }
                eprintln!(
                    "{a:?} order {order:>2}: {repaired} poles reflected, peak |y| {peak:.3e} m over 1000 s"
                );
                assert!(peak.is_finite() && peak < 100.0, "{a:?} {order}: {peak}");
            }
        }
    }

    fn fe_span(elements: usize) -> Driver<slender_units::beam::Beam> {
        let span = slender_units::span::transfer::Span {
            flexural_rigidity: 1e4,
            mass_per_length: 1e2,
            damping_per_length: 5.0,
            length: 10.0,
            tension: 0.0,
        };
        Driver::new(slender_app::span_study::fe_span(&span, elements).unwrap())
    }

    #[test]
    fn in_band_the_span_unit_follows_the_fe_span() {
        // Rotation input: sines at 0.2, 0.7 and 2 rad/s (below the third resonance,
        // 6.17 rad/s), faded in over 20 s; 200 s at 10 ms.
        let input = |t: f64| {
            (1.0 - (-t / 20.0f64).exp())
                * 0.01
                * ((0.2 * t).sin() + 0.5 * (0.7 * t).sin() + 0.25 * (2.0 * t).sin())
        };
        let h = Time::from_secs(0.01).unwrap();
        let mut fe = fe_span(32);
        fe.set_inputs(&[0.0]).unwrap();
        fe.initialize(Time::ZERO).unwrap();
        let mut reference = Vec::new();
        for k in 0..20_000 {
            fe.set_inputs(&[input((k + 1) as f64 * 0.01)]).unwrap();
            fe.do_step(h * k, h).unwrap();
            reference.push(fe.deflection_at(10.0));
        }
        let peak = reference.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        for a in ALL {
            for order in [4, 6, 8, 10, 12, 14, 16] {
                let Ok(u) = SpanUnit::new(params(a, order, 5.0)) else {
                    continue;
                };
                let mut u = Driver::new(u);
                u.set_inputs(&[0.0]).unwrap();
                u.initialize(Time::ZERO).unwrap();
                let mut worst = 0.0f64;
                for (k, r) in reference.iter().enumerate() {
                    u.set_inputs(&[input((k + 1) as f64 * 0.01)]).unwrap();
                    u.do_step(h * k as i64, h).unwrap();
                    let mut y = [0.0];
                    u.outputs(&mut y).unwrap();
                    worst = worst.max((y[0] - r).abs());
                }
                eprintln!(
                    "{a:?} order {order:>2}: largest difference to the FE span (32 el) {:.3e} m = {:.2} % of the peak {peak:.3e} m",
                    worst,
                    100.0 * worst / peak
                );
                if a == Approximation::FunctionPade && (6..=12).contains(&order) {
                    assert!(worst < 1e-3 * peak, "{a:?} {order}: {worst}");
                }
                if a == Approximation::Taylor && order == 14 {
                    assert!(worst < 0.02 * peak, "{a:?} {order}: {worst}");
                }
                if a == Approximation::Fit && order >= 14 {
                    // The vector fit spreads its poles over the whole 10 Hz band.
                    assert!(worst < 0.005 * peak, "{a:?} {order}: {worst}");
                }
            }
        }
    }
}

/// Largest relative difference of the realised function Pade approximation of
/// `order` (repaired if it has unstable poles) to the exact H_{U2 -> U5} at 0.1, 1
/// and 5 rad/s (below the third resonance), band 62.8 rad/s.
fn high_order_pade_error(order: usize) -> f64 {
    use slender_units::span::realization::StateSpace;
    let span = bode_span(5.0);
    let ss = StateSpace::realize(&function_pade_u2_u5(order).unwrap(), &span, 62.8).unwrap();
    assert!(
        ss.repaired > 0,
        "order {order} was expected to need a repair"
    );
    assert!(ss.is_stable(), "order {order}");
    [0.1, 1.0, 5.0]
        .iter()
        .map(|&w| {
            let exact = h25(&span, w);
            let error = (ss.response(C64::new(0.0, w)) - exact).norm() / exact.norm();
            eprintln!("function Pade order {order}, omega {w}: {error:.2e}");
            error
        })
        .fold(0.0, f64::max)
}

#[test]
fn order_16_function_pade_repaired_by_relocation_follows_the_exact_span() {
    // Order 16 has 8 poles in the right half-plane; reflected and relocated by vector
    // fitting over the band it is within 0.64 % (reflection alone: 71 %).
    assert!(high_order_pade_error(16) < 1e-2);
}

#[test]
#[ignore = "known gap (issue 5): function Pade order 14 has 4 right-half-plane poles; reflected and relocated over the 10 Hz band it is 1.65 % off at 5 rad/s (reflection alone: 3.7 %), beyond the 1 % the other orders meet: seven pole pairs cannot cover the eight resonances of the band"]
fn order_14_function_pade_repaired_by_relocation_follows_the_exact_span() {
    assert!(high_order_pade_error(14) < 1e-2);
}

/// Through the study engine (signal units, the master's ramped inputs and substeps,
/// the peak norm, an external reference run) the span study gives the errors the
/// direct implementation gave before it (units stepped by hand,
/// `tests/reference/span_study_direct.json`): to 2e-9 of the peak. (Inputs differ
/// by rounding, t from integer nanoseconds; the FE's Newton tolerance then moves
/// errors by about 1e-10 of the peak.)
fn same_as_the_direct_implementation(report: &slender_app::span_study::StudyReport) {
    let text = std::fs::read_to_string(
        slender_tests::root().join("tests/reference/span_study_direct.json"),
    )
    .unwrap();
    let direct: serde_json::Value = serde_json::from_str(&text).unwrap();
    let close = |a: f64, b: f64, what: &str| {
        assert!((a - b).abs() <= 2e-9, "{what}: {a:.6e} now, {b:.6e} before");
    };
    let rows = direct["rows"].as_array().unwrap();
    assert_eq!(rows.len(), report.rows.len());
    for d in rows {
        let (model, size, substeps) = (
            d["model"].as_str().unwrap(),
            d["size"].as_u64().unwrap() as usize,
            d["substeps"].as_u64().unwrap() as usize,
        );
        let r = report
            .rows
            .iter()
            .find(|r| r.model == model && r.size == size && r.substeps == substeps)
            .unwrap();
        let what = format!("{model} {size} x {substeps}");
        close(r.error_sines, d["error_sines"].as_f64().unwrap(), &what);
        close(r.error_step, d["error_step"].as_f64().unwrap(), &what);
    }
    let halving = direct["halving_change_sines"].as_f64().unwrap();
    close(report.reference.halving_change_sines, halving, "halving");
}

/// The accuracy half of `slender span study` (its cost half is in BENCHMARKS.md):
/// against the continuum's response (FE 128 elements, 64 substeps), the function
/// Pade span unit of order 12 is more accurate than every FE span that steps with
/// the master, since those carry the trapezoidal rule's time error at h = 10 ms;
/// and the reference is converged well below the errors it ranks.
#[test]
fn span_unit_beats_fe_spans_stepping_with_the_master_against_the_continuum() {
    use slender_app::span_study::{StudyPlan, study};
    let plan = StudyPlan {
        orders: vec![8, 12],
        elements: vec![8, 16, 32],
        fe_substeps: vec![1, 4],
        reference_elements: 128,
        reference_substeps: 64,
        duration: 30.0,
        step: 0.01,
    };
    let scenes = std::env::temp_dir().join(format!("slender-span-study-{}", std::process::id()));
    let report = study(&bode_span(5.0), &plan, &scenes).unwrap();
    eprint!("{}", slender_app::span_study::to_markdown(&report));
    same_as_the_direct_implementation(&report);
    // The study's scenes are plain scenes, written where it was told.
    assert!(scenes.join("span_sines.toml").exists() && scenes.join("reference_step.toml").exists());
    std::fs::remove_dir_all(&scenes).ok();
    let row = |model: &str, size: usize, substeps: usize| {
        report
            .rows
            .iter()
            .find(|r| r.model == model && r.size == size && r.substeps == substeps)
            .unwrap()
    };
    let pade12 = row("function_pade", 12, 1).error_sines;
    for n in [8, 16, 32] {
        let fe = row("fe", n, 1).error_sines;
        assert!(
            pade12 < fe,
            "function Pade 12: {pade12:.2e}, FE {n}: {fe:.2e}"
        );
    }
    // With 4 substeps the FE's time error drops 16-fold: 16 elements then come
    // within a factor of a few of the span unit.
    assert!(row("fe", 16, 4).error_sines < row("fe", 16, 1).error_sines / 4.0);
    assert!(report.reference.halving_change_sines < pade12 / 10.0);
}
