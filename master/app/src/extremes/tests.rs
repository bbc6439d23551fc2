use super::pot::{gpd_cdf, gpd_fit, gpd_level};
use super::{of, weibull_fit};
use std::f64::consts::PI;

/// A seeded uniform generator on (0, 1) (a 64-bit LCG's high bits).
fn uniform(seed: &mut u64) -> f64 {
    *seed = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    ((*seed >> 11) as f64 + 0.5) / (1u64 << 53) as f64
}

#[test]
fn weibull_samples_give_back_their_shape_and_scale() {
    // Inverse CDF: h = scale (-ln(1 - u))^(1 / shape).
    for (shape, scale) in [(2.0, 3.0), (1.3, 0.5), (3.5, 20.0)] {
        let mut seed = 11u64;
        let heights: Vec<f64> = (0..20_000)
            .map(|_| scale * (-(1.0 - uniform(&mut seed)).ln()).powf(1.0 / shape))
            .collect();
        let (k, lambda, r2) = weibull_fit(&heights).expect("fit");
        assert!((k / shape - 1.0).abs() < 0.02, "{k} against {shape}");
        assert!(
            (lambda / scale - 1.0).abs() < 0.01,
            "{lambda} against {scale}"
        );
        assert!(r2 > 0.995, "{r2}");
    }
    assert!(weibull_fit(&[1.0; 9]).is_none(), "nine points are no fit");
}

#[test]
fn a_narrow_band_gaussian_sea_has_rayleighs_most_probable_maximum() {
    // 60 random-phase components of a narrow band around 0.1 Hz (40 %
    // wide, bandwidth parameter ~0.1): its peaks are nearly Rayleigh, so
    // over a 3-hour storm both estimates from a 20,000 s record give
    // Rayleigh's closed form from the spectrum, sqrt(2 m0 ln(T / Tz)) with
    // Tz = 2 pi sqrt(m0 / m2), within the sampling error of ~2000 cycles
    // (~400 independent envelope samples).
    let mut seed = 5u64;
    let components: Vec<(f64, f64, f64)> = (0..60)
        .map(|k| {
            let f = 0.08 + 0.04 * (k as f64 + uniform(&mut seed)) / 60.0;
            let a = 0.2 * (1.0 - ((k as f64 - 30.0) / 31.0).powi(2));
            (a, 2.0 * PI * f, 2.0 * PI * uniform(&mut seed))
        })
        .collect();
    let m0: f64 = components.iter().map(|(a, _, _)| a * a / 2.0).sum();
    let m2: f64 = components.iter().map(|(a, w, _)| a * a * w * w / 2.0).sum();
    let dt = 0.25;
    let time: Vec<f64> = (0..=80_000).map(|k| k as f64 * dt).collect();
    let values: Vec<f64> = (time.iter())
        .map(|t| {
            let waves: f64 = components
                .iter()
                .map(|(a, w, p)| a * (w * t + p).sin())
                .sum();
            10.0 + waves
        })
        .collect();
    let storm = 10_800.0;
    let tz = 2.0 * PI * (m0 / m2).sqrt();
    let closed_form = 10.0 + (2.0 * m0 * (storm / tz).ln()).sqrt();
    let e = of((&time, &values), 0.0, (storm, 1.4)).expect("extremes");
    assert!(
        (e.peaks as f64 / (20_000.0 / tz) - 1.0).abs() < 0.01,
        "{e:?} against {tz}"
    );
    assert!(
        (e.rayleigh_mpm / closed_form - 1.0).abs() < 0.01,
        "{e:?} against {closed_form}"
    );
    let w = e.weibull.expect("fit");
    assert!((w.shape - 2.0).abs() < 0.15, "{w:?}");
    assert!(w.r_squared > 0.98, "{w:?}");
    assert!(
        (w.mpm / closed_form - 1.0).abs() < 0.02,
        "{w:?} against {closed_form}"
    );
    // The tail above mean + 1.4 sd: about exp(-1.4^2 / 2) = 38 % of the
    // peaks. A Rayleigh tail lies in Gumbel's domain (shape 0 in the limit)
    // but at a finite threshold its hazard still grows, so the fitted shape
    // is negative (the penultimate approximation) and the GPD's maximum
    // reads low: 3.2 % here, a known bias of peaks over threshold on a
    // Gaussian process (Rayleigh's closed form is the better estimate there).
    let g = e.gpd.expect("peaks over threshold");
    let share = g.exceedances as f64 / e.peaks as f64;
    assert!((share - (-0.98f64).exp()).abs() < 0.03, "{g:?}");
    assert!((-0.4..-0.1).contains(&g.shape), "{g:?}");
    assert!(
        g.ks_distance < 1.36 / (g.exceedances as f64).sqrt(),
        "{g:?}"
    );
    let low = 1.0 - g.mpm / closed_form;
    assert!((0.0..0.05).contains(&low), "{g:?} against {closed_form}");
}

