//! A study stopped by Ctrl-C fits nothing and says so (issue 49, item 1: a
//! UQ study interrupted after 4 runs fitted a chaos expansion on them and
//! wrote a complete-looking report, exit 0).
//!
//! One test in its own binary: the interruption is the process's.

use slender_app::AppError;
use slender_app::uq::{UqPlan, run_uq};
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

#[test]
fn an_interrupted_uq_study_fits_nothing_and_says_how_far_it_got() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/truncation_uq.toml");
    let plan = UqPlan {
        overrides: Vec::new(),
        max_runs: slender_app::DEFAULT_MAX_RUNS,
        samples: Some(8),
        jobs: 1,
        duration: Some(5.0),
        shard: None,
    };
    let finished = AtomicUsize::new(0);
    // Ctrl-C once two runs have finished: the third stops at its first step.
    let result = run_uq(&path, &plan, &[], |_, _, _| {
        if finished.fetch_add(1, Ordering::Relaxed) + 1 == 2 {
            slender_app::interrupt::request();
        }
    });
    match result {
        Err(e @ AppError::Interrupted { .. }) => {
            let AppError::Interrupted { finished, total } = e else {
                unreachable!()
            };
            assert_eq!((finished, total), (2, 8));
            assert!(!e.is_input());
            assert!(e.to_string().contains("after 2 of 8 runs"), "{e}");
        }
        Err(e) => panic!("expected an interruption, got {e}"),
        Ok(_) => panic!("an interrupted study fitted its expansion"),
    }
}
