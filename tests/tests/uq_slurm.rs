//! A UQ study on a real (single-node) Slurm cluster (issue 14): `slender uq
//! --slurm 2` writes a job array of two shards and a merge that depends on it;
//! submitted, they give the local run's files byte for byte.
//!
//! Needs a running Slurm (`scripts/slurm-up.sh`, which `./scripts/test.sh`
//! starts as root); ignored in a plain `cargo test`.

use slender_tests::{fmu, root};
use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

fn slender(args: &[&str]) {
    let cli = fmu::library().with_file_name("slender");
    let out = Command::new(&cli).args(args).output().expect("run slender");
    assert!(
        out.status.success(),
        "slender {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Waits (at most `limit`) until the merge has written `uq.json` and no job of
/// ours is queued.
fn wait_for(dir: &Path, limit: Duration) {
    let start = Instant::now();
    while start.elapsed() < limit {
        let queue = Command::new("squeue")
            .args(["-h", "-n", "slender-uq,slender-uq-merge"])
            .output()
            .expect("squeue runs");
        if queue.stdout.is_empty() && dir.join("uq.json").exists() {
            return;
        }
        std::thread::sleep(Duration::from_millis(500));
    }
    let log = std::fs::read_to_string(dir.join("merge.log")).unwrap_or_default();
    panic!("the Slurm jobs did not finish in {limit:?}; merge.log: {log}");
}

#[test]
#[ignore = "needs a running Slurm: ./scripts/test.sh starts one (scripts/slurm-up.sh)"]
fn a_study_through_a_slurm_job_array_gives_the_local_files() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(root().join("examples/truncation_uq.toml"))
        .unwrap()
        .replace("samples = 208", "samples = 8");
    let scene = dir.path().join("uq.toml");
    std::fs::write(&scene, text).unwrap();
    let (local, cluster) = (dir.path().join("local"), dir.path().join("cluster"));
    let s = scene.to_str().unwrap();
    slender(&[
        "uq",
        s,
        "--duration",
        "2",
        "--jobs",
        "1",
        "--out",
        local.to_str().unwrap(),
    ]);
    slender(&[
        "uq",
        s,
        "--duration",
        "2",
        "--jobs",
        "1",
        "--out",
        cluster.to_str().unwrap(),
        "--slurm",
        "2",
    ]);
    let submit = Command::new("sh")
        .arg(cluster.join("submit.sh"))
        .output()
        .expect("sh runs");
    assert!(
        submit.status.success(),
        "submit.sh: {}",
        String::from_utf8_lossy(&submit.stderr)
    );
    wait_for(&cluster, Duration::from_secs(300));
    for file in ["runs.csv", "uq.json", "uq.md"] {
        let a = std::fs::read(local.join(file)).unwrap();
        let b = std::fs::read(cluster.join(file)).unwrap();
        assert!(a == b, "{file} from Slurm differs from the local run");
    }
    for k in 1..=2 {
        assert!(cluster.join(format!("shard-{k}-of-2/runs.csv")).exists());
    }
}
