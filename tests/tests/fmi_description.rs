//! Honest model descriptions (issue 29): an exported FMU says who made it, when,
//! under which licence and version, in which log categories it reports, and
//! describes its parameters as the scene reference does (unit, range, meaning),
//! all fixed at instantiation. `fmpy validate` of every example unit is in
//! `fmi_python.rs`.

use slender_fmi::model_description::{ModelDescription, Value, VariableCausality};
use slender_tests::{fmu, root};
use std::io::Read;
use std::path::Path;
use std::process::Command;

/// `slender fmu export` of unit `unit` of an example, with the generation date
/// fixed at `epoch` (s) the reproducible-builds way; its model description.
fn exported(scene: &str, unit: &str, epoch: u64, dir: &Path) -> ModelDescription {
    let cli = fmu::library().with_file_name("slender");
    let out = dir.join(format!("{unit}.fmu"));
    let status = Command::new(cli)
        .args(["fmu", "export"])
        .arg(root().join(scene))
        .args(["--unit", unit, "--out"])
        .arg(&out)
        .env("SOURCE_DATE_EPOCH", epoch.to_string())
        .output()
        .expect("slender runs");
    assert!(
        status.status.success(),
        "{}",
        String::from_utf8_lossy(&status.stderr)
    );
    let file = std::fs::File::open(&out).expect("FMU written");
    let mut zip = zip::ZipArchive::new(file).expect("an FMU is a zip");
    let mut xml = String::new();
    zip.by_name("modelDescription.xml")
        .expect("modelDescription.xml")
        .read_to_string(&mut xml)
        .expect("UTF-8");
    ModelDescription::parse(&xml).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn an_exported_fmu_says_who_made_it_when_and_under_which_terms() {
    let dir = tempfile::tempdir().unwrap();
    let md = exported(
        "examples/truncation_substructured.toml",
        "p",
        86_400,
        dir.path(),
    );
    let about = &md.about;
    assert_eq!(
        about.generation_date_and_time.as_deref(),
        Some("1970-01-02T00:00:00Z")
    );
    assert_eq!(about.version, env!("CARGO_PKG_VERSION"));
    assert_eq!(about.license, "MIT OR Apache-2.0");
    assert!(!about.author.is_empty());
    let categories: Vec<&str> = md.log_categories.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(categories, ["logAll", "logStatusWarning", "logStatusError"]);
}

#[test]
fn parameters_carry_the_reference_s_unit_range_and_meaning_and_are_fixed() {
    let dir = tempfile::tempdir().unwrap();
    let md = exported("examples/truncation_substructured.toml", "p", 0, dir.path());
    let var = |name: &str| {
        md.variables
            .iter()
            .find(|v| v.name == name)
            .unwrap_or_else(|| panic!("no variable {name}"))
    };
    let length = var("length");
    assert_eq!(length.unit.as_deref(), Some("m"));
    assert_eq!((length.min, length.max), (Some(1e-2), Some(1e5)));
    assert!(
        length.description.contains("unstretched length"),
        "{}",
        length.description
    );
    assert_eq!(var("mass_per_length").unit.as_deref(), Some("kg/m"));
    assert_eq!(var("rayleigh_stiffness").unit.as_deref(), Some("s"));
    assert!(var("effects.drag").description.contains("drag"));
    for v in md
        .variables
        .iter()
        .filter(|v| v.causality == VariableCausality::Parameter)
    {
        assert_eq!(v.variability, "fixed", "{}", v.name);
        assert!(!v.description.is_empty(), "{}", v.name);
        if let (Value::Real(Some(start)), Some(min), Some(max)) = (&v.value, v.min, v.max) {
            assert!((min..=max).contains(start), "{}: {start} outside", v.name);
        }
    }
}
