//! Multi-rate stepping (issue 15, seed 002 sec. 3.4): a unit that steps n times
//! per synchronisation step, its inputs interpolated within the step. With
//! inputs the interpolation represents exactly (a ramp), it reproduces the unit
//! stepped at the fine rate on its own; a scene asks for it per unit, and a
//! step that does not split into whole nanoseconds is refused.

use slender_scene::Scene;
use slender_tests::{root, run};
use slender_units::benchmark::oscillator::{Oscillator, OscillatorParams};
use slender_units::{Driver, Time};

fn oscillator() -> Driver<Oscillator> {
    let params: OscillatorParams =
        toml::from_str("mass = 1.0\nstiffness = 100.0\ndamping = 0.5\ncoupling = \"force\"")
            .expect("parameters");
    let mut d = Driver::new(Oscillator::new(params).expect("oscillator"));
    d.set_inputs(&[0.0]).unwrap();
    d.initialize(Time::ZERO).unwrap();
    d
}

/// Displacement every `every` steps of `h` under the force F(t) = 10 t.
fn history(driver: &mut Driver<Oscillator>, h: f64, steps: usize, every: usize) -> Vec<f64> {
    let step = Time::from_secs(h).unwrap();
    let mut out = [0.0; 2];
    let mut t = Time::ZERO;
    let mut kept = Vec::new();
    for k in 1..=steps {
        driver.set_inputs(&[10.0 * k as f64 * h]).unwrap();
        driver.do_step(t, step).unwrap();
        t += step;
        if k % every == 0 {
            driver.outputs(&mut out).unwrap();
            kept.push(out[0]);
        }
    }
    kept
}

#[test]
fn ten_substeps_with_ramp_inputs_are_the_fine_rate_run() {
    let fine = history(&mut oscillator(), 1e-3, 2000, 10);
    let mut coarse = oscillator();
    coarse.set_substeps(10).unwrap();
    let multirate = history(&mut coarse, 1e-2, 200, 1);
    let single = history(&mut oscillator(), 1e-2, 200, 1);
    let scale = fine.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let diff = |a: &[f64]| {
        a.iter()
            .zip(&fine)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
            / scale
    };
    eprintln!(
        "against the fine rate: 10 sub-steps {:.1e}, one step {:.1e}",
        diff(&multirate),
        diff(&single)
    );
    // Equal to the round-off of the interpolated inputs (the fine run sets
    // 10 t directly): 1.0e-12 measured over 2 000 fine steps.
    assert!(diff(&multirate) < 1e-10, "{}", diff(&multirate));
    // And it is not the single-rate run (Newmark's error at h = 10 ms is visible).
    assert!(diff(&single) > 1e-6);
    assert!(coarse.set_substeps(0).is_err());
}

#[test]
fn scenes_choose_substeps_per_unit_and_refuse_a_step_that_does_not_split() {
    let path = root().join("examples/b1_two_masses.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let with = |line: &str| {
        let t = text.replacen(
            "kind = \"oscillator\"",
            &format!("kind = \"oscillator\"\n{line}"),
            1,
        );
        Scene::parse(&path, t)
    };
    let plain = run(&Scene::parse(&path, text.clone()).unwrap());
    let sub = run(&with("substeps = 10").unwrap());
    assert!(sub.error.is_none(), "{:?}", sub.error);
    let (a, b) = (
        plain.last("left.displacement"),
        sub.last("left.displacement"),
    );
    assert!(
        a != b && (a - b).abs() < 1e-3 * a.abs().max(1e-3),
        "{a} {b}"
    );
    let refused = with("substeps = 3").expect_err("refused").to_string();
    assert!(
        refused.contains("substeps") && refused.contains("whole nanoseconds"),
        "{refused}"
    );
}
