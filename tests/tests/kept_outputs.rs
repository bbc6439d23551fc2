//! Every example's results and every structure's expansion against readable
//! kept files in `tests/reference/examples/`: a change that moves code must
//! leave them as they are, and one that means to change a result shows what
//! changed, value by value, in the diff this test prints and in the kept
//! file's own diff once regenerated (`./scripts/kept-outputs.sh`).
//!
//! Kept per example: `NAME.outputs.txt`, the run's recorded signals (each
//! column's first, last, smallest, largest value and mean, printed to the
//! last bit) and its `summary.json` without what the wall clock measured;
//! per `[structure]` example also `NAME.expanded.toml` (what `slender expand`
//! prints) and `NAME.fidelities.txt` (every fidelity on every section through
//! `--set`: the expansion's difference from the example's, or the refusal).

use slender_app::run::{RunOptions, run_scene};
use slender_app::study::scene_with_overrides;
use slender_scene::Scene;
use slender_scene::structure::FIDELITIES;
use slender_tests::root;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Where the kept files are, relative to the workspace root.
const KEPT: &str = "tests/reference/examples";

/// Set to write the kept files anew instead of comparing with them.
const KEEP: &str = "SLENDER_KEEP";

/// The example scenes, by name.
fn examples() -> Vec<PathBuf> {
    let mut scenes: Vec<PathBuf> = std::fs::read_dir(root().join("examples"))
        .expect("examples/")
        .map(|e| e.expect("an entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    scenes.sort();
    assert!(scenes.len() >= 30, "{} examples", scenes.len());
    scenes
}

fn name_of(scene: &Path) -> String {
    scene
        .file_stem()
        .expect("a file name")
        .to_string_lossy()
        .into()
}

fn has_structure(scene: &Path) -> bool {
    let text = std::fs::read_to_string(scene).expect("the example");
    let table: toml::Table = toml::from_str(&text).expect("TOML");
    table.contains_key("structure")
}

/// Compares `now` with the kept file `file` (or writes it under `SLENDER_KEEP`);
/// the difference as a unified diff where they differ.
fn compare(file: &str, now: &str) -> Option<String> {
    let path = root().join(KEPT).join(file);
    if std::env::var_os(KEEP).is_some() {
        std::fs::create_dir_all(path.parent().expect("a folder")).expect("the kept folder");
        std::fs::write(&path, now).expect("the kept file");
        return None;
    }
    let kept = std::fs::read_to_string(&path).unwrap_or_default();
    (kept != now).then(|| {
        similar::TextDiff::from_lines(&kept, now)
            .unified_diff()
            .context_radius(1)
            .header(&format!("{KEPT}/{file} (kept)"), "now")
            .to_string()
    })
}

/// The examples with a `[structure]`.
fn structures() -> Vec<PathBuf> {
    examples()
        .into_iter()
        .filter(|s| has_structure(s))
        .collect()
}

/// For each of `scenes`, the difference of its kept file `NAME.SUFFIX` from
/// what `now` makes of it (or the file written, under `SLENDER_KEEP`).
fn differences(scenes: &[PathBuf], suffix: &str, now: impl Fn(&Path) -> String) -> Vec<String> {
    scenes
        .iter()
        .filter_map(|scene| compare(&format!("{}.{suffix}", name_of(scene)), &now(scene)))
        .collect()
}

/// Fails with every difference found, and how to keep a meant change.
fn report(differences: Vec<String>) {
    assert!(
        differences.is_empty(),
        "{}\n{} kept file(s) differ; if the change means it, regenerate them with ./scripts/kept-outputs.sh and say why in the commit",
        differences.join("\n"),
        differences.len()
    );
}

/// Each column's first, last, smallest and largest value and mean (`{:?}`:
/// the shortest text that reads back to the same bits).
fn columns_of(csv: &str) -> String {
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap_or_default().split(',').collect();
    let rows: Vec<Vec<f64>> = lines
        .map(|l| {
            l.split(',')
                .map(|v| v.parse().unwrap_or(f64::NAN))
                .collect()
        })
        .collect();
    let mut out = format!("## timeseries.csv: {} rows\n", rows.len());
    for (c, name) in header.iter().enumerate() {
        let column: Vec<f64> = rows.iter().map(|r| r[c]).collect();
        let (first, last) = (column[0], column[column.len() - 1]);
        let min = column.iter().copied().fold(f64::INFINITY, f64::min);
        let max = column.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let mean = column.iter().sum::<f64>() / column.len() as f64;
        writeln!(
            out,
            "{name}: first {first:?}, last {last:?}, min {min:?}, max {max:?}, mean {mean:?}"
        )
        .expect("a string");
    }
    out
}

/// `summary.json` without what the wall clock measured and the scene's path.
fn summary_of(json: &str) -> String {
    let mut summary: serde_json::Value = serde_json::from_str(json).expect("summary.json");
    let object = summary.as_object_mut().expect("an object");
    for key in ["wall_time_s", "cost_per_simulated_second", "scene"] {
        object.remove(key);
    }
    if let Some(units) = summary["counters"]["units"].as_array_mut() {
        for unit in units {
            unit.as_object_mut().expect("a unit").remove("step_time_s");
        }
    }
    let text = serde_json::to_string_pretty(&summary).expect("JSON");
    format!("## summary.json (wall-clock fields left out)\n{text}\n")
}

/// What is kept of an example's run.
fn outputs_of(scene: &Path) -> String {
    let folder = tempfile::tempdir().expect("a temporary folder");
    let loaded = Scene::load(scene).unwrap_or_else(|e| panic!("{e}"));
    let options = RunOptions {
        output_dir: Some(folder.path().to_owned()),
        progress: false,
        realtime: false,
    };
    // A failed run is kept too: its summary says why (an example may show one).
    let _ = run_scene(&loaded, &options);
    let read = |file: &str| std::fs::read_to_string(folder.path().join(file)).expect(file);
    format!(
        "# examples/{}.toml run by tests/tests/kept_outputs.rs\n{}{}",
        name_of(scene),
        columns_of(&read("timeseries.csv")),
        summary_of(&read("summary.json"))
    )
}

#[test]
fn every_example_runs_as_kept() {
    report(differences(&examples(), "outputs.txt", outputs_of));
}

#[test]
fn every_structure_expands_as_kept() {
    let expansion = |scene: &Path| {
        let loaded = Scene::load(scene).unwrap_or_else(|e| panic!("{e}"));
        loaded.source().expect("the expanded scene").to_owned()
    };
    report(differences(&structures(), "expanded.toml", expansion));
}

/// Every fidelity on every section of `scene`, as `--set` writes it: the
/// expansion's difference from the scene's own, or the refusal.
fn fidelities_of(scene: &Path) -> String {
    let text = std::fs::read_to_string(scene).expect("the example");
    let table: toml::Table = toml::from_str(&text).expect("TOML");
    let sections = table["structure"]
        .get("sections")
        .and_then(toml::Value::as_array)
        .map_or(0, Vec::len);
    let own = Scene::load(scene).unwrap_or_else(|e| panic!("{e}"));
    let mut out = format!(
        "# examples/{}.toml with every fidelity on every section (tests/tests/kept_outputs.rs)\n",
        name_of(scene)
    );
    for k in 0..sections {
        for fidelity in FIDELITIES {
            let set = format!("structure.sections[{k}].fidelity=\"{fidelity}\"");
            writeln!(out, "\n## --set '{set}'").expect("a string");
            match scene_with_overrides(scene, std::slice::from_ref(&set)) {
                Err(e) => writeln!(out, "refused: {e}").expect("a string"),
                Ok(edited) => {
                    let diff = similar::TextDiff::from_lines(
                        own.source().expect("the expanded scene"),
                        edited.source().expect("the expanded scene"),
                    );
                    let diff = diff.unified_diff().context_radius(0).to_string();
                    out.push_str(if diff.is_empty() {
                        "same expansion\n"
                    } else {
                        &diff
                    });
                }
            }
        }
    }
    out.replace(&root().display().to_string(), "<root>")
}

#[test]
fn every_fidelity_on_every_section_expands_as_kept() {
    report(differences(&structures(), "fidelities.txt", fidelities_of));
}
