//! The command line's and the app's own integration tests, in one binary: each module was a
//! test binary of its own, and one binary links the workspace once instead of
//! once per file. One module: `cargo test --release -p slender-app --test
//! integration -- MODULE::`.

mod cases_cli;
mod cli;
mod cli_realtime;
mod cli_results;
mod cli_resume;
mod cli_scene_keys;
mod common;
mod envelopes;
mod figures;
mod full_disk;
mod issue_11_defects;
mod readme_commands;
mod scene_read_once;
mod span_cli;
mod study_engine;
mod study_interrupted;
mod tutorials;
