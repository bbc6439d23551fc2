//! The coupling master's integration tests, one binary: each module below was a test binary of its own; one
//! binary links the workspace once instead of once per file (`cargo test -p
//! PACKAGE --test integration -- MODULE::` runs one module).

mod adaptive;
mod generic_tolerance;
mod schemes;
mod start_check;
