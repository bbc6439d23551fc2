//! Portable FMUs (issue 29): the FMU library built against glibc 2.17 by
//! `./scripts/portable-fmu.sh` (zig through cargo-zigbuild) needs no newer
//! glibc symbol, and an FMU made with it steps bit-identically to one made
//! with the native build. The native build's own requirement is printed for
//! comparison (this machine's glibc).

use slender_fmi::export::ExportConfig;
use slender_scene::export::{ExportedUnit, SceneExport, package};
use slender_tests::{elf, fmu, load, root};
use slender_units::{Driver, Time};
use std::path::PathBuf;

/// Where `./scripts/portable-fmu.sh` puts the library.
fn portable_library() -> PathBuf {
    let lib = root().join("target/x86_64-unknown-linux-gnu/release/libslender_fmu.so");
    assert!(
        lib.exists(),
        "{} is missing: run ./scripts/portable-fmu.sh (./scripts/test.sh does)",
        lib.display()
    );
    lib
}

#[test]
#[ignore = "needs ./scripts/portable-fmu.sh (zig): ./scripts/test.sh runs it"]
fn the_portable_library_needs_glibc_2_17_at_most() {
    let portable = std::fs::read(portable_library()).unwrap();
    let needed = elf::highest_glibc(&portable).expect("links glibc");
    let native = elf::highest_glibc(&std::fs::read(fmu::library()).unwrap());
    eprintln!("portable: GLIBC {needed:?}; native build: GLIBC {native:?}");
    assert!(needed <= (2, 17), "needs GLIBC_{}.{}", needed.0, needed.1);
}

/// The outputs of `steps` steps of an FMU made with `library` under constant
/// start inputs.
fn stepped(config: &ExportConfig, library: &std::path::Path, steps: i64) -> Vec<f64> {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("unit.fmu");
    package(config, library, &file).unwrap_or_else(|e| panic!("{e}"));
    let mut unit = Driver::new(fmu::import(&file).unwrap_or_else(|e| panic!("{e}")));
    let start = slender_tests::samples::start_inputs(config, &config.driver().unwrap());
    unit.set_inputs(&start).unwrap();
    unit.initialize(Time::ZERO).unwrap();
    let h = Time::from_secs(config.step).unwrap();
    let mut out = vec![0.0; unit.description().outputs.len()];
    let mut all = Vec::new();
    for k in 0..steps {
        unit.do_step(h * k, h).unwrap();
        unit.outputs(&mut out).unwrap();
        all.extend_from_slice(&out);
    }
    all
}

#[test]
#[ignore = "needs ./scripts/portable-fmu.sh (zig): ./scripts/test.sh runs it"]
fn an_fmu_with_the_portable_library_steps_as_the_native_one() {
    let scene = load("examples/truncation_substructured.toml");
    let config = ExportConfig::from_scene(&scene, "p").unwrap();
    let native = stepped(&config, &fmu::library(), 200);
    let portable = stepped(&config, &portable_library(), 200);
    assert_eq!(native.len(), portable.len());
    let same = native
        .iter()
        .zip(&portable)
        .all(|(a, b)| a.to_bits() == b.to_bits());
    assert!(
        same,
        "the portable FMU's outputs differ from the native FMU's"
    );
}
