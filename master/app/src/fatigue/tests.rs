use super::{cycles_to_failure, damage, thickness_exponent};
use slender_scene::spec::{FatigueCurve, FatigueSpec, MeanStress};
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
        thickness: None,
        reference_thickness: None,
        thickness_exponent: None,
        mean_stress: None,
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

/// Miner's sum by hand of `sine(mean, amplitude, 100)` when every range r
/// from a valley v enters the curve as `effective(v, r)`: 99.5 cycles of the
/// full range, then the first half cycle (mean up to the first peak) and the
/// last (the last valley up to the mean).
fn miner_of_sine(
    curve: FatigueCurve,
    mean: f64,
    amplitude: f64,
    effective: impl Fn(f64, f64) -> f64,
) -> f64 {
    let n = |range: f64| cycles_to_failure(curve, range, 0.0);
    99.5 / n(effective(mean - amplitude, 2.0 * amplitude))
        + 0.5 / n(effective(mean, amplitude))
        + 0.5 / n(effective(mean - amplitude, amplitude))
}

#[test]
fn dnv_rp_c203_thickness_effect_raises_ranges_above_the_reference_thickness() {
    // A riser wall's stress, 40 +- 30 MPa (nominal area 1 m2, so the tension
    // in N is 1e6 times the stress in MPa), on curve D in air: the full
    // ranges above its knee (52.63 MPa), the end's half cycles below it.
    let mut s = spec(FatigueCurve::DnvC203DAir);
    s.area = Some(1.0);
    let history = sine(40e6, 30e6, 100);
    let plain = damage(&s, &history, None, 1000.0).damage;
    let by_hand = |factor: f64| miner_of_sine(s.curve, 40.0, 30.0, |_, r| factor * r);
    assert!((plain / by_hand(1.0) - 1.0).abs() < 1e-9);
    // 50 mm against the 25 mm reference: ranges times 2^0.20.
    s.thickness = Some(0.05);
    let thick = damage(&s, &history, None, 1000.0).damage;
    let expected = by_hand(2f64.powf(0.20));
    assert!(
        (thick / expected - 1.0).abs() < 1e-9,
        "{thick} against {expected}"
    );
    assert!(
        thick > 1.5 * plain,
        "about 2^0.6 = 1.52 times: {}",
        thick / plain
    );
    // Thinner than the reference counts as the reference.
    s.thickness = Some(0.02);
    assert_eq!(damage(&s, &history, None, 1000.0).damage, plain);
    // A tubular joint's 16 mm reference and an exponent of 0.3 given.
    (s.thickness, s.reference_thickness, s.thickness_exponent) =
        (Some(0.032), Some(0.016), Some(0.3));
    let given = damage(&s, &history, None, 1000.0).damage;
    let expected = miner_of_sine(s.curve, 40.0, 30.0, |_, r| 2f64.powf(0.3) * r);
    assert!((given / expected - 1.0).abs() < 1e-9);
    // The tables' exponents.
    use FatigueCurve::*;
    let k = [
        (DnvC203B1Air, 0.0),
        (DnvC203CSeawaterCp, 0.05),
        (DnvC203EAir, 0.20),
        (DnvC203F1SeawaterCp, 0.25),
        (DnvStudlessChain, 0.0),
    ];
    for (curve, expected) in k {
        assert_eq!(thickness_exponent(curve), expected, "{curve:?}");
    }
}

#[test]
fn dnv_rp_c203_mean_stress_effect_reduces_the_compressive_part_of_each_range() {
    let mut s = spec(FatigueCurve::DnvC203DAir);
    s.area = Some(1.0);
    let damage_of =
        |s: &FatigueSpec, mean: f64| damage(s, &sine(mean * 1e6, 40e6, 100), None, 1000.0).damage;
    // 80 MPa ranges: about a zero mean half of each range is compressive,
    // so f_m = 0.5 + 0.6 x 0.5 = 0.8 in base material, 0.9 after heat
    // treatment; wholly tensile (mean 50 MPa) no change; wholly compressive
    // (-50 MPa) 0.6. The end's half cycles by the same rule: from the mean
    // up to the peak and from the valley up to the mean.
    let plain = damage_of(&s, 0.0);
    for (effect, mean, f_full) in [
        (MeanStress::BaseMaterial, 0.0, 0.8),
        (MeanStress::PostWeldHeatTreated, 0.0, 0.9),
        (MeanStress::BaseMaterial, 50.0, 1.0),
        (MeanStress::BaseMaterial, -50.0, 0.6),
    ] {
        s.mean_stress = Some(effect);
        let c = effect.compressive_factor();
        let effective = |valley: f64, range: f64| {
            if range == 80.0 {
                return f_full * range;
            }
            let tensile = (valley + range).max(0.0) - valley.max(0.0);
            tensile + c * (range - tensile)
        };
        let reduced = damage_of(&s, mean);
        let miner = miner_of_sine(s.curve, mean, 40.0, effective);
        assert!(
            (reduced / miner - 1.0).abs() < 1e-9,
            "{effect:?} {mean}: {reduced} against {miner}"
        );
        if mean == 0.0 {
            assert!(reduced < 0.8 * plain, "{reduced} against {plain}");
        }
    }
}
