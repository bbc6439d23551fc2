//! The FMU library an export packages: checked before it is packaged, and
//! found next to the running executable.

use super::{PackageError, file_error};
use std::path::Path;

/// Checks that `binary` is an ELF shared library carrying the FMI 2.0
/// co-simulation entry points (as `libslender_fmu.so` does), so that a wrong
/// `--binary` is refused instead of packaged.
pub fn check_binary(binary: &Path) -> Result<(), PackageError> {
    let bytes = std::fs::read(binary)
        .map_err(|e| file_error(binary, format!("cannot read the FMU library ({e})")))?;
    if !bytes.starts_with(b"\x7fELF") {
        return Err(file_error(
            binary,
            "not a shared library (no ELF header); expected libslender_fmu.so".into(),
        ));
    }
    for symbol in ["fmi2Instantiate", "fmi2DoStep", "fmi2GetReal"] {
        if !bytes.windows(symbol.len()).any(|w| w == symbol.as_bytes()) {
            return Err(file_error(
                binary,
                format!(
                    "a shared library without the FMI entry point `{symbol}`; expected libslender_fmu.so"
                ),
            ));
        }
    }
    Ok(())
}

/// The FMU library next to the running executable (`target/<profile>/`), where
/// `cargo build -p slender-fmu` puts it.
pub fn default_binary() -> Option<std::path::PathBuf> {
    let exe = std::env::current_exe().ok()?;
    let dir = exe.parent()?;
    [dir, dir.parent()?]
        .iter()
        .map(|d| d.join("libslender_fmu.so"))
        .find(|p| p.exists())
}
