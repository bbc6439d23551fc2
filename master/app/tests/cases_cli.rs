//! `slender cases` (issue 50): a 2 x 2 x 2 load-case matrix of the OC3 spar
//! (two sea states, two headings, two seeds) run whole, then as two shards
//! merged: the same table, byte for byte; a bad sea state or a scene without
//! a sea is refused before any run.

use crate::common;

use common::{slender, text};
use std::path::{Path, PathBuf};

/// The matrix's arguments, shortened to 90 s runs (a 30 s window).
const MATRIX: [&str; 12] = [
    "--sea",
    "4,9,0.6",
    "--sea",
    "6,10,0.4",
    "--heading",
    "0",
    "--heading",
    "30",
    "--seeds",
    "2",
    "--duration",
    "90",
];

/// The OC3 example with its spar's force RAO given at 0 and 30 degrees (an
/// axisymmetric body: the heading's surge and sway are cos and sin of the
/// 0-degree surge, its pitch and roll cos and -sin of the 0-degree pitch).
fn oc3_with_headings(dir: &Path) -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let text = std::fs::read_to_string(root.join("examples/oc3_hywind_jonswap.toml")).unwrap();
    let mut scene: toml::Table = toml::from_str(&text).unwrap();
    let rao = scene["mooring"]["body"]["force_rao"]
        .as_table()
        .unwrap()
        .clone();
    let row = |key: &str, dof: usize| -> Vec<f64> {
        let values = rao[key][dof][0].as_array().unwrap();
        values
            .iter()
            .map(|v| v.as_float().or(v.as_integer().map(|i| i as f64)).unwrap())
            .collect()
    };
    let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    let scaled = |v: Vec<f64>, f: f64| v.into_iter().map(|x| x * f).collect::<Vec<f64>>();
    let shifted = |v: Vec<f64>| v.into_iter().map(|x| x + 180.0).collect::<Vec<f64>>();
    let amplitude: Vec<[Vec<f64>; 2]> = vec![
        [row("amplitude", 0), scaled(row("amplitude", 0), c)],
        [row("amplitude", 1), scaled(row("amplitude", 0), s)],
        [row("amplitude", 2), row("amplitude", 2)],
        [row("amplitude", 3), scaled(row("amplitude", 4), s)],
        [row("amplitude", 4), scaled(row("amplitude", 4), c)],
        [row("amplitude", 5), row("amplitude", 5)],
    ];
    let phase: Vec<[Vec<f64>; 2]> = vec![
        [row("phase_deg", 0), row("phase_deg", 0)],
        [row("phase_deg", 1), row("phase_deg", 0)],
        [row("phase_deg", 2), row("phase_deg", 2)],
        [row("phase_deg", 3), shifted(row("phase_deg", 4))],
        [row("phase_deg", 4), row("phase_deg", 4)],
        [row("phase_deg", 5), row("phase_deg", 5)],
    ];
    let body = scene["mooring"]["body"].as_table_mut().unwrap();
    let rao = body["force_rao"].as_table_mut().unwrap();
    rao.insert(
        "headings_deg".into(),
        toml::Value::try_from(vec![0.0, 30.0]).unwrap(),
    );
    rao.insert(
        "amplitude".into(),
        toml::Value::try_from(amplitude).unwrap(),
    );
    rao.insert("phase_deg".into(), toml::Value::try_from(phase).unwrap());
    let path = dir.join("oc3_headings.toml");
    std::fs::write(&path, toml::to_string(&scene).unwrap()).unwrap();
    path
}

fn cases(scene: &Path, out: &Path, extra: &[&str]) -> std::process::Output {
    let mut args = vec!["cases", scene.to_str().unwrap()];
    args.extend(MATRIX);
    args.extend(["--jobs", "2", "--out", out.to_str().unwrap()]);
    args.extend(extra);
    slender(&args)
}

