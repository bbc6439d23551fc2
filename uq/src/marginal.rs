//! The distributions of uncertain inputs: each maps a design's unit coordinate
//! to the input (its inverse CDF) and the input to the standard variable of
//! its polynomial family (the isoprobabilistic transform): uniform to Legendre,
//! normal and lognormal to Hermite, a truncated normal through its CDF to
//! Legendre.

use crate::UqError;
use crate::basis::Family;
use serde::Deserialize;
use statrs::distribution::{ContinuousCDF, Normal};

/// One input's distribution (SI units of the input).
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Marginal {
    /// Uniform on [low, high].
    Uniform {
        /// Lower bound.
        low: f64,
        /// Upper bound.
        high: f64,
    },
    /// Normal.
    Normal {
        /// Mean.
        mean: f64,
        /// Standard deviation (> 0).
        sd: f64,
    },
    /// ln X is normal with mean `mu` and standard deviation `sigma`.
    Lognormal {
        /// Mean of ln X.
        mu: f64,
        /// Standard deviation of ln X (> 0).
        sigma: f64,
    },
    /// A normal (`mean`, `sd`) restricted to [low, high].
    TruncatedNormal {
        /// Mean of the normal before truncation.
        mean: f64,
        /// Its standard deviation (> 0).
        sd: f64,
        /// Lower bound.
        low: f64,
        /// Upper bound.
        high: f64,
    },
}

fn standard() -> Normal {
    // The standard normal's parameters are valid: the constructor cannot fail.
    Normal::standard()
}

impl Marginal {
    /// Checks the parameters; the error names the distribution.
    pub fn validate(&self) -> Result<(), UqError> {
        let ok = match *self {
            Marginal::Uniform { low, high } => low.is_finite() && high.is_finite() && low < high,
            Marginal::Normal { mean, sd } => mean.is_finite() && sd.is_finite() && sd > 0.0,
            Marginal::Lognormal { mu, sigma } => mu.is_finite() && sigma.is_finite() && sigma > 0.0,
            Marginal::TruncatedNormal {
                mean,
                sd,
                low,
                high,
            } => [mean, sd, low, high].iter().all(|v| v.is_finite()) && sd > 0.0 && low < high,
        };
        if ok {
            Ok(())
        } else {
            Err(UqError::input(
                format!("{self:?}"),
                "expected finite parameters, a positive spread and low < high",
            ))
        }
    }

    /// The polynomial family of the input's standard variable.
    pub fn family(&self) -> Family {
        match self {
            Marginal::Normal { .. } | Marginal::Lognormal { .. } => Family::Hermite,
            Marginal::Uniform { .. } | Marginal::TruncatedNormal { .. } => Family::Legendre,
        }
    }

    /// The input at probability `u` in (0, 1) (the inverse CDF).
    pub fn from_unit(&self, u: f64) -> f64 {
        let z = || standard().inverse_cdf(u);
        match *self {
            Marginal::Uniform { low, high } => low + u * (high - low),
            Marginal::Normal { mean, sd } => mean + sd * z(),
            Marginal::Lognormal { mu, sigma } => (mu + sigma * z()).exp(),
            Marginal::TruncatedNormal { mean, sd, .. } => {
                let (a, b) = self.truncation();
                mean + sd * standard().inverse_cdf(a + u * (b - a))
            }
        }
    }

    /// The standard normal's CDF at a truncated normal's bounds ((0, 1)
    /// for the others: no truncation).
    fn truncation(&self) -> (f64, f64) {
        match *self {
            Marginal::TruncatedNormal {
                mean,
                sd,
                low,
                high,
            } => {
                let n = standard();
                (n.cdf((low - mean) / sd), n.cdf((high - mean) / sd))
            }
            _ => (0.0, 1.0),
        }
    }

    /// The standard variable of [`Marginal::family`] for the input `x`.
    pub fn to_standard(&self, x: f64) -> f64 {
        match *self {
            Marginal::Uniform { low, high } => 2.0 * (x - low) / (high - low) - 1.0,
            Marginal::Normal { mean, sd } => (x - mean) / sd,
            Marginal::Lognormal { mu, sigma } => (x.ln() - mu) / sigma,
            Marginal::TruncatedNormal { mean, sd, .. } => {
                let (a, b) = self.truncation();
                let u = (standard().cdf((x - mean) / sd) - a) / (b - a);
                2.0 * u - 1.0
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverse_cdfs_and_standard_variables_agree() {
        let marginals = [
            Marginal::Uniform {
                low: 2.0,
                high: 6.0,
            },
            Marginal::Normal {
                mean: 1.0,
                sd: 0.015,
            },
            Marginal::Lognormal {
                mu: 0.1,
                sigma: 0.3,
            },
            Marginal::TruncatedNormal {
                mean: 0.0,
                sd: 10800.0,
                low: -20000.0,
                high: 30000.0,
            },
        ];
        for m in &marginals {
            m.validate().unwrap();
            for u in [0.01, 0.3, 0.5, 0.77, 0.99] {
                let x = m.from_unit(u);
                let xi = m.to_standard(x);
                // The standard variable at probability u: 2u - 1 for Legendre,
                // the standard normal quantile for Hermite.
                let want = match m.family() {
                    Family::Legendre => 2.0 * u - 1.0,
                    Family::Hermite => standard().inverse_cdf(u),
                };
                assert!(
                    (xi - want).abs() < 1e-9,
                    "{m:?} u = {u}: {xi} against {want}"
                );
            }
        }
        // The median of a normal is its mean; a truncated normal stays inside.
        assert!((marginals[1].from_unit(0.5) - 1.0).abs() < 1e-12);
        let t = &marginals[3];
        assert!(t.from_unit(1e-9) >= -20000.0 && t.from_unit(1.0 - 1e-9) <= 30000.0);
        assert!(Marginal::Normal { mean: 0.0, sd: 0.0 }.validate().is_err());
        assert!(
            Marginal::Uniform {
                low: 1.0,
                high: 1.0
            }
            .validate()
            .is_err()
        );
    }
}
