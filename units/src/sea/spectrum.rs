//! Wave spectra (DNV-RP-C205, sec. 3.5.5): Pierson-Moskowitz and JONSWAP by
//! significant wave height and peak period, discretised into sines of equal
//! frequency spacing with seeded random phases.

use crate::signal::sine::Sine;
use rand::Rng;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// The spectrum's shape.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SpectrumKind {
    /// A fully developed sea: S_PM(w) = 5/16 Hs^2 wp^4 w^-5 exp(-5/4 (w/wp)^-4).
    PiersonMoskowitz,
    /// A developing sea: A_gamma S_PM(w) gamma^exp(-(w - wp)^2 / (2 sigma^2 wp^2)),
    /// A_gamma = 1 - 0.287 ln(gamma), sigma 0.07 below wp and 0.09 above.
    Jonswap,
}

/// A wave spectrum and how it is cut into components.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Spectrum {
    /// The spectrum's family (JONSWAP, Pierson-Moskowitz) and its parameters.
    pub kind: SpectrumKind,
    /// Significant wave height Hs (m).
    pub significant_height: f64,
    /// Peak period Tp (s).
    pub peak_period: f64,
    /// JONSWAP's peak enhancement factor gamma (1 to 7; default 3.3).
    #[serde(default = "default_gamma")]
    pub gamma: f64,
    /// Number of sines (1 to 10 000; default 200).
    #[serde(default = "default_components")]
    pub components: usize,
    /// The band cut into components, as multiples of the peak frequency
    /// (default [0.5, 5]: 99.8 % of a Pierson-Moskowitz sea's variance).
    #[serde(default = "default_band")]
    pub band: [f64; 2],
    /// Seed of the random phases (ChaCha8): the same seed, the same sea.
    #[serde(default = "default_seed")]
    pub seed: u64,
}

fn default_gamma() -> f64 {
    3.3
}

fn default_components() -> usize {
    200
}

fn default_band() -> [f64; 2] {
    [0.5, 5.0]
}

fn default_seed() -> u64 {
    1
}

/// A refusal: the key under the spectrum, the value and what was expected.
pub type Refusal = (&'static str, String, &'static str);

impl Spectrum {
    /// Checks the values' ranges.
    pub fn validate(&self) -> Result<(), Refusal> {
        let positive = |v: f64| v.is_finite() && v > 0.0;
        if !positive(self.significant_height) {
            return Err((
                "significant_height",
                self.significant_height.to_string(),
                "a height > 0 m",
            ));
        }
        if !positive(self.peak_period) {
            return Err((
                "peak_period",
                self.peak_period.to_string(),
                "a period > 0 s",
            ));
        }
        if !(1.0..=7.0).contains(&self.gamma) {
            return Err((
                "gamma",
                self.gamma.to_string(),
                "a peak enhancement factor from 1 to 7",
            ));
        }
        if !(1..=10_000).contains(&self.components) {
            return Err((
                "components",
                self.components.to_string(),
                "a count from 1 to 10 000",
            ));
        }
        let [lo, hi] = self.band;
        if !(positive(lo) && positive(hi) && hi > lo) {
            return Err((
                "band",
                format!("[{lo}, {hi}]"),
                "[low, high] multiples of the peak frequency, 0 < low < high",
            ));
        }
        Ok(())
    }

    /// The peak angular frequency wp = 2 pi / Tp (rad/s).
    pub fn peak_frequency(&self) -> f64 {
        2.0 * PI / self.peak_period
    }

    /// The one-sided spectral density S(w) of the surface elevation (m^2 s/rad).
    pub fn density(&self, omega: f64) -> f64 {
        if omega <= 0.0 {
            return 0.0;
        }
        let wp = self.peak_frequency();
        let hs = self.significant_height;
        let r = wp / omega;
        let pm = 5.0 / 16.0 * hs * hs * wp.powi(4) / omega.powi(5) * (-1.25 * r.powi(4)).exp();
        match self.kind {
            SpectrumKind::PiersonMoskowitz => pm,
            SpectrumKind::Jonswap => {
                let sigma = if omega <= wp { 0.07 } else { 0.09 };
                let shape = (-(omega - wp).powi(2) / (2.0 * sigma * sigma * wp * wp)).exp();
                (1.0 - 0.287 * self.gamma.ln()) * pm * self.gamma.powf(shape)
            }
        }
    }

    /// The frequency resolution dw of the components (rad/s).
    pub fn resolution(&self) -> f64 {
        let wp = self.peak_frequency();
        (self.band[1] - self.band[0]) * wp / self.components as f64
    }

    /// The time after which the components' sum repeats, 2 pi / dw (s): a
    /// run longer than this sees the same sea again.
    pub fn repeat_period(&self) -> f64 {
        2.0 * PI / self.resolution()
    }

    /// The sea as sines: at w_i = (k0 + i) dw, whole multiples of the
    /// resolution from the band's first bin centre (rounded, so the sum
    /// repeats exactly after 2 pi / dw), amplitude sqrt(2 S(w_i) dw), phase
    /// uniform in [0, 2 pi) from the seed.
    pub fn sines(&self) -> Vec<Sine> {
        let dw = self.resolution();
        let first = (self.band[0] * self.peak_frequency() / dw + 0.5)
            .round()
            .max(1.0);
        let mut rng = ChaCha8Rng::seed_from_u64(self.seed);
        (0..self.components)
            .map(|i| {
                let omega = (first + i as f64) * dw;
                Sine {
                    amplitude: (2.0 * self.density(omega) * dw).sqrt(),
                    angular_frequency: omega,
                    phase: rng.random_range(0.0..2.0 * PI),
                    decay: 0.0,
                }
            })
            .collect()
    }
}