#[test]
fn a_matrix_run_whole_and_in_merged_shards_gives_the_same_table() {
    let dir = tempfile::tempdir().unwrap();
    let (whole, split) = (dir.path().join("whole"), dir.path().join("split"));
    let scene = oc3_with_headings(dir.path());
    let out = cases(&scene, &whole, &[]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let printed = text(&out.stdout);
    assert!(
        printed.contains("8 cases in 4 sea states and headings"),
        "{printed}"
    );
    assert!(printed.contains("## Fatigue: line1_fairlead"), "{printed}");
    for k in ["1/2", "2/2"] {
        let out = cases(&scene, &split, &["--shard", k]);
        assert!(out.status.success(), "{}", text(&out.stderr));
    }
    let out = cases(&scene, &split, &["--merge"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(text(&out.stdout).contains("merging: 8 cases from the shards"));
    for file in ["cases.csv", "cases.json", "cases.md", "cases.svg"] {
        let a = std::fs::read(whole.join(file)).unwrap();
        let b = std::fs::read(split.join(file)).unwrap();
        assert!(
            a == b,
            "{file}: the merged shards differ from the whole run"
        );
    }
    // The table: 8 completed cases, each sea state's heading set in the run.
    let csv = std::fs::read_to_string(whole.join("cases.csv")).unwrap();
    assert_eq!(csv.lines().count(), 9, "{csv}");
    assert!(
        csv.lines().skip(1).all(|l| l.contains(",completed,")),
        "{csv}"
    );
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(whole.join("cases.json")).unwrap()).unwrap();
    let groups = report["groups"].as_array().unwrap();
    assert_eq!(groups.len(), 4);
    assert_eq!(groups[1]["heading_deg"], 30.0);
    // Heading 30 deg loads line 1 less than heading 0: the line lies along
    // +x, the waves along it at 0 degrees.
    let tension = |g: usize| {
        let e = groups[g]["extremes"].as_array().unwrap();
        let t = e
            .iter()
            .find(|e| e["signal"] == "line1_upper.end_tension")
            .unwrap();
        t["value"].as_f64().unwrap()
    };
    assert!(tension(0) > tension(1), "{} {}", tension(0), tension(1));
    // The damage over the scatter is the groups' damages weighed by probability.
    let f = &report["fatigue"][0];
    let sum: f64 = f["contributions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_f64().unwrap())
        .sum();
    assert!((f["damage_per_year"].as_f64().unwrap() - sum).abs() <= 1e-15 * sum);
    assert!(whole.join("report.html").exists());
    // The figure: a panel per design value and per fatigue entry over the
    // two sea states (Tp 9 and 10 s), the design value's cell outlined.
    let svg = std::fs::read_to_string(whole.join("cases.svg")).unwrap();
    let designs = report["design"].as_array().unwrap().len();
    assert_eq!(
        svg.matches("extreme per sea state (design value outlined)")
            .count(),
        designs
    );
    assert!(svg.contains("line1_fairlead: share of the damage per year (%)"));
    assert!(svg.contains("peak period Tp (s)"));
}

/// Runs `slender cases ARGS --out DIR` and checks it is refused (exit 2)
/// saying `says`.
fn refused(args: &str, out: &Path, says: &str) {
    let mut words: Vec<&str> = args.split(' ').collect();
    words.extend(["--out", out.to_str().unwrap()]);
    let run = slender(&words);
    let stderr = text(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{args}: {stderr}");
    assert!(stderr.contains(says), "{args}: {stderr}");
}

#[test]
fn a_matrix_that_cannot_run_is_refused_before_any_run() {
    let dir = tempfile::tempdir().unwrap();
    let o = &dir.path().join("bad");
    let oc3 = "cases examples/oc3_hywind_jonswap.toml";
    refused(&format!("{oc3} --sea 4,9"), o, "expected HS,TP,PROBABILITY");
    refused(
        &format!("{oc3} --sea 4,-9,0.5"),
        o,
        "expected a positive height (m), period (s) and probability",
    );
    refused(
        "cases examples/b1_two_masses.toml --sea 4,9,1",
        o,
        "no wave `spectrum` table",
    );
    refused(
        "cases examples/structure_mooring.toml --sea 4,9,1",
        o,
        "no wave `spectrum` table",
    );
    refused(
        &format!("{oc3} --sea 4,9,1 --duration 60"),
        o,
        "the statistics start at 60 s (`[output] statistics.from`), at or after the runs' end at 60 s",
    );
    refused(
        &format!("{oc3} --sea 4,9,1 --seeds 3 --max-runs 2"),
        o,
        "the matrix: 3 runs, more than the bound of 2",
    );
    refused(
        "cases examples/sea_state.toml --sea 4,9,1 --heading 30",
        o,
        "unknown field `heading_deg`",
    );
    // The body's force RAO covers heading 0 only: refused before any run.
    refused(
        &format!("{oc3} --sea 4,9,1 --heading 0 --heading 30"),
        o,
        "headings that cover the waves' heading_deg = 30",
    );
    refused(
        &format!("{oc3} --sea 4,9,1 --heading 0,0.5 --heading 30"),
        o,
        "give every heading's probability",
    );
    let without = common::variant_in(
        dir.path(),
        "examples/oc3_hywind_jonswap.toml",
        &[(
            "statistics = { from = 60.0, extremes = { duration = 10800.0 }, spectra = { segment = 60.0 } }",
            "",
        )],
    );
    let without = format!("cases {} --sea 4,9,1", without.display());
    refused(&without, o, "judges each case by its statistics");
}

/// The riser's own scatter (`[cases]` in examples/riser_sea.toml, five sea
/// states): run when the command line gives no `--sea`, replaced by one
/// that does; a scene with neither, or with headings half weighted, is
/// refused saying what to give.
#[test]
fn the_scenes_own_scatter_runs_without_sea_states_on_the_command_line() {
    let dir = tempfile::tempdir().unwrap();
    let riser = "examples/riser_sea.toml";
    let rows = |out: &Path| {
        let csv = std::fs::read_to_string(out.join("cases.csv")).unwrap();
        csv.lines().count() - 1
    };
    let own = dir.path().join("own");
    let short = ["--duration", "70", "--jobs", "1", "--out"];
    let run = slender(&[&["cases", riser], &short[..], &[own.to_str().unwrap()]].concat());
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert_eq!(rows(&own), 5);
    let md = std::fs::read_to_string(own.join("cases.md")).unwrap();
    assert!(md.contains("| Hs 6 m, Tp 12 s | 0.05 |"), "{md}");
    let given = dir.path().join("given");
    let args = [
        &["cases", riser, "--sea", "4,10,1"],
        &short[..],
        &[given.to_str().unwrap()],
    ];
    let run = slender(&args.concat());
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert_eq!(rows(&given), 1);
    let o = &dir.path().join("bad");
    refused(
        "cases examples/oc3_hywind_jonswap.toml",
        o,
        "no sea state: give at least one --sea HS,TP,PROBABILITY, or a `[cases]` table",
    );
    let mixed = common::variant_in(
        dir.path(),
        riser,
        &[("seeds = 1\n", "seeds = 1\nheadings = [0.0, [30.0, 0.5]]\n")],
    );
    refused(
        &format!("cases {}", mixed.display()),
        o,
        "`cases.headings`: give every heading as [DEG, PROBABILITY]",
    );
}

/// Waits (at most `limit`) until the merge has written `cases.json` and no
/// job of ours is queued.
fn wait_for_slurm(dir: &Path, limit: std::time::Duration) {
    let start = std::time::Instant::now();
    while start.elapsed() < limit {
        let queue = std::process::Command::new("squeue")
            .args(["-h", "-n", "slender-cases,slender-cases-merge"])
            .output()
            .expect("squeue runs");
        if queue.stdout.is_empty() && dir.join("cases.json").exists() {
            return;
        }
        std::thread::sleep(std::time::Duration::from_millis(500));
    }
    let log = std::fs::read_to_string(dir.join("merge.log")).unwrap_or_default();
    panic!("the Slurm jobs did not finish in {limit:?}; merge.log: {log}");
}

#[test]
#[ignore = "needs a running Slurm: ./scripts/test.sh starts one (scripts/slurm-up.sh)"]
fn a_matrix_through_a_slurm_job_array_gives_the_local_table() {
    let dir = tempfile::tempdir().unwrap();
    let (local, cluster) = (dir.path().join("local"), dir.path().join("cluster"));
    let scene = oc3_with_headings(dir.path());
    let out = cases(&scene, &local, &[]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let out = cases(&scene, &cluster, &["--slurm", "2"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let submit = std::process::Command::new("sh")
        .arg(cluster.join("submit.sh"))
        .output()
        .expect("sh runs");
    assert!(
        submit.status.success(),
        "submit.sh: {}",
        text(&submit.stderr)
    );
    wait_for_slurm(&cluster, std::time::Duration::from_secs(300));
    for file in ["cases.csv", "cases.json", "cases.md"] {
        let a = std::fs::read(local.join(file)).unwrap();
        let b = std::fs::read(cluster.join(file)).unwrap();
        assert!(a == b, "{file} from Slurm differs from the local run");
    }
    for k in 1..=2 {
        assert!(cluster.join(format!("shard-{k}-of-2/cases.csv")).exists());
    }
}
