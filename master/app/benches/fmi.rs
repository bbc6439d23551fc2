//! Criterion benchmarks of the FMI layer: one step of a unit called natively
//! against the same unit exported as an FMU and called through slender's importer
//! (both sides of the C boundary: fmi2SetReal, fmi2SetRealInputDerivatives,
//! fmi2DoStep, fmi2GetReal), and the same for a save/restore cycle.
//!
//! Needs `target/release/libslender_fmu.so`: `cargo build --release -p slender-fmu`
//! first. Run with `cargo bench -p slender-master --bench fmi`.

use criterion::{Criterion, criterion_group, criterion_main};
use slender_fmi::export::ExportConfig;
use slender_fmi::import::{FmuParams, FmuUnit};
use slender_scene::Scene;
use slender_scene::export::{ExportedUnit, SceneExport, package};
use slender_units::{Driver, DriverSlot, Time, Unit};
use std::hint::black_box;
use std::path::{Path, PathBuf};

fn library() -> PathBuf {
    let exe = std::env::current_exe().expect("bench executable");
    let lib = exe
        .parent()
        .and_then(Path::parent)
        .expect("target/release/deps")
        .join("libslender_fmu.so");
    assert!(
        lib.exists(),
        "{} missing: run `cargo build --release -p slender-fmu` first",
        lib.display()
    );
    lib
}

/// The native unit, the same unit through an exported FMU, and the start inputs
/// the scene settled on.
fn pair(scene: &str, unit: &str, dir: &Path) -> (Driver, Driver, Vec<f64>) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(scene);
    let scene = Scene::load(&path).expect("example scene loads");
    let config = ExportConfig::from_scene(&scene, unit).expect("unit exists");
    let file = dir.join(format!("{unit}.fmu"));
    package(&config, &library(), &file).expect("packaged");
    let params = FmuParams {
        file,
        start: Default::default(),
        preload: Vec::new(),
        logging: false,
    };
    let native = config.driver().expect("builds");
    let fmu: Box<dyn Unit> = Box::new(FmuUnit::load(&params, Path::new(".")).expect("loads"));
    let fmu = Driver::new(fmu);
    let inputs = native
        .description()
        .inputs
        .iter()
        .map(|p| config.inputs[&p.name])
        .collect();
    (native, fmu, inputs)
}

fn steps(c: &mut Criterion) {
    let dir = tempfile::tempdir().expect("temporary folder");
    let h = Time::from_secs(0.01).expect("step");
    let mut group = c.benchmark_group("fmi_step");
    for (scene, unit, label) in [
        ("b3_force_displacement.toml", "b", "oscillator"),
        ("truncation_substructured.toml", "n", "cable_80_elements"),
    ] {
        let (mut native, mut fmu, config_inputs) = pair(scene, unit, dir.path());
        native.set_inputs(&config_inputs).expect("inputs");
        native.initialize(Time::ZERO).expect("initialises");
        fmu.set_inputs(&config_inputs).expect("inputs");
        fmu.initialize(Time::ZERO).expect("initialises");
        let mut out = vec![0.0; native.description().outputs.len()];
        for (name, unit) in [("native", &mut native), ("through_fmi", &mut fmu)] {
            let mut t = Time::ZERO;
            group.bench_function(format!("{label}/{name}"), |b| {
                b.iter(|| {
                    unit.set_inputs(black_box(&config_inputs)).expect("inputs");
                    unit.do_step(t, h).expect("steps");
                    unit.outputs(&mut out).expect("outputs");
                    t += h;
                })
            });
            let mut slot = DriverSlot::new();
            group.bench_function(format!("{label}/{name}/save_step_restore"), |b| {
                b.iter(|| {
                    unit.save(&mut slot).expect("saves");
                    unit.set_inputs(black_box(&config_inputs)).expect("inputs");
                    unit.do_step(t, h).expect("steps");
                    unit.outputs(&mut out).expect("outputs");
                    unit.restore(&slot).expect("restores");
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, steps);
criterion_main!(benches);
