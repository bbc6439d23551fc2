//! What stops a study or a scene command of the library, typed so that the
//! binary tells bad input (exit code 2) from a failure on the way (exit
//! code 1) without reading the words: the scene (its file, its line or the
//! change, its key), what was asked of it (a flag's value), or a file of
//! results that could not be read or written.

use slender_scene::SceneError;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// Why a study or a scene command of the library stopped.
#[derive(Debug, Error)]
pub enum AppError {
    /// The scene does not load: its file, line or change, and key.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// What was asked does not apply to the scene (a section or quantity it
    /// does not have, a key path, a study larger than its bound, a folder
    /// that holds another study): the message names the flag.
    #[error("{0}")]
    Asked(String),
    /// Ctrl-C stopped the study before its last run: nothing is fitted or
    /// tabled from part of a study; its finished runs are kept for the same
    /// command to resume.
    #[error(
        "interrupted (Ctrl-C) after {finished} of {total} runs: nothing is fitted or tabled from part of a study; the finished runs are kept, and the same command resumes from them"
    )]
    Interrupted {
        /// The runs that finished.
        finished: usize,
        /// The runs the study makes.
        total: usize,
    },
    /// A file or folder could not be read or written.
    #[error("{}: {message}", path.display())]
    Files {
        /// The file or folder.
        path: PathBuf,
        /// What the system said.
        message: String,
    },
}

impl AppError {
    /// A file or folder at `path` that could not be read or written.
    pub fn files(path: &Path, error: impl std::fmt::Display) -> AppError {
        AppError::Files {
            path: path.to_owned(),
            message: error.to_string(),
        }
    }

    /// Whether the error is the input's (the scene's or the command line's),
    /// not a failure on the way.
    pub fn is_input(&self) -> bool {
        matches!(self, AppError::Scene(_) | AppError::Asked(_))
    }
}

/// A refusal in words is about what was asked.
impl From<String> for AppError {
    fn from(message: String) -> AppError {
        AppError::Asked(message)
    }
}

impl From<&str> for AppError {
    fn from(message: &str) -> AppError {
        AppError::Asked(message.to_owned())
    }
}

#[cfg(test)]
mod tests {
    use super::AppError;
    use std::path::Path;

    #[test]
    fn a_file_not_written_is_a_failure_and_the_rest_bad_input() {
        let full = AppError::files(
            Path::new("results/s/runs/a.toml"),
            "No space left on device",
        );
        assert!(!full.is_input());
        assert_eq!(
            full.to_string(),
            "results/s/runs/a.toml: No space left on device"
        );
        assert!(AppError::from("--section x: no such section").is_input());
    }
}
