//! `slender span`: the Bode plot, and the span study, whose scenes run through
//! `slender study` itself with the same errors.

use std::path::Path;

use crate::common;
use common::{slender, text};

#[test]
fn span_bode_and_study_write_their_figures() {
    let dir = std::env::temp_dir().join(format!("slender-cli-span-{}", std::process::id()));
    let d = dir.to_str().unwrap();
    let out = slender(&["span", "bode", "--out", d]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(dir.join("bode.svg").exists());
    let out = slender(&[
        "span",
        "study",
        "--duration",
        "10",
        "--reference-elements",
        "32",
        "--out",
        d,
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let table = text(&out.stdout);
    assert!(
        table.contains("| function_pade | 8 |") && table.contains("| fe | 64 |"),
        "{table}"
    );
    assert!(dir.join("accuracy_cost.svg").exists() && dir.join("span_study.json").exists());
    span_study_rows_come_from_slender_study(&dir);
    let out = slender(&["span", "bode", "--flexural-rigidity=-1", "--out", d]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("flexural_rigidity"));
    std::fs::remove_dir_all(dir).unwrap();
}

/// The span study's scenes through `slender study` itself: a function Pade span of
/// order 8 against the reference scene, the cost of the span unit alone, gives the
/// span study's error exactly; a sweep of one value without a reference scene and
/// a cost unit the scene lacks are refused.
fn span_study_rows_come_from_slender_study(dir: &Path) {
    let scenes = dir.join("scenes");
    let (scene, reference) = (
        scenes.join("span_sines.toml"),
        scenes.join("reference_sines.toml"),
    );
    let engine = dir.join("engine");
    let args = |extra: &[&str]| -> Vec<String> {
        let mut a: Vec<String> = ["study", scene.to_str().unwrap(), "--grid", "--jobs", "1"]
            .iter()
            .map(|s| s.to_string())
            .collect();
        a.extend(extra.iter().map(|s| s.to_string()));
        a.extend(["--out".to_string(), engine.to_str().unwrap().to_string()]);
        a
    };
    let run = |extra: &[&str]| {
        let a = args(extra);
        slender(&a.iter().map(String::as_str).collect::<Vec<_>>())
    };
    let vary = [
        "--vary",
        "units.span.parameters.approximation=function_pade",
        "--vary",
        "units.span.parameters.order=8",
    ];
    let with_reference = [
        &vary[..],
        &["--reference", reference.to_str().unwrap(), "--cost", "span"],
    ]
    .concat();
    let out = run(&with_reference);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let csv = std::fs::read_to_string(engine.join("study.csv")).unwrap();
    let row = csv.lines().nth(1).unwrap();
    let engine_error: f64 = row.split(',').nth(2).unwrap().parse().unwrap();
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("span_study.json")).unwrap())
            .unwrap();
    let study_error = json["rows"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["model"] == "function_pade" && r["size"] == 8)
        .unwrap()["error_sines"]
        .as_f64()
        .unwrap();
    assert_eq!(engine_error, study_error, "{csv}");
    let out = run(&vary);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        text(&out.stderr).contains("at least two values"),
        "{}",
        text(&out.stderr)
    );
    let unknown = [
        &vary[..],
        &["--reference", reference.to_str().unwrap(), "--cost", "spam"],
    ]
    .concat();
    let out = run(&unknown);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        text(&out.stderr).contains("cost unit `spam`"),
        "{}",
        text(&out.stderr)
    );
}
