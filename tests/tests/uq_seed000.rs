//! Seed 000 sec. 4 (issue 14): E and sd of phi1 and phi2 over Table 2's
//! artefacts from 416 LHS runs, and the Sobol' ranking, against the paper's PCE
//! (E phi1 = 1.32, sd 0.13; E phi2 = 1.77, sd 0.17; phi1 most sensitive to
//! theta9, then the calibrations theta1 and theta2). Tolerance: one published
//! standard deviation on the means, half of it on the sds, theta9 first.
//!
//! Known gap: with zeta2 read in synchronisation steps (`loss_duration_rate`, the
//! reading that comes closest: docs/active-truncation.md) 416 runs give, over
//! the 380 stable runs (the paper's runs were all stable, so its figures compare
//! with these), E phi1 = 1.15 (sd 0.28) and E phi2 = 1.65 (sd 0.21), against the
//! paper's 1.32 (0.13) and 1.77 (0.17): phi2 within the tolerance, phi1's mean
//! 0.17 low and its spread twice the paper's. theta9 ranks first for phi1,
//! theta2 and theta1 first for phi2, as in the paper. 36 of the 416 runs go
//! unstable (the delays theta7 and theta10 drive it); counted at phi = 0 they
//! give E phi1 = 1.08 and E phi2 = 1.54. Each run is one random realisation of
//! noise and losses, so the expansions' LOO error stays near 0.3.

use slender_app::uq::{UqPlan, run_uq};
use slender_tests::{published, root};

#[test]
#[ignore = "known gap: E phi1 = 1.15 (sd 0.28) over the stable runs against the paper's 1.32 (0.13), see the doc comment; 416 runs take 4.5 min"]
fn moments_and_ranking_match_the_paper() {
    let path = root().join("examples/truncation_uq.toml");
    let plan = UqPlan {
        overrides: Vec::new(),
        max_runs: slender_app::DEFAULT_MAX_RUNS,
        samples: Some(416),
        jobs: std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get),
        duration: None,
        shard: None,
    };
    let (report, _) = run_uq(&path, &plan, &[], |_, _, _| {}).unwrap();
    let report = report.unwrap();
    let paper = published();
    let f = &paper["fidelity_results"];
    let number = |k: &str| f[k].as_float().unwrap();
    // Every one of the paper's runs was stable (Fig. 8 draws them all): its
    // moments compare with the expansions over the stable runs; the counted
    // ones (unstable runs at phi = 0) are printed beside them.
    if let Some(s) = &report.stability {
        println!(
            "{} of {} runs unstable: probability {:.3} in [{:.3}, {:.3}]; first drivers {:?}",
            s.unstable_runs,
            s.unstable_runs + s.stable_runs,
            s.probability,
            s.interval.0,
            s.interval.1,
            (s.drivers.iter().take(3))
                .map(|d| (&d.input, d.distance))
                .collect::<Vec<_>>()
        );
    }
    let compared = if report.conditional.is_empty() {
        &report.outputs
    } else {
        &report.conditional
    };
    for (counted, stable) in report.outputs.iter().zip(compared) {
        println!(
            "{}: counted E {:.3} sd {:.3}; stable runs E {:.3} sd {:.3}",
            counted.name, counted.mean, counted.sd, stable.mean, stable.sd
        );
    }
    for (o, mean, sd) in [
        (
            &compared[0],
            number("pce_mean_phi1"),
            number("pce_std_phi1"),
        ),
        (
            &compared[1],
            number("pce_mean_phi2"),
            number("pce_std_phi2"),
        ),
    ] {
        println!(
            "{}: E {:.3} (paper {mean}), sd {:.3} (paper {sd})",
            o.name, o.mean, o.sd
        );
        assert!((o.mean - mean).abs() < sd, "{}: E {}", o.name, o.mean);
        assert!((o.sd - sd).abs() < 0.5 * sd, "{}: sd {}", o.name, o.sd);
    }
    let phi1 = &compared[0];
    let first = (0..phi1.total.len())
        .max_by(|&a, &b| phi1.total[a].total_cmp(&phi1.total[b]))
        .unwrap();
    assert_eq!(report.inputs[first], "theta9");
}
