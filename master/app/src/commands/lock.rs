//! One writer per results folder: two `slender run --out o` at once spliced
//! their rows into one another's files, both exiting 0 (issue 27). A command
//! that writes into a folder holds `.slender.lock` there (made with
//! create-new, holding its process id) until it ends; a second one is refused
//! with the holder's id. A lock left by a process that no longer runs (a kill)
//! is taken over, where the system can tell (Linux: `/proc/<pid>`), and so is
//! one that holds no process id and was last written more than
//! `UNREADABLE_AFTER` ago (a garbage file; a fresh empty one is a holder that
//! has not written its id yet).

use super::CliError;
use std::io::Write;
use std::path::{Path, PathBuf};

/// The lock's file name in a results folder.
const LOCK: &str = ".slender.lock";

/// How old a lock without a process id must be to be taken over.
const UNREADABLE_AFTER: std::time::Duration = std::time::Duration::from_secs(10);

/// Whether the lock at `path` holding `holder` was left behind: its process
/// is gone, or it holds no process id and has not been written for a while.
fn stale(path: &Path, holder: &str) -> bool {
    match holder.trim().parse::<u32>() {
        Ok(pid) => !runs(pid),
        Err(_) => std::fs::metadata(path)
            .and_then(|m| m.modified())
            .ok()
            .and_then(|t| t.elapsed().ok())
            .is_some_and(|age| age > UNREADABLE_AFTER),
    }
}

/// A held results folder; the lock goes when it is dropped.
#[must_use = "the folder is locked only while this lives"]
pub(super) struct FolderLock {
    path: PathBuf,
}

impl Drop for FolderLock {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

/// Whether process `pid` still runs: false only where the system says so.
fn runs(pid: u32) -> bool {
    let proc = Path::new("/proc");
    !proc.is_dir() || proc.join(pid.to_string()).exists()
}

/// Takes the lock of results folder `dir` (which exists).
pub(super) fn lock(dir: &Path) -> Result<FolderLock, CliError> {
    let path = dir.join(LOCK);
    for _ in 0..2 {
        match std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&path)
        {
            Ok(mut file) => {
                let _ = write!(file, "{}", std::process::id());
                return Ok(FolderLock { path });
            }
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
                let holder = std::fs::read_to_string(&path).unwrap_or_default();
                match stale(&path, &holder) {
                    true => {
                        // Left behind: take it over.
                        let _ = std::fs::remove_file(&path);
                    }
                    false => {
                        return Err(CliError::input(format!(
                            "{}: another slender (process {}) is writing its results here; wait for it or choose another --out (if none runs, remove {})",
                            dir.display(),
                            holder.trim(),
                            path.display()
                        )));
                    }
                }
            }
            Err(e) => {
                return Err(CliError::failure(format!(
                    "{}: cannot lock the results folder ({e})",
                    path.display()
                )));
            }
        }
    }
    Err(CliError::failure(format!(
        "{}: cannot take over a stale lock",
        path.display()
    )))
}
