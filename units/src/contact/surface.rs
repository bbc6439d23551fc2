//! Contact surfaces y >= f(x, t): flat, tilted, a smooth bump, a set of rollers and
//! a tabulated profile, optionally moving vertically.

use crate::contract::{UnitError, require_finite, require_non_negative, require_positive};
use crate::signal::sine::{Sine, smoothstep};
use serde::{Deserialize, Serialize};

/// The shape of a contact surface (m).
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Shape {
    /// f = height.
    Flat {
        /// Height of the surface (m).
        height: f64,
    },
    /// f = height + slope x.
    Tilted {
        /// Height at x = 0 (m).
        height: f64,
        /// Rise per unit x (m/m).
        slope: f64,
    },
    /// f = height + bump_height (1 + cos(pi (x - center) / half_width)) / 2 within
    /// half_width of the center, else height.
    Bump {
        /// Height away from the bump (m).
        height: f64,
        /// Where the bump is highest (m).
        center: f64,
        /// Half the bump's width (m), > 0.
        half_width: f64,
        /// Height of the bump above `height` (m).
        bump_height: f64,
    },
    /// Circular rollers of `radius` with tops at `height` (or, per roller, at
    /// `tops`: a stinger's curve), centred at `positions`; no surface between them.
    Rollers {
        /// The rollers' centres along x (m).
        positions: Vec<f64>,
        /// Radius of every roller (m), > 0.
        radius: f64,
        /// Height of the rollers' tops when `tops` is empty (m).
        #[serde(default)]
        height: f64,
        /// Height of each roller's top (m); empty: all at `height`.
        #[serde(default)]
        tops: Vec<f64>,
    },
    /// Piecewise linear through (x, y), constant beyond the ends.
    Table {
        /// Abscissae (m), increasing.
        x: Vec<f64>,
        /// Heights of the surface there (m).
        y: Vec<f64>,
    },
}

/// Vertical motion of the whole surface.
#[derive(Clone, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Motion {
    /// The surface stays where it is.
    #[default]
    None,
    /// amplitude sin(angular_frequency t).
    Sine {
        /// Amplitude of the vertical motion (m).
        amplitude: f64,
        /// Its angular frequency (rad/s).
        angular_frequency: f64,
    },
    /// A sum of sines (a vessel's heave as wave components).
    Sines {
        /// The components (m, rad/s, rad).
        sines: Vec<Sine>,
        /// The sines grow from nothing over this time (s, quintic smoothstep
        /// as an end's `fade_in`); 0: at full amplitude from the start.
        #[serde(default)]
        fade_in: f64,
    },
    /// Rollers moving with their vessel: heave (m, sums of sines) and pitch
    /// (rad, counter-clockwise, sums of sines) about `pivot` ([x, z], m), each
    /// roller's centre carried rigidly (rollers only: a circle stays a circle).
    Vessel {
        /// The vessel's heave (m).
        #[serde(default)]
        heave: Vec<Sine>,
        /// The vessel's pitch (rad, counter-clockwise).
        #[serde(default)]
        pitch: Vec<Sine>,
        /// The point the vessel pitches about ([x, z], m).
        pivot: [f64; 2],
        /// Heave and pitch grow from nothing over this time (s, quintic
        /// smoothstep as an end's `fade_in`, so a pipe's end moved by the same
        /// vessel fades alike); 0: at full amplitude from the start.
        #[serde(default)]
        fade_in: f64,
    },
}

/// Where a surface is at one time: its pitch (cos, sin) about the vessel's
/// pivot when it pitches, and its heave (m).
struct Pose {
    turn: Option<(f64, f64, [f64; 2])>,
    dz: f64,
}

/// The sum of `sines` at t (value, rate), faded in over `fade_in` (s).
fn sum(sines: &[Sine], fade_in: f64, t: f64) -> (f64, f64) {
    let (v, rate) = sines.iter().fold((0.0, 0.0), |(v, r), s| {
        let [a, da, _] = s.eval(t);
        (v + a, r + da)
    });
    let [r, dr, _] = smoothstep(t, fade_in);
    (r * v, dr * v + r * rate)
}

