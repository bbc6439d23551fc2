//! Seed 000's active truncation written as a `[structure]` (issue 13, flagship
//! scene 2): the polyester line under the characteristic load (`top_load`), cut
//! at the node nearest the truncation height, a physical upper section whose cut
//! signals pass through the Table 2 sensor and actuator, a numerical lower
//! section, and the whole line as one cable for the reference. It reproduces the
//! hand-written scenes' fidelities: with the artefacts, truncation_table2.toml's
//! phi1 and phi2; without, truncation_substructured.toml's.

use slender_scene::Scene;
use slender_tests::{load, root, run};

/// phi1 and phi2 of a run.
fn phis(scene: &Scene) -> (f64, f64) {
    let s = run(scene);
    assert!(s.error.is_none(), "{:?}", s.error);
    let phi = |name: &str| {
        s.indicators
            .iter()
            .find(|i| i.name == name)
            .unwrap_or_else(|| panic!("no {name}"))
            .fidelity
    };
    (phi("phi1"), phi("phi2"))
}

fn structure_scene(artefacts: bool) -> Scene {
    let path = root().join("examples/structure_truncation.toml");
    let mut text = std::fs::read_to_string(&path).unwrap();
    if !artefacts {
        let (head, tail) = text
            .split_once("[structure.sections.physical.sensor]")
            .unwrap();
        let (_, output) = tail.split_once("[output]").unwrap();
        let (output, _) = output.split_once("[[output.plots]]").unwrap();
        text = format!("{head}\n[output]{output}")
            .replace(", \"line_upper_start_sensor.out_x\"", "")
            .replace(", \"line_upper_start_actuator.out_x\"", "");
    }
    Scene::parse(&path, text).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn the_structure_with_the_table2_artefacts_reproduces_the_hand_written_scene() {
    let (phi1, phi2) = phis(&structure_scene(true));
    let (want1, want2) = phis(&load("examples/truncation_table2.toml"));
    println!("structure: phi1 {phi1:.4}, phi2 {phi2:.4}; hand-written: {want1:.4}, {want2:.4}");
    // The same artefact realisations (seeds, steps) on the same line: only the
    // sections' static states differ, each solved from the structure's
    // equilibrium (EI = 100 N m^2 in it) instead of the whole cable's.
    assert!((phi1 - want1).abs() < 5e-3, "phi1 {phi1} against {want1}");
    assert!((phi2 - want2).abs() < 5e-3, "phi2 {phi2} against {want2}");
}

#[test]
fn the_structure_without_artefacts_reproduces_the_emulated_line() {
    let (phi1, phi2) = phis(&structure_scene(false));
    let (want1, want2) = phis(&load("examples/truncation_substructured.toml"));
    println!("structure: phi1 {phi1:.4}, phi2 {phi2:.4}; hand-written: {want1:.4}, {want2:.4}");
    // Both at the coupling tolerance of the emulated (whole-cable) reference.
    assert!(phi1 > 5.0 && phi2 > 6.0, "phi1 {phi1}, phi2 {phi2}");
    assert!((phi1 - want1).abs() < 0.05 && (phi2 - want2).abs() < 0.05);
}

#[test]
fn a_top_load_and_physical_sections_are_checked() {
    let path = root().join("examples/structure_truncation.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let refused = |from: &str, to: &str, says: &str| {
        assert!(text.contains(from), "{from}");
        let e = Scene::parse(&path, text.replacen(from, to, 1))
            .map(|_| ())
            .expect_err(to);
        let e = e.to_string();
        assert!(e.contains(says), "{to}: {e}");
    };
    refused(
        "static = [1915111.107797445, 1606969.0242163483]",
        "static = [1.0]",
        "top_load.static",
    );
    refused("x = \"load.force_x\"", "x = \"load\"", "top_load.x");
    refused(
        "ends.start = { kind = \"pinned\" }",
        "ends.start = { kind = \"pinned\" }\nends.end = { z = { force = 1.0 } }",
        "ends.end.z",
    );
    refused("seed = 21", "seed = 21\nquantity = \"force\"", "quantity");
    refused(
        "reference = \"cable\"",
        "reference = \"beam\"",
        "structure.reference",
    );
    // Two physical sections leave a cut without a numerical side.
    refused(
        "to = 1571.375\nfidelity = \"cable\"",
        "to = 1571.375\nfidelity = \"cable\"\nphysical = {}",
        "both physical",
    );
}
