//! A section as an external FMU (issue 13): `fidelity = { kind = "fmu", file,
//! ports }` puts an FMU in place of a section's unit, wired by the ports of the
//! fidelity it names. The mooring line's lower section exported by slender and
//! coupled back as an FMU gives the native run's results bit for bit, and so
//! does the S-lay's suspended span as a `beam` about its chord (kind `chord`).

use slender_fmi::export::ExportConfig;
use slender_scene::Scene;
use slender_scene::export::SceneExport;
use slender_scene::export::package;
use slender_tests::{fmu::library, root, run};

/// The mooring example over 10 s with a nonlinear lower section, `lower` being
/// that section's `fidelity` value. Without Newton's warm start: FMI 2.0 has no
/// call to tell an FMU that it repeats a step, so a native section would start
/// its repeated solves nearer than the FMU (the same to the sections' Newton
/// tolerance, not to the bit).
fn mooring(lower: &str) -> String {
    let text = std::fs::read_to_string(root().join("examples/structure_mooring.toml")).unwrap();
    text.replace("duration = 60.0", "duration = 10.0")
        .replace("fidelity = \"cable\"", &format!("fidelity = {lower}"))
        .replace(
            "newton = { derivatives = \"units\" }",
            "newton = { derivatives = \"units\", warm_start = false }",
        )
}

/// Exports unit `unit` of the scene `native` (TOML) as `file` in `dir`, and
/// loads it and the scene `with_fmu` (TOML naming that file in the unit's place).
fn exported_in_place(
    dir: &std::path::Path,
    (native, unit, file): (&str, &str, &str),
    with_fmu: &str,
) -> (Scene, Scene) {
    let native_path = dir.join("native.toml");
    std::fs::write(&native_path, native).unwrap();
    let native = Scene::load(&native_path).unwrap_or_else(|e| panic!("{e}"));
    let config = ExportConfig::from_scene(&native, unit).unwrap_or_else(|e| panic!("{e}"));
    package(&config, &library(), &dir.join(file)).unwrap_or_else(|e| panic!("{e}"));
    let fmu_path = dir.join("fmu.toml");
    std::fs::write(&fmu_path, with_fmu).unwrap();
    let with_fmu = Scene::load(&fmu_path).unwrap_or_else(|e| panic!("{e}"));
    (native, with_fmu)
}

/// Runs both scenes and asserts the same outputs bit for bit and the same
/// coupling iterations (`what` names the FMU's part in the message).
fn assert_bit_identical(native: &Scene, with_fmu: &Scene, what: &str) {
    let (a, b) = (run(native), run(with_fmu));
    assert!(
        a.error.is_none() && b.error.is_none(),
        "{:?} {:?}",
        a.error,
        b.error
    );
    assert_eq!(a.names, b.names);
    assert_eq!(a.columns, b.columns, "{what} differs from the native one");
    assert_eq!(a.counters.iterations, b.counters.iterations);
}

#[test]
fn a_section_exported_as_an_fmu_and_coupled_back_gives_the_native_results() {
    let dir = tempfile::tempdir().unwrap();
    let (native, with_fmu) = exported_in_place(
        dir.path(),
        (&mooring("\"nonlinear\""), "line_lower", "lower.fmu"),
        &mooring("{ kind = \"fmu\", file = \"lower.fmu\", ports = \"nonlinear\" }"),
    );
    let t: toml::Table = toml::from_str(with_fmu.source().expect("the expanded scene")).unwrap();
    let lower = t["units"]
        .as_array()
        .unwrap()
        .iter()
        .find(|u| u["name"].as_str() == Some("line_lower"))
        .unwrap()
        .clone();
    assert_eq!(lower["kind"].as_str(), Some("fmu"));
    // The first guesses of its force inputs stay with it.
    assert!(lower["inputs"]["end_force_x_in"].as_float().is_some());
    assert_bit_identical(&native, &with_fmu, "the FMU section");
}

/// The S-lay fidelity example over 5 s, its suspended span's `fidelity` being
/// `suspended`.
fn slay(suspended: &str) -> String {
    let text =
        std::fs::read_to_string(root().join("examples/structure_slay_fidelity.toml")).unwrap();
    text.replace("duration = 30.0", "duration = 5.0")
        .replace("fidelity = \"beam\"", &format!("fidelity = {suspended}"))
}

#[test]
fn a_chord_section_exported_as_an_fmu_and_coupled_back_gives_the_native_results() {
    let dir = tempfile::tempdir().unwrap();
    let (native, with_fmu) = exported_in_place(
        dir.path(),
        (&slay("\"beam\""), "pipe_suspended", "span.fmu"),
        &slay("{ kind = \"fmu\", file = \"span.fmu\", ports = \"beam\" }"),
    );
    assert_bit_identical(&native, &with_fmu, "the FMU chord");
}

#[test]
fn an_fmu_section_needs_its_file_and_known_keys() {
    let path = root().join("examples/structure_mooring.toml");
    for (fidelity, says) in [
        ("{ kind = \"fmu\" }", "fidelity.file"),
        (
            "{ kind = \"fmu\", file = \"x.fmu\", elements = 3 }",
            "fidelity.elements",
        ),
        (
            "{ kind = \"fmu\", file = \"x.fmu\", ports = \"shell\" }",
            "fidelity.ports",
        ),
    ] {
        let e = Scene::parse(&path, mooring(fidelity))
            .expect_err(fidelity)
            .to_string();
        assert!(e.contains(says), "{fidelity}: {e}");
    }
}
