//! What the command-line tests share: running the `slender` binary from the
//! repository root and reading its output.

use std::path::Path;
use std::process::{Command, Output};

/// Runs `slender` with `args` from the repository root.
pub fn slender(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_slender"))
        .args(args)
        .current_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("../.."))
        .output()
        .expect("the slender binary runs")
}

/// Output bytes as text.
pub fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}
