//! The artefact unit on a known signal, a ramp x(t) = t (seed 000 Fig. 3): each
//! artefact alone, statistics over many samples, and exact repetition after rollback.

use slender_units::signal::artefact::{Artefact, ArtefactParams};
use slender_units::{Driver, DriverSlot};
use slender_units::{PortKind, Time};

const H: f64 = 0.01;

fn params() -> ArtefactParams {
    ArtefactParams {
        quantity: PortKind::Force,
        channels: vec!["x".into()],
        scale: None,
        bias: None,
        noise_variance: None,
        delay: 0.0,
        lag: 0.0,
        hold_period: 0.0,
        loss_probability: 0.0,
        loss_probability_per_second: 0.0,
        loss_duration_mean: 0.0,
        loss_duration_rate: 0.0,
        seed: 7,
    }
}

/// Drives the unit with the ramp for `steps` steps; returns (t, output) pairs.
fn ramp(p: ArtefactParams, steps: usize) -> (Vec<(f64, f64)>, Driver<Artefact>) {
    ramp_at(p, steps, H)
}

/// The same at steps of `step` seconds.
fn ramp_at(p: ArtefactParams, steps: usize, step: f64) -> (Vec<(f64, f64)>, Driver<Artefact>) {
    let mut a = Driver::new(Artefact::new(p).unwrap());
    a.set_inputs(&[0.0]).unwrap();
    a.initialize(Time::ZERO).unwrap();
    let h = Time::from_secs(step).unwrap();
    let mut out = Vec::with_capacity(steps);
    let mut y = [0.0];
    for k in 0..steps {
        let t_end = (k + 1) as f64 * step;
        a.set_inputs(&[t_end]).unwrap();
        a.do_step(h * k as i64, h).unwrap();
        a.outputs(&mut y).unwrap();
        out.push((t_end, y[0]));
    }
    (out, a)
}

#[test]
fn calibration_and_bias_are_exact() {
    let (s, _) = ramp(
        ArtefactParams {
            scale: Some(vec![1.5]),
            bias: Some(vec![2.0]),
            ..params()
        },
        1000,
    );
    for (t, y) in s {
        assert!((y - (1.5 * t + 2.0)).abs() < 1e-12);
    }
}

#[test]
fn noise_has_the_asked_variance_and_zero_mean() {
    let n = 200_000;
    let (s, _) = ramp(
        ArtefactParams {
            noise_variance: Some(vec![4.0]),
            ..params()
        },
        n,
    );
    let e: Vec<f64> = s.iter().map(|(t, y)| y - t).collect();
    let mean = e.iter().sum::<f64>() / n as f64;
    let var = e.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
    eprintln!("noise: mean {mean:.4}, variance {var:.4} (asked 4)");
    assert!(mean.abs() < 0.02);
    assert!((var - 4.0).abs() < 0.04 * 4.0);
}

#[test]
fn any_delay_shifts_the_ramp_exactly() {
    for delay in [0.0026, 0.01, 0.026, 0.05] {
        let (s, _) = ramp(ArtefactParams { delay, ..params() }, 500);
        for (t, y) in s.iter().filter(|(t, _)| *t > delay + H) {
            assert!(
                (y - (t - delay)).abs() < 1e-12,
                "delay {delay}: at {t}, {y}"
            );
        }
    }
}

#[test]
fn zero_order_hold_updates_every_period() {
    let (s, _) = ramp(
        ArtefactParams {
            hold_period: 0.05,
            ..params()
        },
        100,
    );
    for (t, y) in s {
        let held = (t / 0.05 + 1e-9).floor() * 0.05;
        assert!((y - held).abs() < 1e-9, "at {t}: {y} vs {held}");
    }
}

#[test]
fn signal_losses_start_and_last_as_asked() {
    let (p, mean) = (0.01, 0.1);
    let steps = 1_000_000;
    let (s, a) = ramp(
        ArtefactParams {
            loss_probability: p,
            loss_duration_mean: mean,
            ..params()
        },
        steps,
    );
    let (lost_steps, losses) = a.loss_statistics();
    // Losses start with probability p at each step not already lost.
    let rate = losses as f64 / (steps as u64 - lost_steps) as f64;
    // Each loss covers the steps ending before its end: about D / h + 1/2 steps.
    let mean_steps = lost_steps as f64 / losses as f64;
    eprintln!(
        "{losses} losses, start probability {rate:.5} (asked {p}), {mean_steps:.2} steps each (expected {:.2})",
        mean / H + 0.5
    );
    assert!((rate - p).abs() < 0.05 * p);
    assert!((mean_steps - (mean / H + 0.5)).abs() < 0.05 * (mean / H));
    // While lost the value is frozen.
    let frozen = s.windows(2).filter(|w| w[1].1 == w[0].1).count() as u64;
    assert!(frozen >= lost_steps - losses);
}

