//! Lean FMUs (issue 29): the FMU library links the units, the kind registry and
//! the FMI layer only (no scene, coupling, study, plotting or command-line code),
//! ships stripped, and an exported FMU stays small.

use slender_tests::fmu;
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

/// The names of an ELF64 (little-endian) file's sections.
fn elf_sections(bytes: &[u8]) -> Vec<String> {
    let u16_at = |o: usize| u16::from_le_bytes([bytes[o], bytes[o + 1]]) as usize;
    let u64_at = |o: usize| {
        let mut b = [0u8; 8];
        b.copy_from_slice(&bytes[o..o + 8]);
        u64::from_le_bytes(b) as usize
    };
    assert_eq!(&bytes[..4], b"\x7fELF", "not an ELF file");
    let (table, entry, count, names) = (u64_at(0x28), u16_at(0x3A), u16_at(0x3C), u16_at(0x3E));
    let names_at = u64_at(table + names * entry + 0x18);
    (0..count)
        .map(|k| {
            let name = names_at
                + u32::from_le_bytes(
                    bytes[table + k * entry..table + k * entry + 4]
                        .try_into()
                        .expect("4 bytes"),
                ) as usize;
            let end = bytes[name..].iter().position(|&b| b == 0).unwrap_or(0);
            String::from_utf8_lossy(&bytes[name..name + end]).into_owned()
        })
        .collect()
}

#[test]
fn the_release_fmu_library_is_stripped_and_an_fmu_stays_under_3_mb() {
    if cfg!(debug_assertions) {
        eprintln!("skipped: the debug profile keeps symbols; run with --release");
        return;
    }
    let library = fmu::library();
    let bytes = std::fs::read(&library).expect("library readable");
    let sections = elf_sections(&bytes);
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
