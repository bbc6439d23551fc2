//! A results file that cannot be written (a full disk) is named, and is a
//! failure on the way, not bad input (issue 49, item 19: a full disk exited 2
//! without naming the file).

#[test]
#[cfg(target_os = "linux")]
fn a_full_disk_names_the_file_it_could_not_write() {
    use slender_app::run::{RunError, RunOptions, run_scene};
    let dir = tempfile::tempdir().expect("a folder");
    // Every write to /dev/full fails with "No space left on device".
    let csv = dir.path().join("timeseries.csv.partial");
    std::os::unix::fs::symlink("/dev/full", &csv).expect("a link");
    let scene =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/b1_two_masses.toml");
    let scene = slender_scene::Scene::load(&scene).expect("the example");
    let options = RunOptions {
        output_dir: Some(dir.path().to_owned()),
        progress: false,
        realtime: false,
    };
    let error = match run_scene(&scene, &options) {
        Err(e) => e,
        Ok(r) => panic!("a run on a full disk finished: {:?}", r.summary.error),
    };
    assert!(matches!(error, RunError::File { .. }), "{error:?}");
    let message = error.to_string();
    assert!(message.contains("timeseries.csv.partial"), "{message}");
    assert!(message.contains("No space left on device"), "{message}");
}
