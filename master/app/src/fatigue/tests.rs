use super::{cycles_to_failure, damage};
use slender_scene::spec::{FatigueCurve, FatigueSpec};
use std::f64::consts::PI;

fn spec(curve: FatigueCurve) -> FatigueSpec {
    FatigueSpec {
        name: "f".into(),
        tension: "u.t".into(),
        moment: None,
        curve,
        area: None,
        chain_diameter: None,
        section_modulus: None,
        breaking_load: None,
        scf: None,
        from: None,
    }
}

/// `periods` periods of mean + amplitude sin, 200 samples a period.
fn sine(mean: f64, amplitude: f64, periods: usize) -> Vec<f64> {
    (0..=200 * periods)
        .map(|k| mean + amplitude * (2.0 * PI * k as f64 / 200.0).sin())
        .collect()
}

#[test]
fn a_constant_amplitude_tension_has_miners_closed_form() {
    // A 100 mm studless chain (nominal area 2 pi d^2 / 4), 1 MN +- 0.2 MN,
    // 100 periods in 1000 s: 99.5 cycles of the full range and the two
    // half ranges at the ends, each half a cycle of half the range.
    let mut s = spec(FatigueCurve::DnvStudlessChain);
    s.chain_diameter = Some(0.1);
    let area = 2.0 * PI * 0.01 / 4.0;
    let range = 0.4e6 / area / 1e6;
    let d = damage(&s, &sine(1e6, 0.2e6, 100), None, 1000.0);
    let miner = 99.5 * range.powi(3) / 6.0e10 + (range / 2.0).powi(3) / 6.0e10;
    assert!(
        (d.damage / miner - 1.0).abs() < 1e-9,
        "{d:?} against {miner}"
    );
    assert!((d.largest_range - range).abs() < 1e-9, "{d:?}");
    let per_year = miner * 365.25 * 86_400.0 / 1000.0;
    assert!((d.damage_per_year / per_year - 1.0).abs() < 1e-9, "{d:?}");
    assert!((d.life_years * per_year - 1.0).abs() < 1e-9, "{d:?}");
    // A stress concentration of 1.5 multiplies the damage by 1.5^3.
    s.scf = Some(1.5);
    let raised = damage(&s, &sine(1e6, 0.2e6, 100), None, 1000.0);
    assert!((raised.damage / d.damage - 1.5f64.powi(3)).abs() < 1e-9);
}

#[test]
fn dnv_rp_c203_curves_are_continuous_at_their_knees_and_give_the_fatigue_limits() {
    use FatigueCurve::*;
    // (curve, log10 of the knee's cycles, the stress there (MPa): the
    // fatigue limits DNV-RP-C203 tabulates for air, derived for seawater).
    let curves = [
        (DnvC203B1Air, 7.0, 106.97),
        (DnvC203CAir, 7.0, 73.10),
        (DnvC203DAir, 7.0, 52.63),
        (DnvC203EAir, 7.0, 46.78),
        (DnvC203FAir, 7.0, 41.52),
        (DnvC203F1Air, 7.0, 36.84),
        (DnvC203B1SeawaterCp, 6.0, 169.5),
        (DnvC203CSeawaterCp, 6.0, 115.8),
        (DnvC203DSeawaterCp, 6.0, 83.41),
        (DnvC203ESeawaterCp, 6.0, 74.14),
        (DnvC203FSeawaterCp, 6.0, 65.79),
        (DnvC203F1SeawaterCp, 6.0, 58.38),
    ];
    for (curve, knee, limit) in curves {
        let n = cycles_to_failure(curve, limit, 0.0);
        assert!(
            (n.log10() - knee).abs() < 2e-3,
            "{curve:?}: {n:e} at {limit} MPa"
        );
        let (below, above) = (
            cycles_to_failure(curve, limit * (1.0 - 1e-9), 0.0),
            cycles_to_failure(curve, limit * (1.0 + 1e-9), 0.0),
        );
        assert!(
            (below / above - 1.0).abs() < 5e-3,
            "{curve:?}: {below:e} / {above:e}"
        );
    }
    // Below the knee the slope is 5: half the stress, 32 times the cycles.
    let (a, b) = (
        cycles_to_failure(DnvC203DAir, 20.0, 0.0),
        cycles_to_failure(DnvC203DAir, 10.0, 0.0),
    );
    assert!((b / a - 32.0).abs() < 1e-9);
}

#[test]
fn api_rp_2sk_curves_take_the_range_over_the_breaking_strength() {
    use FatigueCurve::*;
    // N R^M = K: a tenth of the breaking strength, 316 / 0.001 cycles.
    assert!((cycles_to_failure(ApiStudlessChain, 0.1, 0.0) - 316_000.0).abs() < 1e-6);
    assert!((cycles_to_failure(ApiStudlinkChain, 0.1, 0.0) - 1e6).abs() < 1e-6);
    // Rope: K falls with the mean load, log10 K = 3.20 - 2.79 Lm.
    let n = cycles_to_failure(ApiSixStrandRope, 0.1, 0.3);
    assert!((n.log10() - (3.20 - 2.79 * 0.3 + 4.09)).abs() < 1e-12);
    // The same sine as a ratio: damage 99.5 (0.04)^3 / 316 + the half ranges.
    let mut s = spec(ApiStudlessChain);
    s.breaking_load = Some(1e7);
    let d = damage(&s, &sine(1e6, 0.2e6, 100), None, 1000.0);
    let miner = (99.5 * 0.04f64.powi(3) + 0.02f64.powi(3)) / 316.0;
    assert!(
        (d.damage / miner - 1.0).abs() < 1e-9,
        "{d:?} against {miner}"
    );
}

#[test]
fn a_bending_moment_adds_its_fibre_stress_on_the_worse_side() {
    // A riser: 2 MN steady tension on 0.02 m2, a moment of +-50 kN m on a
    // section modulus of 2.5e-3 m3: a stress range of 40 MPa on both sides
    // (S-N curve D in seawater, first slope) and no range from the tension.
    let mut s = spec(FatigueCurve::DnvC203DSeawaterCp);
    s.area = Some(0.02);
    s.section_modulus = Some(2.5e-3);
    let tension = vec![2e6; 20_001];
    let moment = sine(0.0, 5e4, 100);
    let d = damage(&s, &tension, Some(&moment), 1000.0);
    let n = |range: f64| cycles_to_failure(s.curve, range, 0.0);
    let miner = 99.5 / n(40.0) + 1.0 / n(20.0);
    assert!(
        (d.damage / miner - 1.0).abs() < 1e-9,
        "{d:?} against {miner}"
    );
    let without = damage(&s, &tension, None, 1000.0);
    assert_eq!(without.damage, 0.0);
    assert!(without.life_years.is_infinite());
}
