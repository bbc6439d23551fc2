//! Actuator delay and its compensation (issue 15, seed 002 sec. 3.4) on the
//! hybrid test of a damped oscillator (`examples/hybrid_oscillator.toml`): m =
//! 1 kg and c = 1 N s/m numerical, the spring k = 100 N/m physical behind an
//! actuator. A delay tau makes the spring force k x(t - tau) ~ k x - k tau x',
//! a negative damping k tau: zeta falls by omega tau / 2. Predicting the command
//! tau ahead gives the damping back. The damping ratio is measured from the free
//! decay's logarithmic decrement.

use slender_scene::Scene;
use slender_tests::{root, run};

const SCENE: &str = "examples/hybrid_oscillator.toml";

/// The scene with its actuators' delay and lag, and the compensation's lead
/// (all in seconds).
fn hybrid(delay: f64, lag: f64, lead: f64) -> Scene {
    let path = root().join(SCENE);
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replace(
            "delay = 0.005 }",
            &format!("delay = {delay}, lag = {lag} }}"),
        )
        .replace("lead = 0.005", &format!("lead = {lead}"));
    Scene::parse(&path, text).unwrap_or_else(|e| panic!("{e}"))
}

/// Damping ratio from the decay of the positive peaks of x over the run.
fn damping_ratio(x: &[f64]) -> f64 {
    let peaks: Vec<f64> = x
        .windows(3)
        .filter(|w| w[1] > w[0] && w[1] >= w[2] && w[1] > 0.0)
        .map(|w| w[1])
        .collect();
    assert!(peaks.len() > 5, "{} peaks", peaks.len());
    let n = (peaks.len() - 1) as f64;
    let delta = (peaks[0] / peaks[peaks.len() - 1]).ln() / n;
    delta / (4.0 * std::f64::consts::PI.powi(2) + delta * delta).sqrt()
}

fn measured(delay: f64, lag: f64, lead: f64) -> f64 {
    let s = run(&hybrid(delay, lag, lead));
    assert!(s.error.is_none(), "{:?}", s.error);
    damping_ratio(s.get("numerical.displacement"))
}

#[test]
fn compensation_removes_the_negative_damping_of_a_delay() {
    // omega = 10 rad/s, zeta = c / (2 m omega) = 0.05.
    let (omega, zeta) = (10.0, 0.05);
    let exact = measured(0.0, 0.0, 0.0);
    let delayed = measured(0.005, 0.0, 0.0);
    let compensated = measured(0.005, 0.0, 0.005);
    eprintln!(
        "zeta: no actuator {exact:.4}, delay 5 ms {delayed:.4} (predicted {:.4}), compensated {compensated:.4}",
        zeta - omega * 0.005 / 2.0
    );
    // The loop itself is a delay of one step (Gauss-Seidel: the numerical part
    // uses the spring force of the step before), h = 1 ms: omega h / 2 = 0.005
    // off the exact 0.05 (measured 0.0450).
    let h = 0.001;
    assert!((exact - (zeta - omega * h / 2.0)).abs() < 0.001, "{exact}");
    // The delay takes omega tau / 2 = 0.025 off (measured 0.0200).
    assert!(
        (delayed - (exact - omega * 0.005 / 2.0)).abs() < 0.003,
        "{delayed}"
    );
    // The prediction gives it back (measured 0.0450).
    assert!((compensated - exact).abs() < 0.002, "{compensated}");
}

#[test]
fn an_emulated_actuator_with_delay_and_lag_is_compensated_by_their_sum() {
    // A first-order lag of time constant T acts, at omega T << 1, as a delay T
    // (measured: 0.0224 with the actuator, 0.0474 compensated, 0.0450 without).
    let exact = measured(0.0, 0.0, 0.0);
    let actuator = measured(0.002, 0.003, 0.0);
    let compensated = measured(0.002, 0.003, 0.005);
    eprintln!(
        "zeta: no actuator {exact:.4}, delay 2 ms + lag 3 ms {actuator:.4}, compensated by 5 ms {compensated:.4}"
    );
    assert!(
        (actuator - (exact - 10.0 * 0.005 / 2.0)).abs() < 0.004,
        "{actuator}"
    );
    assert!((compensated - exact).abs() < 0.003, "{compensated}");
}