#[test]
fn a_loss_probability_per_second_starts_as_many_losses_whatever_the_step() {
    // p = 0.5 per second: losses start as a Poisson process of rate -ln(1 - p)
    // = ln 2 per second of signal, at 10 ms as at 1 ms steps.
    let p = 0.5;
    for (step, steps) in [(0.01, 400_000), (0.001, 4_000_000)] {
        let (_, a) = ramp_at(
            ArtefactParams {
                loss_probability_per_second: p,
                loss_duration_mean: 0.05,
                ..params()
            },
            steps,
            step,
        );
        let (lost_steps, losses) = a.loss_statistics();
        // Each step not already lost is a trial, the one starting a loss too.
        let trials = (steps as u64 - lost_steps + losses) as f64;
        let q = 1.0 - (1.0 - p).powf(step);
        let (expected, sd) = (q * trials, (trials * q * (1.0 - q)).sqrt());
        eprintln!("step {step}: {losses} losses, expected {expected:.0} +- {sd:.0}");
        assert!((losses as f64 - expected).abs() < 4.0 * sd);
        // About ln 2 per second of signal at either step.
        let per_second = losses as f64 / (trials * step);
        assert!((per_second - std::f64::consts::LN_2).abs() < 0.1);
    }
    let both = ArtefactParams {
        loss_probability: 0.01,
        loss_probability_per_second: 0.5,
        loss_duration_mean: 0.1,
        ..params()
    };
    let why = Artefact::new(both).err().unwrap().to_string();
    assert!(why.contains("not both"), "{why}");
}

#[test]
fn losses_read_in_steps_last_one_over_zeta2_steps() {
    // Seed 000's other reading: d in synchronisation steps, density
    // zeta2 exp(-zeta2 d), mean 1 / zeta2 steps: zeta2 = 0.47 gives about 2.1
    // steps (21 ms at 10 ms), zeta2 = 0.1 the 10 steps of the reading in seconds.
    for zeta2 in [0.47, 0.1] {
        let steps = 1_000_000;
        let (_, a) = ramp(
            ArtefactParams {
                loss_probability: 0.01,
                loss_duration_rate: zeta2,
                ..params()
            },
            steps,
        );
        let (lost_steps, losses) = a.loss_statistics();
        let mean_steps = lost_steps as f64 / losses as f64;
        eprintln!(
            "zeta2 {zeta2}: {mean_steps:.2} steps per loss (expected {:.2})",
            1.0 / zeta2 + 0.5
        );
        assert!((mean_steps - (1.0 / zeta2 + 0.5)).abs() < 0.05 * (1.0 / zeta2 + 0.5));
    }
    // Both readings at once are refused.
    let both = ArtefactParams {
        loss_probability: 0.01,
        loss_duration_mean: 0.1,
        loss_duration_rate: 0.1,
        ..params()
    };
    assert!(Artefact::new(both).is_err());
}

#[test]
fn two_channels_share_losses_and_delay_but_not_calibration() {
    let mut p = params();
    p.channels = vec!["x".into(), "z".into()];
    p.scale = Some(vec![2.0, 1.0]);
    p.loss_probability = 0.05;
    p.loss_duration_mean = 0.05;
    let mut a = Driver::new(Artefact::new(p).unwrap());
    a.set_inputs(&[0.0, 0.0]).unwrap();
    a.initialize(Time::ZERO).unwrap();
    let h = Time::from_secs(H).unwrap();
    let mut y = [0.0; 2];
    for k in 0..2000 {
        let t = (k + 1) as f64 * H;
        a.set_inputs(&[t, t]).unwrap();
        a.do_step(h * k as i64, h).unwrap();
        a.outputs(&mut y).unwrap();
        assert!(
            (y[0] - 2.0 * y[1]).abs() < 1e-9,
            "channels froze apart at {t}"
        );
    }
    assert!(a.loss_statistics().1 > 10);
}

#[test]
fn a_repeated_step_sees_the_same_noise_and_losses() {
    let p = ArtefactParams {
        noise_variance: Some(vec![1.0]),
        loss_probability: 0.2,
        loss_duration_mean: 0.03,
        delay: 0.013,
        ..params()
    };
    let (_, mut a) = ramp(p, 50);
    let h = Time::from_secs(H).unwrap();
    let mut slot = DriverSlot::new();
    let mut first = Vec::new();
    a.save(&mut slot).unwrap();
    for k in 50..80 {
        a.set_inputs(&[k as f64 * H]).unwrap();
        a.do_step(h * k, h).unwrap();
        let mut y = [0.0];
        a.outputs(&mut y).unwrap();
        first.push(y[0].to_bits());
    }
    a.restore(&slot).unwrap();
    for (i, k) in (50..80).enumerate() {
        a.set_inputs(&[k as f64 * H]).unwrap();
        a.do_step(h * k, h).unwrap();
        let mut y = [0.0];
        a.outputs(&mut y).unwrap();
        assert_eq!(y[0].to_bits(), first[i]);
    }
}

#[test]
fn bad_parameters_are_refused() {
    assert!(
        Artefact::new(ArtefactParams {
            loss_probability: 1.0,
            ..params()
        })
        .is_err()
    );
    assert!(
        Artefact::new(ArtefactParams {
            delay: -0.1,
            ..params()
        })
        .is_err()
    );
    assert!(
        Artefact::new(ArtefactParams {
            scale: Some(vec![1.0, 2.0]),
            ..params()
        })
        .is_err()
    );
    assert!(
        Artefact::new(ArtefactParams {
            noise_variance: Some(vec![-1.0]),
            ..params()
        })
        .is_err()
    );
    let e = Artefact::new(ArtefactParams {
        loss_probability: 0.1,
        ..params()
    })
    .err()
    .unwrap();
    assert!(e.to_string().contains("loss_duration_mean"), "{e}");
}
