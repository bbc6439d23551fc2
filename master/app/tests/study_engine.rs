//! The study engine's own measures: an indicator with reference signals of its
//! own is measured inside every run (also the group's reference run), under the
//! norm the scene names.

use slender_app::study::{Design, StudyPlan, Sweep, run_study};

const SCENE: &str = r#"
title = "two prescribed signals, one measured against the other"
[simulation]
duration = 2.0
step = 0.01
[master]
scheme = "gauss_seidel"
[[units]]
name = "model"
kind = "signal"
parameters = { quantity = "rotation", sines = [{ amplitude = 1.0, angular_frequency = 3.0 }] }
[[units]]
name = "truth"
kind = "signal"
parameters = { quantity = "rotation", sines = [{ amplitude = 1.1, angular_frequency = 3.0 }] }
[[output.indicators]]
name = "gap"
signals = ["model.value"]
reference = ["truth.value"]
norm = "peak"
"#;

#[test]
fn an_in_run_reference_is_measured_in_every_run_under_its_norm() {
    let dir = std::env::temp_dir().join(format!("slender-study-engine-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("gap.toml");
    std::fs::write(&path, SCENE).unwrap();
    let plan = StudyPlan {
        overrides: Vec::new(),
        max_runs: slender_app::DEFAULT_MAX_RUNS,
        sweeps: vec![
            "units.model.parameters.sines.0.amplitude=1.0,1.2"
                .parse::<Sweep>()
                .unwrap(),
        ],
        design: Design::OneAtATime,
        duration: None,
        jobs: 1,
        cost_units: vec!["model".into()],
        reference: None,
        repeats: 3,
    };
    let rows = run_study(&path, &plan, |_| {}).unwrap();
    assert_eq!(rows.len(), 2);
    for (row, amplitude) in rows.iter().zip([1.0, 1.2]) {
        // Both sines peak at the same instants: the largest gap is |a - 1.1| of 1.1.
        let expected = (amplitude - 1.1f64).abs() / 1.1;
        let e = row.errors[0].1;
        assert!(
            (e - expected).abs() < 2e-3 * expected,
            "{amplitude}: {e} vs {expected}"
        );
        assert!(row.cost_per_simulated_second.is_finite());
        // Timed three times: the median and a spread (the run is repeated, its
        // results are the first run's).
        assert!(row.cost_spread >= 0.0, "{}", row.cost_spread);
    }
    std::fs::remove_dir_all(dir).unwrap();
}
