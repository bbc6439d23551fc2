//! The CSV of a study's runs (`slender uq`, `slender cases`) that grows as
//! they finish, so that an interrupted study resumes from what it has, and is
//! rewritten in index order at the end.

use super::CliError;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The open file and its header; rows are appended from the worker threads.
pub(super) struct RunsCsv {
    path: PathBuf,
    header: String,
    file: Mutex<std::fs::File>,
}

impl RunsCsv {
    /// Starts `path` afresh with `header` and the rows already `done`
    /// (resumed or merged), so an interruption from here on loses nothing.
    pub(super) fn start(path: &Path, header: &str, done: &str) -> Result<RunsCsv, CliError> {
        let fail = |e: std::io::Error| CliError::failure(format!("{}: {e}", path.display()));
        std::fs::write(path, format!("{header}{done}")).map_err(fail)?;
        let file = std::fs::OpenOptions::new()
            .append(true)
            .open(path)
            .map_err(fail)?;
        Ok(RunsCsv {
            path: path.to_owned(),
            header: header.to_owned(),
            file: Mutex::new(file),
        })
    }

    /// Appends one finished run's row. A row that cannot be written is run
    /// again on resume, so the error is not the study's.
    pub(super) fn append(&self, row: &str) {
        let mut file = self.file.lock().unwrap_or_else(|e| e.into_inner());
        let _ = file.write_all(row.as_bytes());
    }

    /// Rewrites the file whole with every row, in index order.
    pub(super) fn finish(self, rows: &str) -> Result<(), CliError> {
        let text = format!("{}{rows}", self.header);
        slender_app::whole::write(&self.path, text)
            .map_err(|e| CliError::failure(format!("{}: {e}", self.path.display())))
    }
}

/// Writes `<stem>.json` (the report) and `<stem>.md` (its Markdown) in
/// `dir`; their paths.
pub(super) fn write_report_files(
    dir: &Path,
    stem: &str,
    report: &impl serde::Serialize,
    markdown: &str,
) -> Result<[PathBuf; 2], CliError> {
    let json = serde_json::to_string_pretty(report).map_err(CliError::failure)?;
    Ok([
        super::write_in(dir, &format!("{stem}.json"), json)?,
        super::write_in(dir, &format!("{stem}.md"), markdown.to_owned())?,
    ])
}
