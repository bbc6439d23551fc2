//! The coupling master's integration tests, in one binary: each module was a
//! test binary of its own, and one binary links the workspace once instead of
//! once per file. One module: `cargo test --release -p slender-coupling --test
//! integration -- MODULE::`.

mod adaptive;
mod generic_tolerance;
mod schemes;
mod start_check;
