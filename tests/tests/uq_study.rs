//! `slender uq` (issue 14): seed 000's Table 2 artefacts as uncertain inputs of
//! the active-truncation scene. A study grows by doubling its Latin hypercube
//! and keeps the runs it already has (resume), its results do not depend on the
//! number of jobs or on running it in shards and merging them, and bad
//! `[uncertainty]` tables are refused with the key.

use slender_app::uq::{Run, UqPlan, run_uq};
use slender_tests::root;
use std::path::PathBuf;
use std::sync::Mutex;

/// The example with a first design of `samples` points, in a temporary folder.
fn scene(dir: &std::path::Path, samples: usize, change: Option<(&str, &str)>) -> PathBuf {
    let text = std::fs::read_to_string(root().join("examples/truncation_uq.toml")).unwrap();
    let mut text = text.replace("samples = 208", &format!("samples = {samples}"));
    if let Some((from, to)) = change {
        assert!(text.contains(from), "{from}");
        text = text.replacen(from, to, 1);
    }
    let path = dir.join("uq.toml");
    std::fs::write(&path, text).unwrap();
    path
}

fn plan(samples: Option<usize>, jobs: usize) -> UqPlan {
    UqPlan {
        overrides: Vec::new(),
        max_runs: slender_app::DEFAULT_MAX_RUNS,
        samples,
        jobs,
        duration: Some(5.0),
        shard: None,
    }
}

/// An expansion that misses more than a tenth of the variance is reported with
/// a caution, and only then.
fn cautions_follow_the_loo_error(report: &slender_app::uq::UqReport) {
    let markdown = slender_app::uq::report::to_markdown(report);
    let poor = report
        .outputs
        .iter()
        .filter(|o| o.loo_error > slender_app::uq::report::LOO_TRUSTED)
        .count();
    eprintln!(
        "LOO errors: {:?}",
        report
            .outputs
            .iter()
            .map(|o| o.loo_error)
            .collect::<Vec<_>>()
    );
    assert_eq!(markdown.matches("**Caution:**").count(), poor, "{markdown}");
    let mut good = report.outputs[0].clone();
    good.loo_error = 0.01;
    assert!(slender_app::uq::report::poor_fit(&good).is_none());
    good.loo_error = 0.5;
    let caution = slender_app::uq::report::poor_fit(&good).unwrap();
    assert!(
        caution.contains(&good.name) && caution.contains("0.50"),
        "{caution}"
    );
    // The design size to try next: twice this one's.
    let size = good.convergence.last().unwrap().0;
    assert!(
        caution.contains(&format!("--samples {}", 2 * size)),
        "{caution}"
    );
}

/// The runs' every value as bits (NaN compares equal to itself).
fn bits(runs: &[Run]) -> Vec<u64> {
    runs.iter()
        .flat_map(|r| {
            let onset = r.unstable_from.unwrap_or(f64::NAN);
            (r.inputs.iter().chain(&r.outputs).map(|v| v.to_bits())).chain([onset.to_bits()])
        })
        .collect()
}

#[test]
fn a_doubled_design_keeps_its_runs_and_jobs_do_not_change_the_results() {
    let dir = tempfile::tempdir().unwrap();
    let path = scene(dir.path(), 16, None);
    let fresh = Mutex::new(Vec::new());
    let (first, runs) = run_uq(&path, &plan(None, 2), &[], |k, _, _| {
        fresh.lock().unwrap().push(k)
    })
    .unwrap();
    assert_eq!(runs.len(), 16);
    assert_eq!(fresh.lock().unwrap().len(), 16);
    assert_eq!(first.unwrap().inputs.len(), 12);
    // Doubled: 16 more runs, the first 16 kept as they were.
    fresh.lock().unwrap().clear();
    let (second, more) = run_uq(&path, &plan(Some(32), 2), &runs, |k, _, _| {
        fresh.lock().unwrap().push(k)
    })
    .unwrap();
    let mut new: Vec<usize> = fresh.lock().unwrap().clone();
    new.sort();
    assert_eq!(new, (16..32).collect::<Vec<_>>());
    assert_eq!(&more[..16], &runs[..]);
    let second = second.unwrap();
    for o in &second.outputs {
        assert!(o.mean.is_finite() && o.sd >= 0.0, "{o:?}");
        // The moments on each nested design: 16 points, then all 32.
        let sizes: Vec<usize> = o.convergence.iter().map(|c| c.0).collect();
        assert_eq!(sizes, [16, 32]);
        assert_eq!(o.convergence[1].1, o.mean);
        assert!(o.total.iter().all(|t| (-1e-9..=1.0 + 1e-9).contains(t)));
    }
    cautions_follow_the_loo_error(&second);
    // One job: the same runs and the same expansions.
    let (again, runs1) = run_uq(&path, &plan(Some(32), 1), &[], |_, _, _| {}).unwrap();
    assert_eq!(bits(&runs1), bits(&more));
    assert_eq!(
        serde_json::to_string(&again.unwrap()).unwrap(),
        serde_json::to_string(&second).unwrap()
    );
    // Three shards, merged: the same runs and the same expansions.
    let mut merged: Vec<Run> = vec![Run::default(); 32];
    for k in 1..=3 {
        let shard = UqPlan {
            max_runs: slender_app::DEFAULT_MAX_RUNS,
            shard: Some((k, 3)),
            ..plan(Some(32), 1)
        };
        let (report, rows) = run_uq(&path, &shard, &[], |_, _, _| {}).unwrap();
        assert!(report.is_none());
        for (i, r) in rows
            .into_iter()
            .enumerate()
            .filter(|(_, r)| !r.inputs.is_empty())
        {
            assert_eq!(i % 3, k - 1);
            merged[i] = r;
        }
    }
    let ran = Mutex::new(0);
    let (report, all) = run_uq(&path, &plan(Some(32), 2), &merged, |_, _, _| {
        *ran.lock().unwrap() += 1
    })
    .unwrap();
    assert_eq!(
        *ran.lock().unwrap(),
        0,
        "the merge ran again what the shards ran"
    );
    assert_eq!(bits(&all), bits(&more));
    assert_eq!(
        serde_json::to_string(&report.unwrap()).unwrap(),
        serde_json::to_string(&second).unwrap()
    );
}

