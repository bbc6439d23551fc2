//! SSP archives (`.ssp`): a zip with `SystemStructure.ssd` at its root and the
//! FMUs under `resources/`.

use super::{SspError, SystemStructure};
use crate::export::PackageError;
use crate::model_description::ModelDescription;
use std::io::{Read, Write as _};
use std::path::{Path, PathBuf};

/// The description's name inside an archive.
pub const DESCRIPTION: &str = "SystemStructure.ssd";

fn file_error(path: &Path, problem: String) -> PackageError {
    PackageError::File {
        path: path.display().to_string(),
        problem,
    }
}

/// Writes `structure` and the FMUs (`(name in the archive, file)`) to `out`.
pub fn package(
    structure: &SystemStructure,
    fmus: &[(String, PathBuf)],
    out: &Path,
) -> Result<(), PackageError> {
    let (file, partial) = crate::whole_file::create(out)
        .map_err(|e| file_error(out, format!("cannot create the SSP ({e})")))?;
    let failed = |e: &dyn std::fmt::Display| file_error(out, format!("writing the SSP: {e}"));
    let mut zip = zip::ZipWriter::new(file);
    let options = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated);
    zip.start_file(DESCRIPTION, options)
        .map_err(|e| failed(&e))?;
    zip.write_all(structure.to_xml().as_bytes())
        .map_err(|e| failed(&e))?;
    // FMUs are zips already: stored as they are.
    let stored =
        zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Stored);
    for (name, path) in fmus {
        let bytes = std::fs::read(path)
            .map_err(|e| file_error(path, format!("cannot read the FMU ({e})")))?;
        zip.start_file(name, stored).map_err(|e| failed(&e))?;
        zip.write_all(&bytes).map_err(|e| failed(&e))?;
    }
    zip.finish().map_err(|e| failed(&e))?;
    crate::whole_file::finish(&partial, out).map_err(|e| failed(&e))
}

/// Why an SSP cannot be opened.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum OpenError {
    /// The archive or its folder cannot be read or unpacked.
    #[error("{path}: {problem}")]
    File {
        /// The file.
        path: String,
        /// What went wrong.
        problem: String,
    },
    /// The system structure description does not read.
    #[error("{path}: {source}")]
    Description {
        /// The archive.
        path: String,
        /// Where and why.
        source: SspError,
    },
}

/// Unpacks the archive `path` into `dir` and reads its description; an `.ssd`
/// file is read where it is (its components relative to its folder). Returns
/// the structure and the folder its `source`s are relative to.
pub fn open(path: &Path, dir: &Path) -> Result<(SystemStructure, PathBuf), OpenError> {
    let fail = |problem: String| OpenError::File {
        path: path.display().to_string(),
        problem,
    };
    let root = if path.extension().is_some_and(|e| e == "ssd") {
        // Absolute: the scene made of it resolves its units' files from the
        // `.ssd`'s own folder, which would join a relative folder twice.
        let folder = path.parent().unwrap_or(Path::new("."));
        std::path::absolute(folder).map_err(|e| fail(format!("no folder ({e})")))?
    } else {
        let file = std::fs::File::open(path).map_err(|e| fail(format!("cannot open ({e})")))?;
        let mut zip = zip::ZipArchive::new(file).map_err(|e| fail(format!("not a zip ({e})")))?;
        zip.extract(dir)
            .map_err(|e| fail(format!("cannot unpack ({e})")))?;
        dir.to_owned()
    };
    let description = if path.extension().is_some_and(|e| e == "ssd") {
        path.to_owned()
    } else {
        root.join(DESCRIPTION)
    };
    let xml = std::fs::read_to_string(&description)
        .map_err(|e| fail(format!("no readable {DESCRIPTION} ({e})")))?;
    let structure = SystemStructure::parse(&xml).map_err(|source| OpenError::Description {
        path: path.display().to_string(),
        source,
    })?;
    Ok((structure, root))
}

/// An FMU's model description, when it has a readable one.
pub fn fmu_description(fmu: &Path) -> Option<ModelDescription> {
    let file = std::fs::File::open(fmu).ok()?;
    let mut zip = zip::ZipArchive::new(file).ok()?;
    let mut xml = String::new();
    zip.by_name("modelDescription.xml")
        .ok()?
        .read_to_string(&mut xml)
        .ok()?;
    ModelDescription::parse(&xml).ok()
}