#[test]
fn peaks_over_threshold_carry_an_exponential_tail_to_the_storm() {
    // One peak every 3 s of height 0.5 + Exp(1) between troughs at -2: the
    // excesses over any threshold above 0.5 are Exp(1) (no memory), so the
    // most probable largest of the N = 3600 cycles of a 3-hour storm is
    // 0.5 + ln N = 8.69, whatever share of the peaks passes the threshold.
    let mut seed = 3u64;
    let mut values = Vec::new();
    let cycles = 100_000;
    for _ in 0..cycles {
        values.extend([-2.0, 0.5 - (1.0 - uniform(&mut seed)).ln(), -2.0]);
    }
    let time: Vec<f64> = (0..values.len()).map(|k| k as f64).collect();
    let truth = 0.5 + 3600f64.ln();
    for threshold in [1.4, 2.0] {
        let e = of((&time, &values), 0.0, (10_800.0, threshold)).expect("extremes");
        let g = e.gpd.expect("peaks over threshold");
        assert!(g.shape.abs() < 0.03, "{g:?}");
        assert!((g.scale - 1.0).abs() < 0.03, "{g:?}");
        // The exceedances carried to the storm: with the exact law (shape
        // 0, scale 1) they give the truth within 1 %.
        let carried = g.exceedances as f64 * 3600.0 / cycles as f64;
        let exponential = g.threshold + carried.ln();
        assert!((exponential / truth - 1.0).abs() < 0.01, "{g:?}");
        // The fitted shape's sampling error (about 0.01 on these ten
        // thousand excesses) moves the maximum by about 2 % per 0.01 at
        // N ~ 1000.
        assert!((g.mpm / truth - 1.0).abs() < 0.03, "{g:?} against {truth}");
    }
}

#[test]
fn gpd_samples_give_back_their_shape_and_scale() {
    // Inverse CDF: y = scale / shape ((1 - u)^-shape - 1), or -scale ln(1 - u).
    for (shape, scale) in [(-0.2, 2.0), (0.0, 1.0), (0.2, 5.0)] {
        let mut seed = 7u64;
        let excesses: Vec<f64> = (0..20_000)
            .map(|_| {
                let u = uniform(&mut seed);
                if shape == 0.0 {
                    -scale * (1.0 - u).ln()
                } else {
                    scale / shape * ((1.0 - u).powf(-shape) - 1.0)
                }
            })
            .collect();
        let (xi, sigma) = gpd_fit(&excesses).expect("fit");
        assert!((xi - shape).abs() < 0.03, "{xi} against {shape}");
        assert!(
            (sigma / scale - 1.0).abs() < 0.03,
            "{sigma} against {scale}"
        );
        // Once in n excesses: the (1 - 1/n) quantile.
        for n in [10.0, 1e4] {
            let level = gpd_level(n, shape, scale);
            assert!((gpd_cdf(level, shape, scale) - (1.0 - 1.0 / n)).abs() < 1e-12);
        }
    }
    assert!(gpd_fit(&[1.0; 9]).is_none(), "nine excesses are no fit");
}

#[test]
fn a_build_up_is_left_out_and_a_flat_signal_has_no_peaks() {
    let time: Vec<f64> = (0..=2000).map(|k| k as f64 * 0.1).collect();
    let values: Vec<f64> = (time.iter())
        .map(|t| (2.0 * PI * t / 10.0).sin() + 30.0 * (-t).exp())
        .collect();
    let e = of((&time, &values), 20.0, (200.0, 1.4)).expect("extremes");
    assert!((e.largest_seen - 1.0).abs() < 1e-3, "{e:?}");
    assert!((16..=17).contains(&e.peaks), "{e:?}");
    // A sine's Rayleigh estimate over 20 cycles: sqrt(2 ln 20) sigma.
    let rayleigh = (2.0 * 20f64.ln()).sqrt() / 2f64.sqrt();
    assert!((e.rayleigh_mpm - rayleigh).abs() < 0.02, "{e:?}");
    assert!(of((&time, &vec![2.0; time.len()]), 0.0, (100.0, 1.4)).is_none());
}