/// Each named value finite; the first that is not is refused by its key.
fn all_finite(values: &[(&str, f64)]) -> Result<(), UnitError> {
    values
        .iter()
        .try_for_each(|&(key, value)| require_finite(key, value))
}

/// A surface: shape plus motion.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Surface {
    /// Where the surface is when it has not moved.
    pub shape: Shape,
    /// How the whole surface moves.
    #[serde(default)]
    pub motion: Motion,
}

impl Surface {
    /// Checks the parameters.
    pub fn validate(&self) -> Result<(), UnitError> {
        match &self.shape {
            Shape::Flat { height } => require_finite("surface.height", *height)?,
            Shape::Tilted { height, slope } => {
                all_finite(&[("surface.height", *height), ("surface.slope", *slope)])?;
            }
            Shape::Bump {
                height,
                center,
                half_width,
                bump_height,
            } => {
                all_finite(&[
                    ("surface.height", *height),
                    ("surface.center", *center),
                    ("surface.bump_height", *bump_height),
                ])?;
                require_positive("surface.half_width", *half_width)?;
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
        self.validate_motion()
    }

    /// Checks the motion (pitch carries rollers only).
    fn validate_motion(&self) -> Result<(), UnitError> {
        match &self.motion {
            Motion::None => {}
            &Motion::Sine {
                amplitude,
                angular_frequency,
            } => {
                require_finite("surface.motion.amplitude", amplitude)?;
                require_finite("surface.motion.angular_frequency", angular_frequency)?;
            }
            Motion::Sines { sines, fade_in } => {
                finite_sines("surface.motion.sines", sines)?;
                require_non_negative("surface.motion.fade_in", *fade_in)?;
            }
            Motion::Vessel {
                heave,
                pitch,
                pivot,
                fade_in,
            } => {
                if !matches!(self.shape, Shape::Rollers { .. }) {
                    return Err(UnitError::parameter(
                        "surface.motion.kind",
                        "vessel",
                        "a vessel's pitch carries rollers only (a circle turned about its vessel stays a circle); move other surfaces by `sines`",
                    ));
                }
                finite_sines("surface.motion.heave", heave)?;
                finite_sines("surface.motion.pitch", pitch)?;
                require_finite("surface.motion.pivot", pivot[0])?;
                require_finite("surface.motion.pivot", pivot[1])?;
                require_non_negative("surface.motion.fade_in", *fade_in)?;
            }
        }
        Ok(())
    }

    /// Roller `i`'s top at time t: its centre's x and the height of its top (m);
    /// `None` when the surface has no roller `i`.
    pub fn roller(&self, i: usize, t: f64) -> Option<(f64, f64)> {
        self.roller_in(i, &self.pose(t))
    }

    /// Every roller's top at time t (centre's x, top's height; m), in order, the
    /// vessel's motion evaluated once.
    pub fn rollers(&self, t: f64) -> impl Iterator<Item = (f64, f64)> + '_ {
        let count = match &self.shape {
            Shape::Rollers { positions, .. } => positions.len(),
            _ => 0,
        };
        let pose = self.pose(t);
        (0..count).filter_map(move |i| self.roller_in(i, &pose))
    }

    /// The surface's rigid motion at time t.
    fn pose(&self, t: f64) -> Pose {
        match &self.motion {
            Motion::Vessel {
                pitch,
                pivot,
                fade_in,
                ..
            } => {
                let theta = sum(pitch, *fade_in, t).0;
                Pose {
                    turn: Some((theta.cos(), theta.sin(), *pivot)),
                    dz: self.heave(t).0,
                }
            }
            _ => Pose {
                turn: None,
                dz: self.heave(t).0,
            },
        }
    }

    /// Roller `i`'s top with the surface at `pose`.
    fn roller_in(&self, i: usize, pose: &Pose) -> Option<(f64, f64)> {
        let Shape::Rollers {
            positions,
            radius,
            height,
            tops,
        } = &self.shape
        else {
            return None;
        };
        let (x, top) = (*positions.get(i)?, *tops.get(i).unwrap_or(height));
        Some(match pose.turn {
            Some((c, s, pivot)) => {
                let (rx, rz) = (x - pivot[0], top - radius - pivot[1]);
                let centre = [
                    pivot[0] + c * rx - s * rz,
                    pivot[1] + s * rx + c * rz + pose.dz,
                ];
                (centre[0], centre[1] + radius)
            }
            None => (x, top + pose.dz),
        })
    }

    /// Vertical motion of the whole surface (m) and its rate (m/s) (not pitch).
    fn heave(&self, t: f64) -> (f64, f64) {
        match &self.motion {
            Motion::None => (0.0, 0.0),
            &Motion::Sine {
                amplitude,
                angular_frequency,
            } => (
                amplitude * (angular_frequency * t).sin(),
                amplitude * angular_frequency * (angular_frequency * t).cos(),
            ),
            Motion::Sines { sines, fade_in } => sum(sines, *fade_in, t),
            Motion::Vessel { heave, fade_in, .. } => sum(heave, *fade_in, t),
        }
    }

    /// Height (m) over x of the rollers at time t; `None` between them.
    fn rollers_at(&self, x: f64, t: f64, radius: f64) -> Option<f64> {
        self.rollers(t)
            .filter(|&(c, _)| (x - c).abs() < radius)
            .map(|(c, top)| top - radius + (radius * radius - (x - c).powi(2)).sqrt())
            .fold(None, |best: Option<f64>, v| {
                Some(best.map_or(v, |b| b.max(v)))
            })
    }

    /// Surface height f(x, t) (m) and its rate df/dt (m/s); `None` where there is no
    /// surface (between rollers).
    pub fn at(&self, x: f64, t: f64) -> Option<(f64, f64)> {
        if let &Shape::Rollers { radius, .. } = &self.shape {
            let f = self.rollers_at(x, t, radius)?;
            // Rollers carried by a pitching vessel also move sideways: the
            // height's rate at a fixed x by central differences.
            let rate = match &self.motion {
                Motion::Vessel { .. } => {
                    let dt = 1e-6;
                    match (
                        self.rollers_at(x, t + dt, radius),
                        self.rollers_at(x, t - dt, radius),
                    ) {
                        (Some(a), Some(b)) => (a - b) / (2.0 * dt),
                        _ => 0.0,
                    }
                }
                _ => self.heave(t).1,
            };
            return Some((f, rate));
        }
        let (dz, rate) = self.heave(t);
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
            Shape::Rollers { .. } => return None,
            Shape::Table { x: xs, y } => crate::numerics::table::interpolate(xs, y, x),
        };
        Some((f + dz, rate))
    }
}

