//! The units' own integration tests, in one binary: each module was a
//! test binary of its own, and one binary links the workspace once instead of
//! once per file. One module: `cargo test --release -p slender-units --test
//! integration -- MODULE::`.

mod artefacts;
mod beam;
mod beam_dynamic_contact;
mod beam_tension;
mod cable_modes;
mod moment_recovery;
mod nonlinear_dynamics;
mod nonlinear_hard;
mod nonlinear_slay;
mod nonlinear_statics;
mod reduced_bases;
mod reduced_capacity;
mod reduced_frame;
mod reduced_lrbf;
mod support;
