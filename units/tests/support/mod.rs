//! What the units' own integration tests share: the published figures, seed
//! 004's beams, the S-lay pipe, a seed 002 section made from its text, random states. Each
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

/// A deterministic pseudo-random vector of `n` entries in [-scale, scale]
/// (a linear congruential generator: the same states on every machine).
pub(crate) fn random_vector(n: usize, seed: u64, scale: f64) -> nalgebra::DVector<f64> {
    let next = |x: u64| {
        x.wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407)
    };
    let mut x = next(seed);
    nalgebra::DVector::from_fn(n, |_, _| {
        x = next(x);
        scale * (2.0 * ((x >> 11) as f64 / (1u64 << 53) as f64) - 1.0)
    })
}

/// The nonlinear section of `text`, initialised at t = 0.
pub(crate) fn section(text: &str) -> Driver<NonlinearSection> {
    let params: NonlinearParams = toml::from_str(text).expect("parameters parse");
    let mut driver = Driver::new(NonlinearSection::new(params).expect("valid parameters"));
    driver.initialize(Time::ZERO).expect("initialize");
    driver
}

/// Root mean square of `x`.
pub(crate) fn rms(x: impl Iterator<Item = f64>) -> f64 {
    let (sum, n) = x.fold((0.0, 0usize), |(s, n), v| (s + v * v, n + 1));
    (sum / n.max(1) as f64).sqrt()
}
