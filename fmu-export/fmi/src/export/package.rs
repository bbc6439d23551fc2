//! An FMU written: the model description of the version asked for, the
//! `slender-fmu` library as its binary, and the unit's configuration and
//! variables as resources, zipped into a file that appears whole.

use super::{
    CONFIG_FILE, ExportConfig, Layout, PackageError, VARIABLES_FILE, check_binary, file_error,
};
use std::io::Write as _;
use std::path::Path;

/// Now in UTC (xs:dateTime), or `SOURCE_DATE_EPOCH` (s) where it is set, so
/// that a build meant to be reproducible writes the same description.
fn generation_date() -> String {
    let fixed = std::env::var("SOURCE_DATE_EPOCH")
        .ok()
        .and_then(|s| s.trim().parse::<u64>().ok())
        .map(|s| std::time::UNIX_EPOCH + std::time::Duration::from_secs(s));
    let when = fixed.unwrap_or_else(std::time::SystemTime::now);
    humantime::format_rfc3339_seconds(when).to_string()
}

/// The FMI version an FMU is written for (the library serves both).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum FmiVersion {
    /// FMI 2.0.
    #[default]
    Two,
    /// FMI 3.0.
    Three,
}

impl FmiVersion {
    /// The binaries folder of this platform in the standard's naming.
    fn binaries(self) -> &'static str {
        match self {
            FmiVersion::Two => "binaries/linux64",
            FmiVersion::Three => "binaries/x86_64-linux",
        }
    }
}

/// Writes the FMI 2.0 FMU for `config` with `layout` to `out` (see
/// [`package_version`]).
pub fn package(
    config: &ExportConfig,
    layout: &Layout,
    binary: &Path,
    out: &Path,
) -> Result<(), PackageError> {
    package_version(config, layout, binary, out, FmiVersion::Two)
}

/// Writes the FMU for `config` with `layout` to `out`, with `binary` (the
/// `slender-fmu` shared library, which has both versions' entry points) as
/// `<binaries>/<modelIdentifier>.so` and the model description of `version`.
pub fn package_version(
    config: &ExportConfig,
    layout: &Layout,
    binary: &Path,
    out: &Path,
    version: FmiVersion,
) -> Result<(), PackageError> {
    check_binary(binary)?;
    let library = std::fs::read(binary).map_err(|e| {
        file_error(
            binary,
            format!(
                "cannot read the FMU library ({e}); build it with `cargo build --release -p slender-fmu`"
            ),
        )
    })?;
    // The folder it goes in is made, as `slender fmu wrap` makes its own.
    if let Some(folder) = out.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(folder)
            .map_err(|e| file_error(folder, format!("cannot create the FMU's folder ({e})")))?;
    }
    let (file, partial) = crate::whole_file::create(out)
        .map_err(|e| file_error(out, format!("cannot create the FMU ({e})")))?;
    let mut zip = zip::ZipWriter::new(file);
    let options = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated);
    let mut model = layout.model.clone();
    model.about.generation_date_and_time = Some(generation_date());
    let description = match version {
        FmiVersion::Two => model.to_xml(),
        FmiVersion::Three => model.to_xml_fmi3(),
    };
    let entries: [(String, Vec<u8>); 4] = [
        ("modelDescription.xml".into(), description.into_bytes()),
        (
            format!("{}/{}.so", version.binaries(), config.model_identifier()),
            library,
        ),
        (
            format!("resources/{CONFIG_FILE}"),
            config.to_toml()?.into_bytes(),
        ),
        (
            format!("resources/{VARIABLES_FILE}"),
            layout.variables_text().into_bytes(),
        ),
    ];
    let failed = |e: &dyn std::fmt::Display| file_error(out, format!("writing the FMU: {e}"));
    for (name, bytes) in entries {
        zip.start_file(name, options).map_err(|e| failed(&e))?;
        zip.write_all(&bytes).map_err(|e| failed(&e))?;
    }
    zip.finish().map_err(|e| failed(&e))?;
    crate::whole_file::finish(&partial, out).map_err(|e| failed(&e))
}