/// Issue 28: any `--samples`. Off the doubling ladder (24 from a first design
/// of 16) the design is a Latin hypercube of its own size, said so in the
/// report, with no nested sizes to show convergence over; runs of the 16-point
/// design are not taken for its points.
#[test]
fn a_design_off_the_doubling_ladder_is_a_latin_hypercube_of_its_own() {
    let dir = tempfile::tempdir().unwrap();
    let path = scene(dir.path(), 16, None);
    let (_, sixteen) = run_uq(&path, &plan(None, 2), &[], |_, _, _| {}).unwrap();
    let fresh = Mutex::new(0);
    let (report, runs) = run_uq(&path, &plan(Some(24), 2), &sixteen, |_, _, _| {
        *fresh.lock().unwrap() += 1
    })
    .unwrap();
    assert_eq!(runs.len(), 24);
    assert_eq!(
        *fresh.lock().unwrap(),
        24,
        "a run of another design was reused"
    );
    let report = report.unwrap();
    assert!(report.design.contains("of its own"), "{}", report.design);
    for o in &report.outputs {
        assert!(o.mean.is_finite() && o.sd >= 0.0, "{o:?}");
        assert_eq!(o.convergence.len(), 1);
        assert_eq!(o.convergence[0].0, 24);
    }
    // Its strata (one point each) are checked in the app's unit tests.
}

#[test]
fn failed_runs_are_left_out_and_reported_with_their_reason() {
    // A loss probability beyond 1 is refused by the artefact: those points
    // fail, the others expand.
    let dir = tempfile::tempdir().unwrap();
    let path = scene(
        dir.path(),
        16,
        Some((
            "\"units.sensor.parameters.loss_probability\", distribution = { kind = \"uniform\", low = 0.01, high = 0.10 }",
            "\"units.sensor.parameters.loss_probability\", distribution = { kind = \"uniform\", low = 0.3, high = 1.2 }",
        )),
    );
    let (report, runs) = run_uq(&path, &plan(None, 2), &[], |_, _, _| {}).unwrap();
    let report = report.unwrap();
    let failed: Vec<usize> = (0..runs.len())
        .filter(|&k| runs[k].outputs.iter().any(|v| v.is_nan()))
        .collect();
    assert!(
        !failed.is_empty() && failed.len() < runs.len(),
        "{failed:?}"
    );
    assert_eq!(report.failed_runs, failed.len());
    let listed: Vec<usize> = report.failures.iter().map(|f| f.index).collect();
    assert_eq!(listed, failed);
    for f in &report.failures {
        assert!(
            runs[f.index].inputs[7] >= 1.0,
            "run {}: {}",
            f.index,
            f.reason
        );
        assert_eq!(f.inputs, runs[f.index].inputs);
        assert!(f.reason.contains("loss_probability"), "{}", f.reason);
    }
    // Refused inputs are failures, not an unstable loop; uq.md names each
    // failed point's inputs.
    assert!(report.stability.is_none() && report.conditional.is_empty());
    let markdown = slender_app::uq::report::to_markdown(&report);
    let first = &report.failures[0];
    assert!(
        markdown.contains(&format!("run {} (theta1 = ", first.index)),
        "{markdown}"
    );
}

