//! FMUs that are wrong in every way an importer meets (broken archives, model
//! descriptions, binaries, GUIDs, units of measure, start values): each gives a
//! clear error naming the file and what is wrong.

use slender_fmi::export::ExportConfig;
use slender_fmi::import::{FmuParams, FmuUnit, LoadError};
use slender_scene::export::{ExportedUnit, SceneExport};
use slender_tests::fmu::import;
use slender_tests::{fmu, load};
use slender_units::{Driver, Time, Unit};
use std::io::Write;
use std::path::Path;

fn temp() -> tempfile::TempDir {
    tempfile::tempdir().unwrap()
}

fn write_zip(path: &Path, entries: &[(&str, &[u8])]) {
    let file = std::fs::File::create(path).unwrap();
    let mut zip = zip::ZipWriter::new(file);
    for (name, bytes) in entries {
        zip.start_file(*name, zip::write::SimpleFileOptions::default())
            .unwrap();
        zip.write_all(bytes).unwrap();
    }
    zip.finish().unwrap();
}

/// An exported FMU's model description and library, to build broken variants.
fn parts(dir: &Path) -> (String, Vec<u8>, Vec<u8>) {
    let file = fmu::export("examples/b1_two_masses.toml", "left", dir);
    let mut archive = zip::ZipArchive::new(std::fs::File::open(file).unwrap()).unwrap();
    let mut read = |name: &str| {
        let mut bytes = Vec::new();
        std::io::Read::read_to_end(&mut archive.by_name(name).unwrap(), &mut bytes).unwrap();
        bytes
    };
    let xml = String::from_utf8(read("modelDescription.xml")).unwrap();
    (
        xml,
        read("binaries/linux64/slender_left.so"),
        read("resources/slender-unit.toml"),
    )
}

fn expect_error(file: &Path, wanted: &[&str]) -> String {
    let e = match import(file) {
        Ok(_) => panic!("{} loaded", file.display()),
        Err(e) => e,
    };
    for w in wanted {
        assert!(e.contains(w), "`{w}` not in: {e}");
    }
    e
}

#[test]
fn broken_archives_and_model_descriptions_give_clear_errors() {
    let dir = temp();
    let (xml, library, _) = parts(dir.path());
    let at = |name: &str| dir.path().join(name);
    let so = "binaries/linux64/slender_left.so";

    std::fs::write(at("corrupt.fmu"), b"PK\x03\x04 this is not a zip").unwrap();
    expect_error(&at("corrupt.fmu"), &["corrupt.fmu", "zip"]);

    expect_error(&at("missing.fmu"), &["missing.fmu", "cannot open"]);

    write_zip(&at("no_description.fmu"), &[(so, &library)]);
    expect_error(&at("no_description.fmu"), &["modelDescription.xml"]);

    let broken = xml.replacen("<ModelVariables>", "<ModelVariables><oops", 1);
    write_zip(
        &at("bad_xml.fmu"),
        &[("modelDescription.xml", broken.as_bytes())],
    );
    // The error names the line where the broken tag ends: `<oops` runs on to the
    // first `>` on the line after `<ModelVariables>`.
    let line = 2 + xml[..xml.find("<ModelVariables>").unwrap()]
        .matches('\n')
        .count();
    expect_error(
        &at("bad_xml.fmu"),
        &[
            "bad_xml.fmu",
            &format!("modelDescription.xml:{line}"),
            "<oops>",
        ],
    );

    let no_guid = xml.replacen(" guid=", " nope=", 1);
    write_zip(
        &at("no_guid.fmu"),
        &[("modelDescription.xml", no_guid.as_bytes())],
    );
    expect_error(
        &at("no_guid.fmu"),
        &["modelDescription.xml:2", "fmiModelDescription", "guid"],
    );

    let me_only = xml.replacen("<CoSimulation", "<ModelExchange", 1);
    write_zip(
        &at("me.fmu"),
        &[("modelDescription.xml", me_only.as_bytes())],
    );
    expect_error(&at("me.fmu"), &["does not offer co-simulation"]);
}

