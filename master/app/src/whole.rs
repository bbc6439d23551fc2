//! Results files written whole: each is made under a temporary name beside
//! its place (`NAME.partial`) and renamed when complete, so a results file
//! that is there is complete. A run killed mid-write (SIGKILL, power loss)
//! leaves a `.partial` file, never a torn `summary.json` or a CSV cut
//! mid-row that looks like a finished one.

use std::io;
use std::path::{Path, PathBuf};

/// Where `path` is written until it is complete.
pub fn partial(path: &Path) -> PathBuf {
    let mut name = path.file_name().unwrap_or_default().to_os_string();
    name.push(".partial");
    path.with_file_name(name)
}

/// Writes `contents` to `path` whole: to its partial name, then renamed.
pub fn write(path: &Path, contents: impl AsRef<[u8]>) -> io::Result<()> {
    let temporary = partial(path);
    std::fs::write(&temporary, contents)?;
    std::fs::rename(&temporary, path)
}

/// A finished file that could not be renamed into its place.
#[derive(Debug, thiserror::Error)]
#[error("{}: {source}", path.display())]
pub struct RenameError {
    /// The file.
    pub path: PathBuf,
    /// Why it could not be renamed into place.
    pub source: io::Error,
}

/// Makes `path` by `make`, which writes the file it is given (its partial
/// name), then renames it; a partial file left by a failed `make` is removed.
pub fn through<E>(path: &Path, make: impl FnOnce(&Path) -> Result<(), E>) -> Result<(), E>
where
    E: From<RenameError>,
{
    let temporary = partial(path);
    match make(&temporary) {
        Ok(()) => std::fs::rename(&temporary, path).map_err(|source| {
            E::from(RenameError {
                path: path.to_owned(),
                source,
            })
        }),
        Err(e) => {
            let _ = std::fs::remove_file(&temporary);
            Err(e)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_appears_only_when_complete() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("summary.json");
        assert_eq!(partial(&path), dir.path().join("summary.json.partial"));
        write(&path, "{}").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "{}");
        assert!(!partial(&path).exists());
        let failed: Result<(), crate::plot::PlotError> = through(&dir.path().join("a.svg"), |p| {
            std::fs::write(p, "<svg").unwrap();
            Err(crate::plot::PlotError::new(p, &"drawing failed"))
        });
        assert!(failed.is_err());
        assert!(!dir.path().join("a.svg").exists());
        assert!(!dir.path().join("a.svg.partial").exists());
    }
}
