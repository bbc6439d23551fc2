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

/// The crates `package` links (its normal and build dependencies), as
/// `cargo tree` lists them.
fn linked_by(package: &str) -> Vec<String> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let tree = Command::new(cargo)
        .args(["tree", "--offline", "-p", package, "-e", "normal,build"])
        .args(["--prefix", "none", "--format", "{p}"])
        .current_dir(slender_tests::root())
        .output()
        .expect("cargo tree runs");
    assert!(
        tree.status.success(),
        "cargo tree failed: {}",
        String::from_utf8_lossy(&tree.stderr)
    );
    String::from_utf8_lossy(&tree.stdout)
        .lines()
        .filter_map(|l| l.split_whitespace().next().map(str::to_owned))
        .collect()
}

/// The unit contract is its own crate: the master and the FMI layer depend on
/// it, not on the physics (issue 29).
#[test]
fn the_master_and_the_fmi_layer_depend_on_the_contract_not_the_units() {
    for package in ["slender-coupling", "slender-fmi"] {
        let linked = linked_by(package);
        assert!(
            linked.iter().any(|c| c == "slender-contract"),
            "{package}: {linked:?}"
        );
        assert!(
            !linked.iter().any(|c| c == "slender-units"),
            "{package}: {linked:?}"
        );
    }
}

#[test]
fn the_fmu_library_links_no_scene_coupling_study_or_cli_crate() {
    let linked = linked_by("slender-fmu");
    let tree = linked.join("\n");
    let linked: Vec<&str> = linked.iter().map(String::as_str).collect();
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