#[test]
fn missing_binaries_symbols_resources_and_wrong_guids_give_clear_errors() {
    let dir = temp();
    let (xml, library, resources) = parts(dir.path());
    let at = |name: &str| dir.path().join(name);
    let so = "binaries/linux64/slender_left.so";
    let res = "resources/slender-unit.toml";

    write_zip(
        &at("windows.fmu"),
        &[
            ("modelDescription.xml", xml.as_bytes()),
            ("binaries/win64/slender_left.dll", b"MZ"),
        ],
    );
    expect_error(
        &at("windows.fmu"),
        &["binaries/linux64/slender_left.so", "win64"],
    );

    let libm = std::fs::read("/lib/x86_64-linux-gnu/libm.so.6").unwrap();
    write_zip(
        &at("no_symbols.fmu"),
        &[("modelDescription.xml", xml.as_bytes()), (so, &libm)],
    );
    expect_error(
        &at("no_symbols.fmu"),
        &["does not export `fmi2Instantiate`"],
    );

    write_zip(
        &at("no_resources.fmu"),
        &[("modelDescription.xml", xml.as_bytes()), (so, &library)],
    );
    expect_error(
        &at("no_resources.fmu"),
        &["fmi2Instantiate failed", "slender-unit.toml"],
    );

    let other_guid = xml.replacen("guid=\"{", "guid=\"{0", 1);
    write_zip(
        &at("guid.fmu"),
        &[
            ("modelDescription.xml", other_guid.as_bytes()),
            (so, &library),
            (res, &resources),
        ],
    );
    expect_error(&at("guid.fmu"), &["fmi2Instantiate failed", "GUID"]);
}

#[test]
fn a_library_that_lays_the_unit_out_otherwise_is_refused() {
    let dir = temp();
    let (xml, library, resources) = parts(dir.path());
    let at = |name: &str| dir.path().join(name);
    let so = "binaries/linux64/slender_left.so";
    let res = "resources/slender-unit.toml";
    // A library that lays the unit out otherwise than the description (built
    // from other sources than the exporter) is refused at instantiation,
    // naming the first variable that differs; an FMU without the list (older
    // exports) still loads.
    let variables = "resources/slender-variables.txt";
    let entries = |list: &[u8]| -> Vec<(&str, Vec<u8>)> {
        vec![
            ("modelDescription.xml", xml.as_bytes().to_vec()),
            (so, library.clone()),
            (res, resources.clone()),
            (variables, list.to_vec()),
        ]
    };
    let list = b"0 force_in Input Real []\n";
    let stale: Vec<(&str, Vec<u8>)> = entries(list);
    let stale: Vec<(&str, &[u8])> = stale.iter().map(|(n, b)| (*n, &b[..])).collect();
    write_zip(&at("stale_library.fmu"), &stale);
    expect_error(
        &at("stale_library.fmu"),
        &[
            "lays the unit out differently",
            "`0 force_in Input Real []`",
            "export again",
        ],
    );
    write_zip(
        &at("no_list.fmu"),
        &[
            ("modelDescription.xml", xml.as_bytes()),
            (so, &library),
            (res, &resources),
        ],
    );
    assert!(import(&at("no_list.fmu")).is_ok());
}

