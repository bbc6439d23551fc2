//! The FMU archive: unzipped into a temporary folder, its model description
//! read, its binary for this platform found.

use super::LoadError;
use crate::model_description::{CoSimulation, ModelDescription};
use std::path::{Path, PathBuf};

/// Unzips the FMU into a temporary folder and reads its model description, which
/// must offer co-simulation.
pub(super) fn unpack(
    path: &Path,
    label: &str,
) -> Result<(tempfile::TempDir, ModelDescription, CoSimulation), LoadError> {
    let archive_error = |problem: &'static str| {
        let fmu = label.to_owned();
        move |e: &dyn std::fmt::Display| LoadError::Archive {
            fmu,
            problem,
            reason: e.to_string(),
        }
    };
    let file = std::fs::File::open(path).map_err(|e| archive_error("cannot open")(&e))?;
    let mut archive =
        zip::ZipArchive::new(file).map_err(|e| archive_error("not a readable zip archive")(&e))?;
    let folder = tempfile::Builder::new()
        .prefix("slender-fmu-")
        .tempdir()
        .map_err(|e| archive_error("cannot create a temporary folder")(&e))?;
    archive
        .extract(folder.path())
        .map_err(|e| archive_error("cannot unzip")(&e))?;
    let xml = std::fs::read_to_string(folder.path().join("modelDescription.xml"))
        .map_err(|e| archive_error("no readable modelDescription.xml at the archive root")(&e))?;
    let model = ModelDescription::parse(&xml).map_err(|source| LoadError::Description {
        fmu: label.to_owned(),
        source,
    })?;
    let cs = model
        .co_simulation
        .clone()
        .ok_or_else(|| LoadError::NotCoSimulation {
            fmu: label.to_owned(),
        })?;
    if !model.clocks.is_empty() {
        return Err(LoadError::Clocked {
            fmu: label.to_owned(),
            names: model.clocks.join(", "),
        });
    }
    Ok((folder, model, cs))
}

/// The FMU's binary for 64-bit Linux (`linux64`, FMI 3.0: `x86_64-linux`),
/// or an error saying which platforms it has.
pub(super) fn binary_for_this_platform(
    folder: &Path,
    identifier: &str,
    fmi3: bool,
    label: &str,
) -> Result<PathBuf, LoadError> {
    let platform = if fmi3 { "x86_64-linux" } else { "linux64" };
    let binary = folder
        .join("binaries")
        .join(platform)
        .join(format!("{identifier}.so"));
    if !binary.exists() {
        let platforms: Vec<String> = std::fs::read_dir(folder.join("binaries"))
            .map(|d| {
                d.filter_map(|e| e.ok())
                    .map(|e| e.file_name().to_string_lossy().into_owned())
                    .collect()
            })
            .unwrap_or_default();
        return Err(LoadError::NoBinary {
            fmu: label.to_owned(),
            identifier: format!("{platform}/{identifier}"),
            found: if platforms.is_empty() {
                "no binaries at all (source-only FMUs are not compiled by slender)".to_owned()
            } else {
                format!("binaries for {}", platforms.join(", "))
            },
        });
    }
    Ok(binary)
}
