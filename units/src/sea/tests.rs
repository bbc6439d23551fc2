//! Sea states against their definitions: Pierson-Moskowitz's variance is
//! Hs^2 / 16 exactly, JONSWAP with gamma = 1 is Pierson-Moskowitz and peaks
//! at the peak frequency, the discretised sea carries the band's variance, a
//! RAO scales and shifts each component, and the same seed gives the same sea.

use super::SeaState;
use super::rao::Rao;
use super::spectrum::{Spectrum, SpectrumKind};
use crate::beam::boundary::TimeFunction;
use crate::signal::source::SignalParams;

fn spectrum(kind: SpectrumKind, gamma: f64) -> Spectrum {
    Spectrum {
        kind,
        significant_height: 4.0,
        peak_period: 10.0,
        gamma,
        components: 400,
        band: [0.5, 5.0],
        seed: 7,
    }
}

/// Trapezoidal integral of S over [a, b] in n panels.
fn integral(s: &Spectrum, a: f64, b: f64, n: usize) -> f64 {
    let h = (b - a) / n as f64;
    (0..=n)
        .map(|i| {
            let w = if i == 0 || i == n { 0.5 } else { 1.0 };
            w * s.density(a + i as f64 * h)
        })
        .sum::<f64>()
        * h
}

#[test]
fn pierson_moskowitz_carries_hs_squared_over_16() {
    let s = spectrum(SpectrumKind::PiersonMoskowitz, 3.3);
    let wp = s.peak_frequency();
    let m0 = integral(&s, 0.05 * wp, 200.0 * wp, 400_000);
    assert!((m0 - 1.0).abs() < 1e-4, "m0 = {m0}, Hs^2/16 = 1");
}

#[test]
fn jonswap_is_pierson_moskowitz_at_gamma_one_and_peaks_at_the_peak_frequency() {
    let pm = spectrum(SpectrumKind::PiersonMoskowitz, 3.3);
    let flat = spectrum(SpectrumKind::Jonswap, 1.0);
    let peaked = spectrum(SpectrumKind::Jonswap, 3.3);
    let wp = pm.peak_frequency();
    for w in [0.3 * wp, wp, 2.0 * wp] {
        assert_eq!(flat.density(w), pm.density(w));
    }
    let grid: Vec<f64> = (1..20_000).map(|i| wp * i as f64 / 5000.0).collect();
    let argmax = grid.iter().copied().fold(0.0, |best: f64, w| {
        if peaked.density(w) > peaked.density(best) {
            w
        } else {
            best
        }
    });
    assert!(
        (argmax / wp - 1.0).abs() < 1e-3,
        "JONSWAP peaks at {argmax}, wp = {wp}"
    );
    // DNV-RP-C205's normalisation A_gamma keeps the variance near Hs^2 / 16.
    let m0 = integral(&peaked, 0.05 * wp, 200.0 * wp, 400_000);
    assert!((m0 - 1.0).abs() < 0.02, "JONSWAP m0 = {m0}, Hs^2/16 = 1");
}

#[test]
fn the_discretised_sea_carries_the_band_variance_and_repeats_after_two_pi_over_dw() {
    let s = spectrum(SpectrumKind::Jonswap, 3.3);
    let sines = s.sines();
    assert_eq!(sines.len(), 400);
    let variance: f64 = sines.iter().map(|c| 0.5 * c.amplitude * c.amplitude).sum();
    let wp = s.peak_frequency();
    let band = integral(&s, 0.5 * wp, 5.0 * wp, 200_000);
    assert!(
        (variance / band - 1.0).abs() < 2e-3,
        "{variance} against {band}"
    );
    // The time series over one repeat period has that variance.
    let period = s.repeat_period();
    let n = 200_000;
    let elevation = |t: f64| sines.iter().map(|c| c.eval(t)[0]).sum::<f64>();
    let sampled: f64 = (0..n)
        .map(|i| elevation(period * i as f64 / n as f64).powi(2))
        .sum::<f64>()
        / n as f64;
    assert!(
        (sampled / variance - 1.0).abs() < 1e-9,
        "{sampled} against {variance}"
    );
    assert!((elevation(0.3) - elevation(0.3 + period)).abs() < 1e-9);
    assert!((s.resolution() - 4.5 * wp / 400.0).abs() < 1e-15);
}

#[test]
fn the_same_seed_makes_the_same_sea_and_another_another() {
    let a = spectrum(SpectrumKind::Jonswap, 3.3).sines();
    let b = spectrum(SpectrumKind::Jonswap, 3.3).sines();
    let mut other = spectrum(SpectrumKind::Jonswap, 3.3);
    other.seed = 8;
    let c = other.sines();
    assert_eq!(a, b);
    assert!(a.iter().zip(&c).all(|(x, y)| x.phase != y.phase));
    assert!(
        a.iter()
            .all(|x| (0.0..2.0 * std::f64::consts::PI).contains(&x.phase))
    );
}

#[test]
fn a_rao_scales_and_advances_each_component() {
    let rao = Rao {
        table: vec![[0.2, 1.0, 0.0], [0.6, 0.5, -1.0], [1.0, 0.1, -2.0]],
    };
    let (a, p) = rao.response(0.4);
    assert!(
        (a - 0.75).abs() < 1e-15 && (p + 0.5).abs() < 1e-15,
        "{a}, {p}"
    );
    assert_eq!(rao.response(1.0), (0.1, -2.0));
    assert_eq!(rao.response(0.1), (0.0, 0.0));
    assert_eq!(rao.response(1.5), (0.0, 0.0));
    let sea = SeaState {
        spectrum: spectrum(SpectrumKind::PiersonMoskowitz, 3.3),
        rao: Some(rao.clone()),
    };
    let waves = sea.spectrum.sines();
    for (motion, wave) in sea.sines().iter().zip(&waves) {
        let (a, p) = rao.response(wave.angular_frequency);
        assert_eq!(motion.amplitude, wave.amplitude * a);
        assert_eq!(motion.phase, wave.phase + p);
    }
}

#[test]
fn a_signal_and_an_end_motion_take_the_same_sea() {
    let sea = "sea = { spectrum = { kind = \"jonswap\", significant_height = 4.0, peak_period = 10.0, components = 50 } }";
    let signal: SignalParams =
        toml::from_str(&format!("quantity = \"displacement\"\n{sea}")).unwrap();
    assert_eq!(signal.sines.len(), 50);
    let motion: TimeFunction =
        toml::from_str::<toml::Table>(&format!("m = {{ offset = 1.0, {sea} }}")).unwrap()["m"]
            .clone()
            .try_into()
            .unwrap();
    for t in [0.0, 3.7, 120.0] {
        let value = motion.eval(t).unwrap()[0];
        assert!(
            (value - 1.0 - signal.value(t)).abs() < 1e-12,
            "{value} at {t}"
        );
    }
}

#[test]
fn a_bad_sea_is_refused_with_its_key() {
    let text = "quantity = \"displacement\"\nsea = { spectrum = { kind = \"jonswap\", significant_height = 4.0, peak_period = -10.0 } }";
    let signal: SignalParams = toml::from_str(text).unwrap();
    let message = crate::signal::source::Signal::new(signal)
        .err()
        .unwrap()
        .to_string();
    assert!(message.contains("sea.spectrum.peak_period"), "{message}");
    let rao = Rao {
        table: vec![[0.5, 1.0, 0.0], [0.4, 1.0, 0.0]],
    };
    let refusal = rao.validate().unwrap_err();
    assert_eq!(refusal.0, "table[1]");
}