fn finite_sines(key: &str, sines: &[Sine]) -> Result<(), UnitError> {
    for (i, s) in sines.iter().enumerate() {
        s.check(&format!("{key}.{i}"))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stinger(motion: &str) -> Surface {
        let text = format!(
            "shape = {{ kind = \"rollers\", positions = [10.0, 20.0], radius = 0.5, tops = [1.0, 2.0] }}\nmotion = {motion}"
        );
        let s: Surface = toml::from_str(&text).unwrap();
        s.validate().unwrap();
        s
    }

    #[test]
    fn a_pitching_vessel_carries_its_rollers_round_its_pivot() {
        // A constant pitch of 0.1 rad (sin(pi / 2)) about (30, 0), 2 m of heave.
        let s = stinger(
            "{ kind = \"vessel\", pivot = [30.0, 0.0], heave = [{ amplitude = 2.0, phase = 1.5707963267948966 }], pitch = [{ amplitude = 0.1, phase = 1.5707963267948966 }] }",
        );
        let (c, sn) = (0.1f64.cos(), 0.1f64.sin());
        for (i, (x, top)) in [(10.0, 1.0), (20.0, 2.0)].into_iter().enumerate() {
            let (rx, rz) = (x - 30.0, top - 0.5);
            let want = (30.0 + c * rx - sn * rz, sn * rx + c * rz + 2.0 + 0.5);
            let (xr, zr) = s.roller(i, 3.0).unwrap();
            assert!((xr - want.0).abs() < 1e-12 && (zr - want.1).abs() < 1e-12);
            // The surface's height over the roller's top is the top, at rest.
            let (f, rate) = s.at(xr, 3.0).unwrap();
            assert!((f - zr).abs() < 1e-12 && rate.abs() < 1e-6, "{f} {rate}");
        }
        assert!(s.roller(2, 0.0).is_none());
    }

    #[test]
    fn a_heaving_surface_rises_at_the_heave_rate() {
        let s = stinger(
            "{ kind = \"vessel\", pivot = [0.0, 0.0], heave = [{ amplitude = 1.5, angular_frequency = 0.6 }] }",
        );
        let t = 1.3;
        let (_, rate) = s.at(10.0, t).unwrap();
        assert!((rate - 1.5 * 0.6 * (0.6 * t).cos()).abs() < 1e-6);
        let same =
            stinger("{ kind = \"sines\", sines = [{ amplitude = 1.5, angular_frequency = 0.6 }] }");
        assert_eq!(s.at(10.2, t).unwrap().0, same.at(10.2, t).unwrap().0);
        // Pitch is refused on a continuous surface.
        let flat: Surface = toml::from_str(
            "shape = { kind = \"flat\", height = 0.0 }\nmotion = { kind = \"vessel\", pivot = [0.0, 0.0] }",
        )
        .unwrap();
        assert!(flat.validate().is_err());
    }

    #[test]
    fn a_faded_vessel_starts_at_rest_and_moves_as_its_end_motion() {
        let motion = "heave = [{ amplitude = 1.5, angular_frequency = 0.6 }], pitch = [{ amplitude = 0.02, angular_frequency = 0.5 }]";
        let faded = stinger(&format!(
            "{{ kind = \"vessel\", pivot = [30.0, 0.0], {motion}, fade_in = 10.0 }}"
        ));
        let full = stinger(&format!(
            "{{ kind = \"vessel\", pivot = [30.0, 0.0], {motion} }}"
        ));
        // At rest at the start: where it was drawn, not moving.
        assert_eq!(faded.roller(0, 0.0), Some((10.0, 1.0)));
        let (x, top) = faded.roller(1, 0.0).unwrap();
        assert!((x - 20.0).abs() < 1e-12 && (top - 2.0).abs() < 1e-12);
        assert!(faded.at(20.0, 0.0).unwrap().1.abs() < 1e-9);
        // Half way, the quintic smoothstep's half of the motion; from the
        // fade's end on, the unfaded motion itself.
        let heave = |s: &Surface, t| s.heave(t);
        let (half, _) = heave(&faded, 5.0);
        assert!((half - 0.5 * heave(&full, 5.0).0).abs() < 1e-12);
        for t in [10.5, 17.3] {
            assert_eq!(faded.roller(1, t), full.roller(1, t));
            assert_eq!(faded.at(20.0, t), full.at(20.0, t));
        }
        // The faded heave's rate is its derivative.
        let (h, t) = (1e-6, 3.7);
        let slope = (heave(&faded, t + h).0 - heave(&faded, t - h).0) / (2.0 * h);
        assert!((heave(&faded, t).1 - slope).abs() < 1e-8);
        // A fade-in that is not a duration is refused by its key.
        let bad: Surface = toml::from_str(
            "shape = { kind = \"flat\", height = 0.0 }\nmotion = { kind = \"sines\", sines = [], fade_in = -1.0 }",
        )
        .unwrap();
        let e = bad.validate().unwrap_err().to_string();
        assert!(e.contains("surface.motion.fade_in"), "{e}");
    }
}
