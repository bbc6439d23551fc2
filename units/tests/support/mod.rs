//! What the units' own integration tests share: the published figures, seed
//! 004's beams, the S-lay pipe, a seed 002 section made from its text. Each
//! test binary compiles this module whole and uses part of it.
#![allow(dead_code)]

pub(crate) mod beams;
pub(crate) mod slay;

use slender_units::nonlinear::{NonlinearParams, NonlinearSection};
use slender_units::{Driver, Time};
use std::path::Path;

/// The published figures (`tests/reference/published.toml` at the
/// workspace's root), with their sources.
pub(crate) fn published() -> toml::Table {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/reference/published.toml");
    let text = std::fs::read_to_string(path).expect("reference file");
    text.parse().expect("reference parses")
}

/// The nonlinear section of `text`, initialised at t = 0.
pub(crate) fn section(text: &str) -> Driver<NonlinearSection> {
    let params: NonlinearParams = toml::from_str(text).expect("parameters parse");
    let mut driver = Driver::new(NonlinearSection::new(params).expect("valid parameters"));
    driver.initialize(Time::ZERO).expect("initialize");
    driver
}
