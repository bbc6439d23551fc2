//! Current profiles: horizontal water velocity (along +x) against height z above
//! the seabed.

use crate::contract::{UnitError, require_finite};
use serde::{Deserialize, Serialize};

/// A current profile.
#[derive(Clone, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum CurrentProfile {
    /// No current.
    #[default]
    None,
    /// Linear shear from `seabed` (m/s, at z = 0) to `surface` (m/s, at the water
    /// depth); constant beyond.
    Linear {
        /// Speed at the seabed (m/s, z = 0).
        seabed: f64,
        /// Speed at the surface (m/s, z = water depth).
        surface: f64,
    },
    /// Piecewise linear through (z, speed) points, z increasing (m, m/s); constant
    /// beyond the ends.
    Table {
        /// Heights above the seabed (m), increasing.
        z: Vec<f64>,
        /// Current speed at each height (m/s).
        speed: Vec<f64>,
    },
}

impl CurrentProfile {
    /// Checks the profile.
    pub fn validate(&self) -> Result<(), UnitError> {
        match self {
            CurrentProfile::None => Ok(()),
            CurrentProfile::Linear { seabed, surface } => {
                require_finite("current.seabed", *seabed)?;
                require_finite("current.surface", *surface)
            }
            CurrentProfile::Table { z, speed } => {
                if z.is_empty() || z.len() != speed.len() {
                    return Err(UnitError::parameter(
                        "current.z",
                        format!("{} heights, {} speeds", z.len(), speed.len()),
                        "expected as many heights as speeds, at least one",
                    ));
                }
                for v in z.iter().chain(speed) {
                    require_finite("current", *v)?;
                }
                if z.windows(2).any(|w| w[1] <= w[0]) {
                    return Err(UnitError::parameter(
                        "current.z",
                        format!("{z:?}"),
                        "expected strictly increasing heights",
                    ));
                }
                Ok(())
            }
        }
    }

    /// Current speed (m/s) at height z (m) above the seabed, for water depth `depth`.
    pub fn speed(&self, z: f64, depth: f64) -> f64 {
        match self {
            CurrentProfile::None => 0.0,
            CurrentProfile::Linear { seabed, surface } => {
                let s = (z / depth).clamp(0.0, 1.0);
                seabed + s * (surface - seabed)
            }
            CurrentProfile::Table { z: zs, speed } => {
                crate::numerics::table::interpolate(zs, speed, z)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_and_tabulated_profiles_interpolate_and_clamp() {
        let lin = CurrentProfile::Linear {
            seabed: 0.0,
            surface: 0.5,
        };
        assert_eq!(lin.speed(600.0, 1200.0), 0.25);
        assert_eq!(lin.speed(1300.0, 1200.0), 0.5);
        let tab = CurrentProfile::Table {
            z: vec![0.0, 100.0, 200.0],
            speed: vec![0.0, 1.0, 0.0],
        };
        assert_eq!(tab.speed(50.0, 200.0), 0.5);
        assert_eq!(tab.speed(150.0, 200.0), 0.5);
        assert_eq!(tab.speed(-5.0, 200.0), 0.0);
        assert!(
            CurrentProfile::Table {
                z: vec![1.0, 0.0],
                speed: vec![0.0, 0.0]
            }
            .validate()
            .is_err()
        );
    }
}
