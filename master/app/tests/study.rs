//! `slender study` as the one study engine (issue 13): any scene key by its path,
//! one at a time or as a grid, in parallel with results independent of the job
//! count, the observed order of convergence for steps and element counts.

use std::path::Path;
use std::process::{Command, Output};

fn slender(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_slender"))
        .args(args)
        .current_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("../.."))
        .output()
        .expect("the slender binary runs")
}

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
        ("mastr.scheme=a,b", "unknown study setting"),
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
