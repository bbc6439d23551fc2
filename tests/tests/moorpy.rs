//! Cross-check of a moored body's statics with MoorPy (issue 47): `slender
//! statics` on the OC3-Hywind example against MoorPy's quasi-static lines
//! (PyPI `moorpy`, no seabed friction) from a body held at slender's
//! equilibrium: the fairlead tensions, the 6x6 mooring stiffness and the
//! surge, sway and yaw offset curves.
//!
//! Needs MoorPy in the test environment (.venv, `./scripts/test.sh`);
//! ignored in a plain `cargo test`, run by test.sh with `--ignored`.

use slender_tests::{fmu, root};
use std::process::Command;
use toml::{Table, Value};

/// The system's facts as MoorPy takes them, read from the scene.
fn facts(scene: &Table) -> serde_json::Value {
    let mooring = &scene["mooring"];
    let body = &mooring["body"];
    let line = &mooring["line"];
    let number = |v: &Value| v.as_float().unwrap();
    let point = |v: &Value| -> Vec<f64> { v.as_array().unwrap().iter().map(number).collect() };
    let fairleads: Vec<(String, Vec<f64>)> = (body["fairleads"].as_array().unwrap().iter())
        .map(|f| {
            (
                f["name"].as_str().unwrap().to_owned(),
                point(&f["position"]),
            )
        })
        .collect();
    let lines = mooring["lines"].as_array().unwrap();
    let at = |name: &str| fairleads.iter().find(|f| f.0 == name).unwrap().1.clone();
    serde_json::json!({
        "depth": number(&line["seabed"]["depth"]),
        "rho": 1025.0,
        "g": 9.80665,
        "length": number(&line["length"]),
        "mass_per_length": number(&line["mass_per_length"]),
        "diameter": number(&line["diameter"]),
        "axial_stiffness": number(&line["axial_stiffness"]),
        "fairleads": lines.iter().map(|l| at(l["fairlead"].as_str().unwrap())).collect::<Vec<_>>(),
        "anchors": lines.iter().map(|l| point(&l["anchor"])).collect::<Vec<_>>(),
    })
}

#[test]
#[ignore = "needs MoorPy in .venv: ./scripts/test.sh runs it"]
fn moorpy_gives_the_oc3_mooring_s_tensions_stiffness_and_offset_curves() {
    let scene_path = root().join("examples/oc3_hywind.toml");
    let scene: Table = toml::from_str(&std::fs::read_to_string(&scene_path).unwrap()).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let status = Command::new(root().join("target/release/slender"))
        .current_dir(root())
        .args(["statics", "examples/oc3_hywind.toml", "--out"])
        .arg(dir.path())
        .output()
        .expect("run slender statics");
    assert!(
        status.status.success(),
        "{}",
        String::from_utf8_lossy(&status.stderr)
    );
    let facts_path = dir.path().join("facts.json");
    std::fs::write(&facts_path, facts(&scene).to_string()).unwrap();
    let out = Command::new(fmu::python())
        .arg(root().join("tests/python/moorpy_statics.py"))
        .arg(&facts_path)
        .arg(dir.path().join("statics.json"))
        .arg(dir.path().join("offsets.csv"))
        .output()
        .expect("run python");
    assert!(
        out.status.success(),
        "moorpy: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let theirs: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    println!("{theirs}");
    let error = |key: &str| theirs[key].as_f64().unwrap();
    // The bar: 1e-4. Both solve the same elastic catenary to their
    // solvers' tolerances; MoorPy's stiffness is analytic, slender's by
    // central differences of 1 mm and 1e-5 rad.
    assert!(error("tension_error") < 1e-4, "{theirs}");
    assert!(error("stiffness_error") < 1e-4, "{theirs}");
    assert!(error("curve_error") < 1e-4, "{theirs}");
}
