//! The adaptive coupling step on the riser (`examples/structure_riser.toml`,
//! its heave and surge faded in over 20 s): the step follows the motion,
//! every unit is rolled back with a repeated step (the partition stays on its
//! monolithic twin), and the answers stay those of the fixed step.

use slender_scene::Scene;
use slender_tests::{rms, root, run};

const SYNC: f64 = 0.4;
const DURATION: f64 = 40.0;

/// The riser example over 40 s with `master` lines added to its `[master]`
/// and a synchronisation step of `step` s.
fn riser(step: f64, master: &str) -> Scene {
    let path = root().join("examples/structure_riser.toml");
    let text = std::fs::read_to_string(&path).expect("the example");
    let newton = "newton = { derivatives = \"units\", one_sweep = true }\n";
    assert!(text.contains("step = 0.05\n") && text.contains(newton));
    let text = text
        .replace("step = 0.05\n", &format!("step = {step:?}\n"))
        .replace("duration = 200.0", &format!("duration = {DURATION:?}"))
        .replace(newton, &format!("{newton}{master}\n"));
    Scene::parse(&path, text).unwrap_or_else(|e| panic!("{e}"))
}

/// The steps the master took in each synchronisation step.
fn steps_per_sync(scene: &Scene) -> Vec<u64> {
    let mut master = scene.build().expect("the riser");
    master.initialize(scene.start).expect("initialised");
    let mut taken = 0;
    let mut per_sync = Vec::new();
    for _ in 0..scene.steps {
        master.step().expect("a step");
        let steps = master.counters().steps;
        per_sync.push(steps - taken);
        taken = steps;
    }
    per_sync
}

#[test]
fn the_riser_s_step_follows_its_faded_in_motion_and_its_answers_stay_the_fixed_step_s() {
    let adaptive = riser(
        SYNC,
        "adaptive = { min_step = 0.0125, interface = false, displacement = 1e-3 }",
    );
    let per_sync = steps_per_sync(&adaptive);
    let second = |from: f64, to: f64| -> f64 {
        let range = (from / SYNC) as usize..(to / SYNC) as usize;
        per_sync[range.clone()].iter().sum::<u64>() as f64 / (to - from)
    };
    let (early, late) = (second(0.0, 2.0), second(30.0, 40.0));
    eprintln!("steps per second: {early:.1} in the first 2 s, {late:.1} at 30-40 s");
    assert!(late > 2.0 * early, "{early} then {late}");

    let series = run(&adaptive);
    assert!(series.error.is_none(), "{:?}", series.error);
    let sizes = series.counters.adaptive.clone().expect("adaptive counters");
    eprintln!("{sizes:?}");
    assert_eq!(sizes.over_tolerance, 0, "{sizes:?}");
    assert!(sizes.rejected > 0, "{sizes:?}");
    assert!(sizes.accepted[0] > 0 && sizes.accepted[4] > 0, "{sizes:?}");
    // The partition against its twin as at the example's fixed step.
    for indicator in &series.indicators {
        assert!(
            indicator.relative_error < 1e-3,
            "{}: {}",
            indicator.name,
            indicator.relative_error
        );
    }
    // Against the example's fixed step of 0.05 s, recorded at the same times.
    let fixed = run(&riser(0.05, ""));
    let every = (SYNC / 0.05).round() as usize;
    for signal in ["riser_top.end_force_x", "riser_sagbend.sagbend_moment"] {
        let (a, f) = (series.get(signal), fixed.get(signal));
        let f: Vec<f64> = f.iter().copied().step_by(every).collect();
        assert_eq!(a.len(), f.len(), "{signal}");
        let mean = f.iter().sum::<f64>() / f.len() as f64;
        let spread = rms(f.iter().map(|x| x - mean));
        let difference = rms(a.iter().zip(&f).map(|(x, y)| x - y));
        eprintln!(
            "{signal}: rms difference {:.3e} of its spread",
            difference / spread
        );
        assert!(
            difference < 0.05 * spread,
            "{signal}: {difference} against {spread}"
        );
    }
}
