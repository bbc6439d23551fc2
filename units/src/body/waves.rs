//! A body in waves: first-order wave excitation from a force RAO table, or a
//! prescribed motion through motion RAOs, on the sea states slender makes
//! (the same `waves` table as a 3D line's: a spectrum's seeded components or
//! sines, a heading, the dispersion on a water depth, a fade-in).
//!
//! Each wave component `a sin(omega t + phi - k . x)` gives each degree of
//! freedom a sine `a |X| sin(omega t + phi - k . x_ref + arg X)`, `X` the
//! table's complex value at the component's frequency and the sea's heading
//! (its real and imaginary parts interpolated linearly in frequency and in
//! heading; the end frequencies' values held beyond the table), `x_ref` the
//! reference point at rest. The sines are made once, when the body is built.

use crate::contract::{UnitError, require_finite};
use crate::line3d::params::Waves;
use crate::line3d::waves::wavenumber;
use crate::signal::sine::Sine;
use serde::{Deserialize, Serialize};

/// A response amplitude operator per degree of freedom.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RaoTable {
    /// Wave angular frequencies (rad/s), increasing.
    pub frequencies: Vec<f64>,
    /// Wave headings (deg, the direction the waves travel towards,
    /// counter-clockwise from +x), increasing.
    pub headings_deg: Vec<f64>,
    /// Per degree of freedom (6), per heading, per frequency: the response
    /// per metre of wave amplitude (a force table N/m and N m/m; a motion
    /// table m/m and rad/m).
    pub amplitude: Vec<Vec<Vec<f64>>>,
    /// The same shape (deg): the response's phase lead over the wave
    /// elevation at the reference point.
    pub phase_deg: Vec<Vec<Vec<f64>>>,
}

impl RaoTable {
    /// Refuses a table of the wrong shape or order, naming `key`.
    pub fn validate(&self, key: &str) -> Result<(), UnitError> {
        let increasing = |v: &[f64]| v.windows(2).all(|w| w[1] > w[0]);
        for (name, values) in [
            ("frequencies", &self.frequencies),
            ("headings_deg", &self.headings_deg),
        ] {
            if values.is_empty() || !increasing(values) {
                return Err(UnitError::parameter(
                    &format!("{key}.{name}"),
                    format!("{values:?}"),
                    "one value or more, increasing",
                ));
            }
            for v in values.iter() {
                require_finite(&format!("{key}.{name}"), *v)?;
            }
        }
        let (headings, frequencies) = (self.headings_deg.len(), self.frequencies.len());
        for (name, table) in [
            ("amplitude", &self.amplitude),
            ("phase_deg", &self.phase_deg),
        ] {
            let shaped = table.len() == 6
                && table.iter().all(|dof| {
                    dof.len() == headings && dof.iter().all(|row| row.len() == frequencies)
                });
            if !shaped {
                return Err(UnitError::parameter(
                    &format!("{key}.{name}"),
                    "of another shape",
                    &format!(
                        "6 degrees of freedom x {headings} headings x {frequencies} frequencies"
                    ),
                ));
            }
            for v in table.iter().flatten().flatten() {
                require_finite(&format!("{key}.{name}"), *v)?;
            }
        }
        Ok(())
    }

    /// The complex value (re, im) of degree of freedom `dof` at `omega`
    /// (rad/s) and `heading` (deg, within the table's headings).
    fn at(&self, dof: usize, omega: f64, heading: f64) -> (f64, f64) {
        let (h0, h1, wh) = bracket(&self.headings_deg, heading);
        let (f0, f1, wf) = bracket(&self.frequencies, omega);
        let value = |h: usize, f: usize| {
            let (a, p) = (
                self.amplitude[dof][h][f],
                self.phase_deg[dof][h][f].to_radians(),
            );
            (a * p.cos(), a * p.sin())
        };
        let mix =
            |x: (f64, f64), y: (f64, f64), w: f64| (x.0 + w * (y.0 - x.0), x.1 + w * (y.1 - x.1));
        let low = mix(value(h0, f0), value(h0, f1), wf);
        let high = mix(value(h1, f0), value(h1, f1), wf);
        mix(low, high, wh)
    }

    /// Refuses a sea whose heading (deg) the table does not cover.
    pub fn check_heading(&self, key: &str, heading: f64) -> Result<(), UnitError> {
        let (first, last) = (
            self.headings_deg[0],
            self.headings_deg[self.headings_deg.len() - 1],
        );
        let tolerance = 1e-9 * heading.abs().max(1.0);
        if heading < first - tolerance || heading > last + tolerance {
            return Err(UnitError::parameter(
                &format!("{key}.headings_deg"),
                format!("{:?}", self.headings_deg),
                &format!("headings that cover the waves' heading_deg = {heading}"),
            ));
        }
        Ok(())
    }

    /// The sines per degree of freedom of the response to `waves` at the
    /// reference point `reference` (m) at rest.
    pub fn sines(&self, waves: &Waves, reference: [f64; 3]) -> [Vec<Sine>; 6] {
        let depth = if waves.water_depth > 0.0 {
            waves.water_depth
        } else {
            f64::INFINITY
        };
        let components = match &waves.spectrum {
            Some(spectrum) => spectrum.sines(),
            None => waves.sines.clone(),
        };
        let beta = waves.heading_deg.to_radians();
        let along = reference[0] * beta.cos() + reference[1] * beta.sin();
        std::array::from_fn(|dof| {
            components
                .iter()
                .map(|c| {
                    let (re, im) = self.at(dof, c.angular_frequency, waves.heading_deg);
                    let k = wavenumber(c.angular_frequency, depth);
                    Sine {
                        amplitude: c.amplitude * re.hypot(im),
                        angular_frequency: c.angular_frequency,
                        phase: c.phase - k * along + im.atan2(re),
                        decay: c.decay,
                    }
                })
                .collect()
        })
    }
}

/// The indices either side of `x` in the increasing `grid` and the weight
/// of the upper one; the end values held beyond it.
fn bracket(grid: &[f64], x: f64) -> (usize, usize, f64) {
    let last = grid.len() - 1;
    if last == 0 || x <= grid[0] {
        return (0, 0, 0.0);
    }
    if x >= grid[last] {
        return (last, last, 0.0);
    }
    let i = grid.partition_point(|&g| g <= x) - 1;
    (i, i + 1, (x - grid[i]) / (grid[i + 1] - grid[i]))
}
