//! A body in waves against closed forms: the steady response of a linear
//! oscillator to a regular wave through a force RAO, a motion RAO's motion,
//! the table's interpolation and the refusals.

use super::tests::{body_params, outs, secs};
use super::waves::RaoTable;
use super::*;
use crate::contract::Driver;

/// A table of one heading (0 deg) and two frequencies, `value` (amplitude,
/// phase in deg) in degree of freedom `dof`, zero elsewhere.
fn table(dof: usize, value: [(f64, f64); 2]) -> RaoTable {
    let mut amplitude = vec![vec![vec![0.0; 2]; 1]; 6];
    let mut phase_deg = vec![vec![vec![0.0; 2]; 1]; 6];
    for (f, (a, p)) in value.iter().enumerate() {
        amplitude[dof][0][f] = *a;
        phase_deg[dof][0][f] = *p;
    }
    RaoTable {
        frequencies: vec![0.2, 1.2],
        headings_deg: vec![0.0],
        amplitude,
        phase_deg,
    }
}

/// A regular wave of amplitude `a` (m) and frequency `w` (rad/s), heading 0.
fn wave(a: f64, w: f64) -> crate::line3d::params::Waves {
    toml::from_str(&format!(
        "sines = [{{ amplitude = {a}, angular_frequency = {w}, phase = 0.4 }}]"
    ))
    .unwrap()
}

#[test]
fn a_regular_wave_through_a_force_rao_gives_the_oscillator_s_steady_response() {
    // Surge: m 2e5 kg, k 8e5 N/m, b 2e5 N s/m (zeta 0.25); a 1 m wave at
    // 1.5 rad/s; the RAO 3e5 N/m at 30 deg, constant in frequency.
    let (w, force, lead) = (1.5_f64, 3e5_f64, 30f64.to_radians());
    let mut p = body_params([3.0e7, 4.0e7, 5.0e7]);
    let (m, k, b) = (p.mass, 8e5, 2e5);
    p.hydrostatic_stiffness[0][0] = k;
    p.damping_linear[0][0] = b;
    p.waves = Some(wave(1.0, w));
    p.force_rao = Some(table(0, [(force, 30.0), (force, 30.0)]));
    let h = 2.0 * std::f64::consts::PI / w / 200.0;
    let mut driver = Driver::new(Body::new(p).unwrap());
    driver.initialize(Time::ZERO).unwrap();
    // The response x = X sin(w t + 0.4 + lead - delay), X = F / |k - m w^2 + i b w|.
    let denominator = (k - m * w * w).hypot(b * w);
    let (amplitude, delay) = (force / denominator, (b * w).atan2(k - m * w * w));
    let mut worst = 0.0_f64;
    let steps = (120.0 / h) as usize;
    for n in 0..steps {
        driver.do_step(secs(n as f64 * h), secs(h)).unwrap();
        let t = (n + 1) as f64 * h;
        if t > 80.0 {
            let exact = amplitude * (w * t + 0.4 + lead - delay).sin();
            worst = worst.max((outs(&driver)[0] - exact).abs());
        }
    }
    eprintln!("regular wave on a surge oscillator: {worst:.3e} m of {amplitude:.4} m");
    // The trapezoidal rule at 200 steps a period: a phase error of
    // (w h)^2 / 12 per radian, 8e-5 of the amplitude.
    assert!(worst < 2e-4 * amplitude, "{worst:e} of {amplitude}");
}

#[test]
fn a_motion_rao_moves_the_body_as_the_wave_asks() {
    // Heave 0.8 m/m at 1.2 rad/s, 0.6 m/m at 0.2 rad/s, -45 and -10 deg:
    // at 0.7 rad/s (half way) the real and imaginary parts are averaged.
    let mut p = body_params([3.0e7, 4.0e7, 5.0e7]);
    p.reference = [10.0, 0.0, 0.0];
    p.waves = Some(wave(2.0, 0.7));
    let rao = table(2, [(0.6, -10.0), (0.8, -45.0)]);
    let (re, im) = {
        let (a, b) = ((0.6, -10f64.to_radians()), (0.8, -45f64.to_radians()));
        (
            0.5 * (a.0 * a.1.cos() + b.0 * b.1.cos()),
            0.5 * (a.0 * a.1.sin() + b.0 * b.1.sin()),
        )
    };
    p.motion_rao = Some(rao);
    let mut driver = Driver::new(Body::new(p).unwrap());
    driver.initialize(Time::ZERO).unwrap();
    let k = 0.7 * 0.7 / crate::line3d::waves::GRAVITY;
    for n in 0..50 {
        driver.do_step(secs(n as f64 * 0.2), secs(0.2)).unwrap();
        let t = (n + 1) as f64 * 0.2;
        let exact = 2.0 * re.hypot(im) * (0.7 * t + 0.4 - k * 10.0 + im.atan2(re)).sin();
        let z = outs(&driver)[2];
        assert!((z - exact).abs() < 1e-12, "{t}: {z} vs {exact}");
    }
}

#[test]
fn a_table_that_does_not_fit_is_refused_by_key() {
    let mut p = body_params([3.0e7, 4.0e7, 5.0e7]);
    p.force_rao = Some(table(0, [(1.0, 0.0), (1.0, 0.0)]));
    let e = Body::new(p.clone()).err().unwrap().to_string();
    assert!(e.contains("force_rao") && e.contains("waves"), "{e}");
    let mut sea = wave(1.0, 0.5);
    sea.heading_deg = 30.0;
    p.waves = Some(sea);
    let e = Body::new(p.clone()).err().unwrap().to_string();
    assert!(
        e.contains("force_rao.headings_deg") && e.contains("30"),
        "{e}"
    );
    p.waves = Some(wave(1.0, 0.5));
    if let Some(t) = &mut p.force_rao {
        t.amplitude[3].pop();
    }
    let e = Body::new(p).err().unwrap().to_string();
    assert!(
        e.contains("force_rao.amplitude") && e.contains("6 degrees of freedom"),
        "{e}"
    );
}