#[test]
fn an_unknown_unit_of_measure_is_kept_and_checked_on_connection() {
    let dir = temp();
    let (xml, library, resources) = parts(dir.path());
    let at = |name: &str| dir.path().join(name);
    let so = "binaries/linux64/slender_left.so";
    let res = "resources/slender-unit.toml";

    // A unit of measure slender's kinds do not use (kN) is kept and checked
    // against the connection.
    assert!(xml.contains(r#"<Real unit="m"/>"#));
    let kilonewton = xml.replacen(r#"<Real unit="m"/>"#, r#"<Real unit="kN"/>"#, 1);
    write_zip(
        &at("kn.fmu"),
        &[
            ("modelDescription.xml", kilonewton.as_bytes()),
            (so, &library),
            (res, &resources),
        ],
    );
    let unit = import(&at("kn.fmu")).unwrap();
    let port = &unit.description().outputs[0];
    assert_eq!(
        (port.kind, port.unit.as_str()),
        (slender_units::PortKind::Generic, "kN")
    );
    let mut system = slender_coupling::System::new();
    system.add_unit("fmu", Box::new(unit)).unwrap();
    let native = ExportConfig::from_scene(&load("examples/b1_two_masses.toml"), "right")
        .unwrap()
        .build_unit()
        .unwrap();
    system.add_unit("right", native).unwrap();
    let link = slender_coupling::Link {
        gain: 1.0,
        offset: 0.0,
        tolerance: None,
    };
    let e = system
        .connect("fmu.displacement", "right.coupling_displacement", link)
        .unwrap_err();
    assert!(
        matches!(&e, slender_coupling::SystemError::UnitMismatch { from_unit, to_unit, .. } if from_unit == "kN" && to_unit == "m"),
        "{e}"
    );
    assert!(
        e.to_string().contains("units of measure differ (kN vs m)"),
        "{e}"
    );
}

#[test]
fn start_values_are_checked_against_the_model_description() {
    let dir = temp();
    let (xml, library, resources) = parts(dir.path());
    let at = |name: &str| dir.path().join(name);
    let so = "binaries/linux64/slender_left.so";
    let res = "resources/slender-unit.toml";

    // Start values: an unknown name, a wrong type.
    let good = at("good.fmu");
    write_zip(
        &good,
        &[
            ("modelDescription.xml", xml.as_bytes()),
            (so, &library),
            (res, &resources),
        ],
    );
    let with_start = |name: &str, value: toml::Value| FmuParams {
        file: good.clone(),
        start: [(name.to_owned(), value)].into_iter().collect(),
        preload: Vec::new(),
        logging: false,
    };
    let e = FmuUnit::load(&with_start("mas", toml::Value::Float(2.0)), Path::new("."))
        .err()
        .unwrap();
    assert!(
        matches!(&e, LoadError::UnknownStart { name, hint, .. } if name == "mas" && hint.contains("mass")),
        "{e}"
    );
    let e = e.to_string();
    assert!(e.contains("no variable `mas`") && e.contains("mass"), "{e}");
    let e = FmuUnit::load(
        &with_start("mass", toml::Value::String("heavy".into())),
        Path::new("."),
    )
    .err()
    .unwrap();
    assert!(
        matches!(
            e,
            LoadError::WrongStartType {
                expected: "Real",
                ..
            }
        ),
        "{e}"
    );
    let e = e.to_string();
    assert!(
        e.contains("start.mass") && e.contains("expected a Real"),
        "{e}"
    );
    let e = FmuUnit::load(
        &with_start("displacement", toml::Value::Float(1.0)),
        Path::new("."),
    )
    .err()
    .unwrap();
    assert!(matches!(e, LoadError::NotSettable { .. }), "{e}");
    let e = e.to_string();
    assert!(e.contains("not a parameter or an input"), "{e}");
    // A parameter the unit rejects: reported by the FMU at initialisation.
    let mut unit = Driver::new(
        FmuUnit::load(
            &with_start("mass", toml::Value::Float(-1.0)),
            Path::new("."),
        )
        .unwrap(),
    );
    unit.set_inputs(&[0.0, 0.0]).unwrap();
    let e = unit.initialize(Time::ZERO).unwrap_err().to_string();
    assert!(
        e.contains("good.fmu") && e.contains("mass") && e.contains("> 0"),
        "{e}"
    );
}
