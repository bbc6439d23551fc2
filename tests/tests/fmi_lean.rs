//! Lean FMUs (issue 29): the FMU library links the units, the kind registry and
//! the FMI layer only (no scene, coupling, study, plotting or command-line code),
//! ships stripped, and an exported FMU stays small.

use slender_tests::{elf, fmu};
use std::path::Path;
use std::process::Command;

/// Crates an exported FMU has no use for: the scene and the master, studies,
/// and the command line's crates.
const NOT_IN_AN_FMU: [&str; 9] = [
    "slender-scene",
    "slender-coupling",
    "slender-app",
    "slender-uq",
    "statrs",
    "sobol_burley",
    "clap",
    "plotters",
    "indicatif",
];

#[test]
fn the_fmu_library_links_no_scene_coupling_study_or_cli_crate() {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let tree = Command::new(cargo)
        .args([
            "tree",
            "--offline",
            "-p",
            "slender-fmu",
            "-e",
            "normal,build",
        ])
        .args(["--prefix", "none", "--format", "{p}"])
        .current_dir(slender_tests::root())
        .output()
        .expect("cargo tree runs");
    assert!(
        tree.status.success(),
        "cargo tree failed: {}",
        String::from_utf8_lossy(&tree.stderr)
    );
    let tree = String::from_utf8_lossy(&tree.stdout);
    let linked: Vec<&str> = tree
        .lines()
        .filter_map(|l| l.split_whitespace().next())
        .collect();
    assert!(linked.contains(&"slender-kinds") && linked.contains(&"slender-units"));
    for name in NOT_IN_AN_FMU {
        assert!(
            !linked.contains(&name),
            "the FMU library links `{name}`:\n{tree}"
        );
    }
}

#[test]
fn the_release_fmu_library_is_stripped_and_an_fmu_stays_under_3_mb() {
    if cfg!(debug_assertions) {
        eprintln!("skipped: the debug profile keeps symbols; run with --release");
        return;
    }
    let library = fmu::library();
    let bytes = std::fs::read(&library).expect("library readable");
    let sections: Vec<String> = elf::sections(&bytes).into_iter().map(|s| s.name).collect();
    assert!(sections.iter().any(|s| s == ".text"), "{sections:?}");
    for kept in [".symtab", ".debug_info", ".debug_line", ".strtab"] {
        assert!(
            !sections.iter().any(|s| s == kept),
            "{} keeps {kept}: {sections:?}",
            library.display()
        );
    }
    let dir = tempfile::tempdir().expect("temporary folder");
    let fmu = fmu::export("examples/truncation_substructured.toml", "p", dir.path());
    let size = std::fs::metadata(&fmu).expect("fmu written").len();
    eprintln!(
        "{}: library {} bytes, FMU {size} bytes",
        Path::new(&library).display(),
        bytes.len()
    );
    assert!(
        size < 3_000_000,
        "the FMU is {size} bytes (goal: under 3 MB)"
    );
}
