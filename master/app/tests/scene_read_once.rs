//! A `--set` run and a fidelity study read the user's scene file once and
//! write no TOML text to read again (issue 45): their changes are made on the
//! keys as read, so their errors name the user's line or the change.
//!
//! One test in its own binary: the count of texts parsed is the process's.

use slender_app::fidelity::{FidelityPlan, run_fidelity};
use slender_app::run::{RunOptions, run_scene};
use slender_app::study::Design;
use slender_app::study::scene_with_overrides;
use slender_scene::{texts_parsed, texts_written};
use std::path::{Path, PathBuf};

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name)
}

#[test]
fn a_set_run_and_a_fidelity_study_parse_the_file_once() {
    let scene = example("structure_hanging_pipe.toml");
    let (before, written) = (texts_parsed(), texts_written());
    let set = ["simulation.duration=0.5".to_owned()];
    let loaded = scene_with_overrides(&scene, &set).expect("the scene with --set");
    let options = RunOptions {
        output_dir: None,
        progress: false,
        realtime: false,
    };
    run_scene(&loaded, &options).expect("the run");
    assert_eq!(texts_parsed() - before, 1, "a --set run");
    assert_eq!(texts_written(), written, "a --set run writes no scene text");

    let before = texts_parsed();
    let plan = FidelityPlan {
        reference: slender_app::fidelity::ReferenceMode::Model,
        max_refinements: 3,
        from: None,
        overrides: Vec::new(),
        max_runs: 10,
        repeats: 1,
        sections: vec!["upper=cable,nonlinear:4".parse().expect("a choice")],
        design: Design::OneAtATime,
        duration: Some(0.5),
        jobs: 1,
        tolerance: 0.01,
        judged: Vec::new(),
    };
    let report = run_fidelity(&scene, &plan, |_| {}).expect("the study");
    // The reference and two combinations, each a scene of its own.
    assert_eq!(report.rows.len(), 3);
    assert_eq!(texts_parsed() - before, 1, "a fidelity study of three runs");
    assert_eq!(
        texts_written(),
        written,
        "a fidelity study writes no scene text"
    );
    // What counts: `slender expand` writes the expanded text once.
    loaded.source().expect("the expanded text");
    assert_eq!(texts_written(), written + 1);
}
