//! FMU helpers: where the exported library is, exporting scene units, Python.

use super::root;
use slender_fmi::export::ExportConfig;
use slender_scene::Scene;
use slender_scene::export::{FmiVersion, SceneExport, package, wrap_scene};
use std::path::{Path, PathBuf};

/// `libslender_fmu.so` of the profile the tests run in (target/<profile>/).
pub fn library() -> PathBuf {
    let exe = std::env::current_exe().expect("test executable path");
    let profile_dir = exe
        .parent()
        .and_then(Path::parent)
        .expect("target/<profile>/deps/<test>");
    let lib = profile_dir.join("libslender_fmu.so");
    assert!(
        lib.exists(),
        "{} is missing: build it with `cargo build --release -p slender-fmu` (./scripts/test.sh does)",
        lib.display()
    );
    lib
}

/// Loads an FMU as a unit (no start values, no logging); the error as text.
pub fn import(file: &Path) -> Result<slender_fmi::import::FmuUnit, String> {
    let params = slender_fmi::import::FmuParams {
        file: file.to_owned(),
        start: Default::default(),
        preload: Vec::new(),
        logging: false,
    };
    slender_fmi::import::FmuUnit::load(&params, Path::new(".")).map_err(|e| e.to_string())
}

/// Exports unit `unit` of the example scene `scene` (relative to the root)
/// into `dir`; returns the FMU's path.
pub fn export(scene: &str, unit: &str, dir: &Path) -> PathBuf {
    let scene = super::load(scene);
    let config = ExportConfig::from_scene(&scene, unit).unwrap_or_else(|e| panic!("{e}"));
    let out = dir.join(format!("{unit}.fmu"));
    package(&config, &library(), &out).unwrap_or_else(|e| panic!("{e}"));
    out
}

/// Exports every unit of an example scene into `dir` (FMI 2.0) and loads
/// the scene that uses the FMUs.
pub fn wrapped(scene: &str, dir: &Path) -> Scene {
    wrapped_version(scene, dir, FmiVersion::Two)
}

/// As [`wrapped`], with FMUs of FMI `version`.
pub fn wrapped_version(scene: &str, dir: &Path, version: FmiVersion) -> Scene {
    let scene = super::load(scene);
    let path = wrap_scene(&scene, &library(), dir, version).unwrap_or_else(|e| panic!("{e}"));
    Scene::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// The shared libpython and the site-packages folder of the test
/// environment's Python (a pythonfmu FMU needs libpython preloaded and
/// its packages on PYTHONPATH).
pub fn python_paths() -> (PathBuf, String) {
    let query = |code: &str| {
        let out = std::process::Command::new(python())
            .args(["-c", code])
            .output()
            .unwrap();
        String::from_utf8(out.stdout).unwrap().trim().to_owned()
    };
    let libdir = query("import sysconfig; print(sysconfig.get_config_var('LIBDIR'))");
    let library = query("import sysconfig; print(sysconfig.get_config_var('LDLIBRARY'))");
    let site = query("import site; print(site.getsitepackages()[0])");
    (Path::new(&libdir).join(library), site)
}

/// Builds the pythonfmu script `script` (under tests/python/) into an FMU
/// in `dir` with pythonfmu's `options` (e.g. `--handle-state`), asserting
/// that the build succeeds.
pub fn pythonfmu_build(script: &str, options: &[&str], dir: &Path) {
    let build = std::process::Command::new(python())
        .args(["-m", "pythonfmu", "build"])
        .args(options)
        .arg("-f")
        .arg(root().join("tests/python").join(script))
        .arg("-d")
        .arg(dir)
        .output()
        .unwrap();
    assert!(
        build.status.success(),
        "{}",
        String::from_utf8_lossy(&build.stderr)
    );
}

/// Runs the `slender` command line (built beside the FMU library) with
/// `args` and PYTHONPATH `site`, echoing its output.
pub fn slender(args: &[&str], site: &str) -> std::process::Output {
    let cli = library().with_file_name("slender");
    assert!(
        cli.exists(),
        "{} is missing: cargo build --release",
        cli.display()
    );
    let out = std::process::Command::new(cli)
        .args(args)
        .env("PYTHONPATH", site)
        .output()
        .unwrap();
    println!("{}", String::from_utf8_lossy(&out.stdout));
    eprintln!("{}", String::from_utf8_lossy(&out.stderr));
    out
}

/// The Python of the test environment (SLENDER_PYTHON, else .venv/bin/python).
pub fn python() -> PathBuf {
    let python = std::env::var_os("SLENDER_PYTHON")
        .map(PathBuf::from)
        .unwrap_or_else(|| root().join(".venv/bin/python"));
    assert!(
        python.exists(),
        "{} is missing: ./scripts/test.sh creates the Python environment with FMPy and pythonfmu",
        python.display()
    );
    python
}
