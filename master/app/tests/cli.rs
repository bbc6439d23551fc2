//! The `slender` command line: help, check, run, bench, study, and bad input.

use std::path::{Path, PathBuf};

use crate::common;
use common::{slender, text};

#[test]
fn help_lists_every_command() {
    let out = slender(&["--help"]);
    assert!(out.status.success());
    let help = text(&out.stdout);
    for cmd in ["run", "check", "bench", "kinds"] {
        assert!(help.contains(cmd), "{help}");
    }
}

#[test]
fn check_accepts_an_example_and_rejects_a_bad_scene_with_exit_code_2() {
    let out = slender(&["check", "examples/b1_two_masses.toml"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(text(&out.stdout).contains("ok"));
    let bad = std::env::temp_dir().join(format!("slender-cli-bad-{}.toml", std::process::id()));
    std::fs::write(
        &bad,
        "[simulation]\nduration = 1.0\nstep = 0.0\n[master]\nscheme = \"jacobi\"\n",
    )
    .unwrap();
    let out = slender(&["check", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let err = text(&out.stderr);
    assert!(
        err.contains("simulation.step") && err.contains("> 0"),
        "{err}"
    );
    std::fs::remove_file(bad).unwrap();
    let out = slender(&["run", "no/such/scene.toml"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("cannot read the file"));
}

#[test]
fn run_writes_results_and_prints_a_summary() {
    let dir: PathBuf = std::env::temp_dir().join(format!("slender-cli-run-{}", std::process::id()));
    let out = slender(&[
        "run",
        "examples/b1_two_masses.toml",
        "--quiet",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let summary = text(&out.stdout);
    assert!(
        summary.contains("iterations") && summary.contains("per simulated second"),
        "{summary}"
    );
    for f in ["timeseries.csv", "summary.json", "displacements.svg"] {
        assert!(dir.join(f).exists(), "{f} missing");
    }
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn bench_reports_cost_and_master_overhead() {
    let out = slender(&[
        "bench",
        "examples/b1_two_masses.toml",
        "--repeats",
        "1",
        "--json",
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let json = text(&out.stdout);
    assert!(json.contains("median_cost_per_simulated_second"), "{json}");
    assert!(
        json.contains("master_overhead_per_connection_iteration_s"),
        "{json}"
    );
}

#[test]
fn modes_prints_periods_and_refuses_units_without_modes() {
    let dir = std::env::temp_dir().join(format!("slender-cli-modes-{}", std::process::id()));
    let out = slender(&[
        "modes",
        "examples/truncation_emulated.toml",
        "--unit",
        "emulated",
        "--count",
        "3",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    // Table 3, last column: 50.17 s.
    let first: f64 = stdout
        .lines()
        .find(|l| l.trim_start().starts_with("1 "))
        .unwrap()
        .split_whitespace()
        .nth(1)
        .unwrap()
        .parse()
        .unwrap();
    assert!((first - 50.17).abs() < 0.01 * 50.17, "{stdout}");
    assert!(dir.join("modes.svg").exists() && dir.join("modes.csv").exists());
    let out = slender(&[
        "modes",
        "examples/truncation_emulated.toml",
        "--unit",
        "load",
    ]);
    assert!(!out.status.success());
    assert!(text(&out.stderr).contains("modal analysis of a `characteristic_load` unit"));
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn study_sweeps_a_setting_and_writes_a_table() {
    let dir = std::env::temp_dir().join(format!("slender-cli-study-{}", std::process::id()));
    let out = slender(&[
        "study",
        "examples/truncation_study.toml",
        "--duration",
        "5",
        "--vary",
        "elements=10,20,40",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let csv = std::fs::read_to_string(dir.join("study.csv")).unwrap();
    let eps1: Vec<f64> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(2).unwrap().parse().unwrap())
        .collect();
    // Rows sorted by value: 10, 20, 40 (the reference, zero).
    assert_eq!(eps1.len(), 3);
    assert!(
        eps1[0] > eps1[1] && eps1[1] > eps1[2] && eps1[2] == 0.0,
        "{csv}"
    );
    assert!(dir.join("study.svg").exists() && dir.join("study.md").exists());
    let out = slender(&[
        "study",
        "examples/truncation_study.toml",
        "--vary",
        "elemnts=10,20",
    ]);
    assert!(!out.status.success());
    assert!(
        text(&out.stderr).contains("did you mean `elements`"),
        "{}",
        text(&out.stderr)
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn fidelity_runs_a_structures_sections_and_names_the_cheapest() {
    let dir = std::env::temp_dir().join(format!("slender-cli-fidelity-{}", std::process::id()));
    let d = dir.to_str().unwrap();
    let out = slender(&[
        "fidelity",
        "examples/structure_mooring.toml",
        "--duration",
        "5",
        "--section",
        "lower=cable,nonlinear:16",
        "--tolerance",
        "0.001",
        "--quantities",
        "top_force,start_force",
        "--jobs",
        "2",
        "--out",
        d,
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(
        text(&out.stdout).contains("Cheapest within epsilon <= 0.001 on top_force, start_force"),
        "{}",
        text(&out.stdout)
    );
    for file in [
        "fidelity.csv",
        "fidelity.json",
        "fidelity.md",
        "fidelity.svg",
    ] {
        assert!(dir.join(file).exists(), "{file}");
    }
    let csv = std::fs::read_to_string(dir.join("fidelity.csv")).unwrap();
    // The reference and two combinations.
    assert_eq!(csv.lines().count(), 4, "{csv}");
    let out = slender(&[
        "fidelity",
        "examples/structure_mooring.toml",
        "--section",
        "middle=cable",
        "--out",
        d,
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("its sections are lower, upper"));
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn uq_shards_merged_give_the_local_files_byte_for_byte() {
    let dir = std::env::temp_dir().join(format!("slender-cli-uq-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let written = std::fs::read_to_string(root.join("examples/truncation_uq.toml"))
        .unwrap()
        .replace("samples = 208", "samples = 12");
    let scene = dir.join("uq.toml");
    std::fs::write(&scene, written).unwrap();
    let s = scene.to_str().unwrap();
    let (local, sharded) = (dir.join("local"), dir.join("sharded"));
    let run = |args: &[&str]| {
        let out = slender(args);
        assert!(out.status.success(), "{args:?}: {}", text(&out.stderr));
    };
    let common = ["--duration", "2", "--jobs", "2"];
    run(&[
        &["uq", s, "--out", local.to_str().unwrap()][..],
        &common[..],
    ]
    .concat());
    for k in ["1/3", "2/3", "3/3"] {
        run(&[
            &["uq", s, "--out", sharded.to_str().unwrap(), "--shard", k][..],
            &common[..],
        ]
        .concat());
    }
    run(&[
        &["uq", s, "--out", sharded.to_str().unwrap(), "--merge"][..],
        &common[..],
    ]
    .concat());
    assert_uq_files(&local);
    for file in ["runs.csv", "uq.json", "uq.md"] {
        let a = std::fs::read(local.join(file)).unwrap();
        let b = std::fs::read(sharded.join(file)).unwrap();
        assert!(
            a == b,
            "{file} differs between the local run and the merged shards"
        );
    }
    // The Slurm scripts: a job array of the shards, the merge after it.
    run(&[
        "uq",
        s,
        "--out",
        sharded.to_str().unwrap(),
        "--slurm",
        "4",
        "--duration",
        "2",
    ]);
    let array = std::fs::read_to_string(sharded.join("uq-shards.sbatch")).unwrap();
    assert!(
        array.contains("#SBATCH --array=1-4")
            && array.contains("--shard \"$SLURM_ARRAY_TASK_ID/4\"")
    );
    let submit = std::fs::read_to_string(sharded.join("submit.sh")).unwrap();
    assert!(submit.contains("--dependency=afterok") && submit.contains("--merge"));
    let out = slender(&["uq", s, "--shard", "5/4"]);
    assert_eq!(out.status.code(), Some(2));
    std::fs::remove_dir_all(dir).unwrap();
}

/// A whole UQ study's files in `out`: its figures, its Markdown summary, and
/// its report page showing that Markdown as HTML (it showed "## phi1" and
/// "**Caution:**" raw).
fn assert_uq_files(out: &Path) {
    for figure in [
        "sobol.svg",
        "convergence.svg",
        "distribution.svg",
        "scatter.svg",
    ] {
        assert!(out.join(figure).exists(), "{figure}");
    }
    let summary = std::fs::read_to_string(out.join("uq.md")).unwrap();
    assert!(
        summary.contains("maximin Latin hypercube") && summary.contains("90 % of outcomes in"),
        "{summary}"
    );
    let page = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(
        page.contains("<h2>phi1</h2>"),
        "no heading in the UQ report"
    );
    assert!(
        !page.contains("## phi") && !page.contains("**"),
        "raw Markdown in the UQ report"
    );
}

// `slender study` as the one study engine (issue 13): any scene key by its path,
// one at a time or as a grid, in parallel with results independent of the job
// count, the observed order of convergence for steps and element counts.

fn study(args: &[&str], name: &str) -> Vec<Vec<String>> {
    let dir = std::env::temp_dir().join(format!("slender-study-{name}-{}", std::process::id()));
    let mut all = vec![
        "study",
        "examples/truncation_study.toml",
        "--duration",
        "4",
        "--out",
    ];
    let d = dir.to_str().unwrap().to_owned();
    all.push(&d);
    all.extend_from_slice(args);
    let out = slender(&all);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(dir.join("study.csv")).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    csv.lines()
        .map(|l| l.split(',').map(str::to_owned).collect())
        .collect()
}

/// Every column but the wall-clock cost.
fn computed(rows: &[Vec<String>]) -> Vec<Vec<String>> {
    let cost = rows[0]
        .iter()
        .position(|c| c == "cost_per_simulated_second")
        .unwrap();
    rows.iter()
        .map(|r| {
            r.iter()
                .enumerate()
                .filter(|(i, _)| *i != cost)
                .map(|(_, c)| c.clone())
                .collect()
        })
        .collect()
}

#[test]
fn any_key_varies_and_two_jobs_give_the_same_rows_as_one() {
    let args = [
        "--vary",
        "master.scheme=iterative_gauss_seidel,iterative_jacobi",
        "--vary",
        "units.n.parameters.elements=10,20,40",
    ];
    let one = study(&[&args[..], &["--jobs", "1"]].concat(), "one");
    let two = study(&[&args[..], &["--jobs", "2"]].concat(), "two");
    assert_eq!(computed(&one), computed(&two));
    // Header and 2 + 3 rows; the scheme's reference is the first value given.
    assert_eq!(one.len(), 6, "{one:?}");
    let row = |setting: &str, value: &str| {
        one.iter()
            .find(|r| r[0] == setting && r[1] == value)
            .unwrap()
            .clone()
    };
    assert_eq!(row("master.scheme", "iterative_gauss_seidel")[2], "0e0");
    let jacobi: f64 = row("master.scheme", "iterative_jacobi")[2].parse().unwrap();
    assert!(
        jacobi > 0.0 && jacobi < 1e-3,
        "Jacobi against Gauss-Seidel: {jacobi}"
    );
    // Element counts: the finest (40) is the reference; 10 -> 20 gives an order.
    let order: f64 = row("units.n.parameters.elements", "10")[4].parse().unwrap();
    assert!((1.5..3.0).contains(&order), "observed order {order}");
}

#[test]
fn a_grid_runs_every_combination_against_the_finest_corner() {
    let rows = study(
        &[
            "--grid",
            "--vary",
            "step=0.01,0.02",
            "--vary",
            "elements=10,20",
        ],
        "grid",
    );
    assert_eq!(rows.len(), 5, "{rows:?}");
    let reference: Vec<&Vec<String>> = rows.iter().filter(|r| r[2] == "0e0").collect();
    assert_eq!(reference.len(), 1, "{rows:?}");
    assert_eq!(reference[0][0], "step=0.01;elements=20");
}

#[test]
fn a_key_that_does_not_apply_is_refused_before_anything_runs() {
    for (key, says) in [
        ("units.nn.parameters.elements=10,20", "no entry named `nn`"),
        (
            "units.n.parameters.elemnts=10,20",
            "unknown field `elemnts`",
        ),
        ("mastr.scheme=a,b", "unknown setting"),
    ] {
        let out = slender(&["study", "examples/truncation_study.toml", "--vary", key]);
        assert_eq!(out.status.code(), Some(2), "{key}");
        assert!(
            String::from_utf8_lossy(&out.stderr).contains(says),
            "{key}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

/// `run --duration` looks at part of a scene (a whole number of its steps,
/// else bad input), and `fmu export` takes `--out` as the other commands do
/// (issue 28).
#[test]
fn run_takes_a_duration_and_fmu_export_takes_out() {
    let dir = std::env::temp_dir().join(format!("slender-cli-duration-{}", std::process::id()));
    let d = dir.to_str().unwrap();
    let out = slender(&[
        "run",
        "examples/b1_two_masses.toml",
        "--duration",
        "0.5",
        "--out",
        d,
        "--quiet",
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(
        text(&out.stdout).contains("simulated    0.5 s in 50 steps"),
        "{}",
        text(&out.stdout)
    );
    let bad = slender(&[
        "run",
        "examples/b1_two_masses.toml",
        "--duration",
        "0.505",
        "--out",
        d,
    ]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(
        text(&bad.stderr).contains("--duration 0.505: 0.505 s is not a whole number of steps"),
        "{}",
        text(&bad.stderr)
    );
    let help = text(&slender(&["fmu", "export", "--help"]).stdout);
    assert!(help.contains("--out"), "{help}");
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_count_or_a_key_given_wrong_is_refused_in_a_users_words() {
    // `--repeats -1` was "unexpected argument '-1'", `--jobs x` "invalid digit
    // found in string", `--set master=5` an "unknown study setting".
    let cases: [(&[&str], &str); 4] = [
        (
            &[
                "study",
                "examples/b1_two_masses.toml",
                "--vary",
                "step=0.01",
                "--repeats",
                "-1",
            ],
            "`-1`: expected a whole number >= 0",
        ),
        (
            &[
                "fidelity",
                "examples/structure_mooring.toml",
                "--section",
                "lower=cable",
                "--jobs",
                "x",
            ],
            "`x`: expected a whole number >= 0",
        ),
        (
            &["bench", "examples/b1_two_masses.toml", "--repeats", "0"],
            "--repeats 0: expected 1 to 1000",
        ),
        (
            &["check", "examples/b1_two_masses.toml", "--set", "master=5"],
            "master.scheme, not master",
        ),
    ];
    for (args, expected) in cases {
        let output = slender(args);
        let stderr = text(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(expected), "{args:?}: {stderr}");
        assert!(
            !stderr.contains("digit") && !stderr.contains("unexpected argument"),
            "{stderr}"
        );
    }
}
