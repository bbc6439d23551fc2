//! Contact surfaces y >= f(x, t): flat, tilted, a smooth bump, a set of rollers and
//! a tabulated profile, optionally moving vertically.

use crate::contract::{UnitError, require_finite, require_positive};
use serde::Deserialize;

/// The shape of a contact surface (m).
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Shape {
    /// f = height.
    Flat { height: f64 },
    /// f = height + slope x.
    Tilted { height: f64, slope: f64 },
    /// f = height + bump_height (1 + cos(pi (x - center) / half_width)) / 2 within
    /// half_width of the center, else height.
    Bump {
        height: f64,
        center: f64,
        half_width: f64,
        bump_height: f64,
    },
    /// Circular rollers of `radius` with tops at `height` (or, per roller, at
    /// `tops`: a stinger's curve), centred at `positions`; no surface between them.
    Rollers {
        positions: Vec<f64>,
        radius: f64,
        #[serde(default)]
        height: f64,
        #[serde(default)]
        tops: Vec<f64>,
    },
    /// Piecewise linear through (x, y), constant beyond the ends.
    Table { x: Vec<f64>, y: Vec<f64> },
}

/// Vertical motion of the whole surface.
#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Motion {
    #[default]
    None,
    /// amplitude sin(angular_frequency t).
    Sine {
        amplitude: f64,
        angular_frequency: f64,
    },
    /// A sum of sines (a vessel's heave as wave components).
    Sines {
        sines: Vec<crate::beam::boundary::Sine>,
    },
}

/// A surface: shape plus motion.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Surface {
    pub shape: Shape,
    #[serde(default)]
    pub motion: Motion,
}

impl Surface {
    /// Checks the parameters.
    pub fn validate(&self) -> Result<(), UnitError> {
        match &self.shape {
            Shape::Flat { height } => require_finite("surface.height", *height)?,
            Shape::Tilted { height, slope } => {
                require_finite("surface.height", *height)?;
                require_finite("surface.slope", *slope)?;
            }
            Shape::Bump {
                height,
                center,
                half_width,
                bump_height,
            } => {
                require_finite("surface.height", *height)?;
                require_finite("surface.center", *center)?;
                require_positive("surface.half_width", *half_width)?;
                require_finite("surface.bump_height", *bump_height)?;
            }
            Shape::Rollers {
                positions,
                radius,
                height,
                tops,
            } => {
                require_positive("surface.radius", *radius)?;
                require_finite("surface.height", *height)?;
                if !tops.is_empty() && tops.len() != positions.len() {
                    return Err(UnitError::parameter(
                        "surface.tops",
                        format!("{} tops for {} rollers", tops.len(), positions.len()),
                        "one top height per roller, or none",
                    ));
                }
                for top in tops {
                    require_finite("surface.tops", *top)?;
                }
                if positions.is_empty() {
                    return Err(UnitError::parameter(
                        "surface.positions",
                        "[]",
                        "expected at least one roller",
                    ));
                }
                for p in positions {
                    require_finite("surface.positions", *p)?;
                }
            }
            Shape::Table { x, y } => {
                if x.is_empty() || x.len() != y.len() {
                    return Err(UnitError::parameter(
                        "surface.x",
                        format!("{} x, {} y", x.len(), y.len()),
                        "expected as many x as y, at least one",
                    ));
                }
                for v in x.iter().chain(y) {
                    require_finite("surface", *v)?;
                }
                if x.windows(2).any(|w| w[1] <= w[0]) {
                    return Err(UnitError::parameter(
                        "surface.x",
                        format!("{x:?}"),
                        "expected strictly increasing x",
                    ));
                }
            }
        }
        match &self.motion {
            Motion::None => {}
            &Motion::Sine {
                amplitude,
                angular_frequency,
            } => {
                require_finite("surface.motion.amplitude", amplitude)?;
                require_finite("surface.motion.angular_frequency", angular_frequency)?;
            }
            Motion::Sines { sines } => {
                for s in sines {
                    require_finite("surface.motion.sines.amplitude", s.amplitude)?;
                    require_finite(
                        "surface.motion.sines.angular_frequency",
                        s.angular_frequency,
                    )?;
                    require_finite("surface.motion.sines.phase", s.phase)?;
                }
            }
        }
        Ok(())
    }

    /// Surface height f(x, t) (m) and its rate df/dt (m/s); `None` where there is no
    /// surface (between rollers).
    pub fn at(&self, x: f64, t: f64) -> Option<(f64, f64)> {
        let (dz, rate) = match &self.motion {
            Motion::None => (0.0, 0.0),
            &Motion::Sine {
                amplitude,
                angular_frequency,
            } => (
                amplitude * (angular_frequency * t).sin(),
                amplitude * angular_frequency * (angular_frequency * t).cos(),
            ),
            Motion::Sines { sines } => sines.iter().fold((0.0, 0.0), |(z, r), s| {
                let [v, dv, _] = s.eval(t);
                (z + v, r + dv)
            }),
        };
        let f = match &self.shape {
            Shape::Flat { height } => *height,
            Shape::Tilted { height, slope } => height + slope * x,
            Shape::Bump {
                height,
                center,
                half_width,
                bump_height,
            } => {
                let u = (x - center) / half_width;
                if u.abs() < 1.0 {
                    height + bump_height * 0.5 * (1.0 + (std::f64::consts::PI * u).cos())
                } else {
                    *height
                }
            }
            Shape::Rollers {
                positions,
                radius,
                height,
                tops,
            } => positions
                .iter()
                .enumerate()
                .filter(|&(_, &c)| (x - c).abs() < *radius)
                .map(|(i, &c)| {
                    let top = tops.get(i).unwrap_or(height);
                    top - radius + (radius * radius - (x - c).powi(2)).sqrt()
                })
                .fold(None, |best: Option<f64>, v| {
                    Some(best.map_or(v, |b| b.max(v)))
                })?,
            Shape::Table { x: xs, y } => {
                let last = xs.len() - 1;
                if x <= xs[0] {
                    y[0]
                } else if x >= xs[last] {
                    y[last]
                } else {
                    let i = xs.partition_point(|&v| v <= x) - 1;
                    y[i] + (y[i + 1] - y[i]) * (x - xs[i]) / (xs[i + 1] - xs[i])
                }
            }
        };
        Some((f + dz, rate))
    }
}
