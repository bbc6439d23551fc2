//! What the command-line tests share: running the `slender` binary from the
//! repository root and reading its output. Each test file uses some of it.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Runs `slender` with `args` from the repository root.
pub(crate) fn slender(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_slender"))
        .args(args)
        .current_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("../.."))
        .output()
        .expect("the slender binary runs")
}

/// Output bytes as text.
pub(crate) fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// An example scene with some text replaced, written into `dir`.
pub(crate) fn variant_in(dir: &Path, example: &str, from: &[(&str, &str)]) -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut text = std::fs::read_to_string(root.join(example)).unwrap();
    for (a, b) in from {
        assert!(text.contains(a), "{a}");
        text = text.replace(a, b);
    }
    let path = dir.join(Path::new(example).file_name().unwrap());
    std::fs::write(&path, text).unwrap();
    path
}

/// A run's summary.json.
pub(crate) fn summary(out: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap()
}