/// Issue 49 #2: with delays up to 80 ms on both sides the hybrid loop goes
/// unstable at some points (the physical part's velocity grows until the lower
/// cable stops). Those points are detected as unstable, not failures; the
/// probability of instability comes with its interval, the delays rank first
/// among the inputs that drive it, and the expansions count the unstable
/// points as failures of fidelity (phi = 0), beside the expansions over the
/// stable points alone.
#[test]
fn unstable_loops_are_counted_and_their_drivers_named() {
    let dir = tempfile::tempdir().unwrap();
    let delays = "distribution = { kind = \"uniform\", low = 0.0, high = 0.05 }";
    let text = std::fs::read_to_string(scene(dir.path(), 32, None)).unwrap();
    assert_eq!(text.matches(delays).count(), 2);
    let wide = "distribution = { kind = \"uniform\", low = 0.0, high = 0.08 }";
    let path = dir.path().join("unstable.toml");
    std::fs::write(&path, text.replace(delays, wide)).unwrap();
    let plan = UqPlan {
        duration: Some(30.0),
        ..plan(None, 2)
    };
    let (report, runs) = run_uq(&path, &plan, &[], |_, _, _| {}).unwrap();
    let report = report.unwrap();
    let unstable: Vec<&Run> = runs.iter().filter(|r| r.unstable()).collect();
    assert!(
        unstable.len() >= 3 && unstable.len() < 29,
        "{} unstable",
        unstable.len()
    );
    assert_eq!(report.failed_runs, 0, "{:?}", report.failures);
    let s = report.stability.as_ref().unwrap();
    assert_eq!(
        (s.unstable_runs, s.stable_runs),
        (unstable.len(), 32 - unstable.len())
    );
    assert!(s.interval.0 < s.probability && s.probability < s.interval.1);
    for r in &unstable {
        let t = r.unstable_from.unwrap();
        assert!(t > 0.0 && t < 30.0, "{t}");
    }
    // The round-trip delay decides: theta7 (sensor) and theta10 (actuator).
    let first = &s.drivers[0];
    assert!(
        ["theta7", "theta10"].contains(&first.input.as_str()),
        "{:?}",
        s.drivers
    );
    assert!(first.mean_unstable > first.mean_stable && first.p_value < 0.05);
    // Counted as failures of fidelity the mean falls below the stable runs'.
    assert_eq!(report.conditional.len(), report.outputs.len());
    for (counted, stable) in report.outputs.iter().zip(&report.conditional) {
        assert!(counted.mean < stable.mean, "{counted:?} {stable:?}");
    }
    let markdown = slender_app::uq::report::to_markdown(&report);
    for says in [
        "## Stability",
        "probability of instability",
        "conditional on stability",
    ] {
        assert!(markdown.contains(says), "{markdown}");
    }
    // A resumed study keeps the unstable runs as they were.
    let fresh = Mutex::new(0);
    let (_, again) = run_uq(&path, &plan, &runs, |_, _, _| *fresh.lock().unwrap() += 1).unwrap();
    assert_eq!(*fresh.lock().unwrap(), 0);
    assert_eq!(again.len(), runs.len());
}

#[test]
fn bad_uncertainty_tables_are_refused_with_the_key() {
    let dir = tempfile::tempdir().unwrap();
    for (change, says) in [
        (
            ("outputs = [\"phi1\", \"phi2\"]", "outputs = [\"phi3\"]"),
            "phi3",
        ),
        (("sd = 0.015 } },", "sd = -1.0 } },"), "theta1"),
        (
            ("samples = 16", "samples = 16\nunstable_growth = 0.5"),
            "unstable_growth",
        ),
        (
            ("samples = 16", "samples = 16\nunstable_fidelity = nan"),
            "unstable_fidelity",
        ),
        (
            (
                "units.sensor.parameters.scale.0",
                "units.nobody.parameters.scale.0",
            ),
            "theta1",
        ),
    ] {
        let path = scene(dir.path(), 16, Some(change));
        let e = run_uq(&path, &plan(None, 1), &[], |_, _, _| {});
        match e {
            Err(e) => assert!(e.to_string().contains(says), "{change:?}: {e}"),
            Ok(_) => panic!("{change:?} accepted"),
        }
    }
    let path = scene(dir.path(), 16, None);
    // Any design size (issue 28), but not one too small to fit.
    let e = run_uq(&path, &plan(Some(3), 1), &[], |_, _, _| {}).unwrap_err();
    assert!(
        e.to_string().contains("--samples 3: expected at least 4"),
        "{e}"
    );
}
