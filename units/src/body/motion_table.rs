//! A prescribed motion from a time table (a basin test's measured motion, a
//! vessel's motion from another code): per degree of freedom a natural cubic
//! spline through the samples, so the position, the velocity and the
//! acceleration the fairleads give the lines are continuous (a linear
//! interpolation would jolt the lines with a jump in velocity at every
//! sample).

use crate::contract::{UnitError, require_finite};
use serde::{Deserialize, Serialize};

/// The table as a scene gives it: the times and, per degree of freedom, the
/// displacement from rest at each (m for surge, sway, heave; rad for roll,
/// pitch, yaw). A degree of freedom left out stays at rest.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MotionTable {
    /// Sample times (s), strictly increasing.
    pub time: Vec<f64>,
    /// Surge (m).
    #[serde(default)]
    pub surge: Option<Vec<f64>>,
    /// Sway (m).
    #[serde(default)]
    pub sway: Option<Vec<f64>>,
    /// Heave (m).
    #[serde(default)]
    pub heave: Option<Vec<f64>>,
    /// Roll (rad).
    #[serde(default)]
    pub roll: Option<Vec<f64>>,
    /// Pitch (rad).
    #[serde(default)]
    pub pitch: Option<Vec<f64>>,
    /// Yaw (rad).
    #[serde(default)]
    pub yaw: Option<Vec<f64>>,
}

impl MotionTable {
    /// The columns in matrix order (surge ... yaw), `None` where left out.
    fn columns(&self) -> [(&'static str, Option<&Vec<f64>>); 6] {
        [
            ("surge", self.surge.as_ref()),
            ("sway", self.sway.as_ref()),
            ("heave", self.heave.as_ref()),
            ("roll", self.roll.as_ref()),
            ("pitch", self.pitch.as_ref()),
            ("yaw", self.yaw.as_ref()),
        ]
    }

    /// Refuses too few samples, times that do not increase, a column of
    /// another length and values that are not finite, naming the key under
    /// `key` (`motion_table`).
    pub fn validate(&self, key: &str) -> Result<(), UnitError> {
        let n = self.time.len();
        if n < 2 {
            return Err(UnitError::parameter(
                &format!("{key}.time"),
                format!("{:?}", self.time),
                "at least two sample times",
            ));
        }
        for (i, t) in self.time.iter().enumerate() {
            require_finite(&format!("{key}.time[{i}]"), *t)?;
            if i > 0 && *t <= self.time[i - 1] {
                return Err(UnitError::parameter(
                    &format!("{key}.time[{i}]"),
                    t,
                    &format!("a time after the previous one ({} s)", self.time[i - 1]),
                ));
            }
        }
        for (name, column) in self.columns() {
            let Some(values) = column else { continue };
            if values.len() != n {
                return Err(UnitError::parameter(
                    &format!("{key}.{name}"),
                    format!("{} values", values.len()),
                    &format!("one value per time ({n})"),
                ));
            }
            for (i, v) in values.iter().enumerate() {
                require_finite(&format!("{key}.{name}[{i}]"), *v)?;
            }
        }
        if self.columns().iter().all(|(_, c)| c.is_none()) {
            return Err(UnitError::parameter(
                key,
                "a table with times only",
                "at least one of surge, sway, heave, roll, pitch, yaw",
            ));
        }
        Ok(())
    }

    /// The splines of a validated table.
    pub(super) fn splines(&self) -> TableMotion {
        let columns = self
            .columns()
            .map(|(_, c)| c.map(|values| Spline::natural(&self.time, values)));
        TableMotion {
            time: self.time.clone(),
            columns,
        }
    }
}

/// The table's splines, ready to evaluate.
#[derive(Clone, Debug)]
pub(super) struct TableMotion {
    time: Vec<f64>,
    columns: [Option<Spline>; 6],
}

impl TableMotion {
    /// The first and the last sample time (s).
    pub(super) fn span(&self) -> (f64, f64) {
        (self.time[0], self.time[self.time.len() - 1])
    }

    /// Refuses a time outside the table (a run longer than its motion):
    /// `what` says which time it is.
    pub(super) fn require_within(&self, t: f64, what: &str) -> Result<(), UnitError> {
        let (first, last) = self.span();
        let slack = 1e-9 * (last - first);
        if t < first - slack || t > last + slack {
            return Err(UnitError::Numerical(format!(
                "the body's motion_table covers {first} s to {last} s; {what} is at {t} s: give samples over the whole run"
            )));
        }
        Ok(())
    }

    /// Per degree of freedom the displacement, velocity and acceleration at
    /// `t` (s), within the table.
    pub(super) fn eval(&self, t: f64) -> [[f64; 3]; 6] {
        let i = match self.time.partition_point(|&ti| ti <= t) {
            0 => 0,
            k => (k - 1).min(self.time.len() - 2),
        };
        self.columns
            .each_ref()
            .map(|c| c.as_ref().map_or([0.0; 3], |s| s.eval(&self.time, i, t)))
    }
}

/// A natural cubic spline: the samples and the second derivatives at them.
#[derive(Clone, Debug)]
struct Spline {
    values: Vec<f64>,
    curvatures: Vec<f64>,
}

impl Spline {
    /// The natural spline (zero second derivative at both ends) through
    /// `values` at `time`, solved by the tridiagonal (Thomas) algorithm.
    fn natural(time: &[f64], values: &[f64]) -> Self {
        let n = time.len();
        let mut curvatures = vec![0.0; n];
        if n > 2 {
            let (mut diag, mut rhs) = (vec![0.0; n], vec![0.0; n]);
            for i in 1..n - 1 {
                let (h0, h1) = (time[i] - time[i - 1], time[i + 1] - time[i]);
                diag[i] = 2.0 * (h0 + h1);
                rhs[i] =
                    6.0 * ((values[i + 1] - values[i]) / h1 - (values[i] - values[i - 1]) / h0);
                if i > 1 {
                    let w = h0 / diag[i - 1];
                    diag[i] -= w * h0;
                    rhs[i] -= w * rhs[i - 1];
                }
            }
            for i in (1..n - 1).rev() {
                let h1 = time[i + 1] - time[i];
                curvatures[i] = (rhs[i] - h1 * curvatures[i + 1]) / diag[i];
            }
        }
        Self {
            values: values.to_vec(),
            curvatures,
        }
    }

    /// Value, first and second derivative at `t` in the interval `i`.
    fn eval(&self, time: &[f64], i: usize, t: f64) -> [f64; 3] {
        let (t0, t1) = (time[i], time[i + 1]);
        let h = t1 - t0;
        let (a, b) = ((t1 - t) / h, (t - t0) / h);
        let (y0, y1) = (self.values[i], self.values[i + 1]);
        let (m0, m1) = (self.curvatures[i], self.curvatures[i + 1]);
        let value = a * y0 + b * y1 + ((a * a * a - a) * m0 + (b * b * b - b) * m1) * h * h / 6.0;
        let slope = (y1 - y0) / h + ((1.0 - 3.0 * a * a) * m0 + (3.0 * b * b - 1.0) * m1) * h / 6.0;
        [value, slope, a * m0 + b * m1]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(time: Vec<f64>, surge: Vec<f64>) -> MotionTable {
        MotionTable {
            time,
            surge: Some(surge),
            sway: None,
            heave: None,
            roll: None,
            pitch: None,
            yaw: None,
        }
    }

    /// A sine sampled over half its period (no curvature at either end, as
    /// the natural spline assumes) is followed at the spline's orders: 4 in
    /// the value, 3 in the velocity, 2 in the acceleration.
    #[test]
    fn a_sampled_sine_is_followed_to_fourth_order() {
        let error = |n: usize| {
            let time: Vec<f64> = (0..=n)
                .map(|i| std::f64::consts::PI * i as f64 / n as f64)
                .collect();
            let values = time.iter().map(|t| t.sin()).collect();
            let motion = table(time, values).splines();
            let mut worst = [0.0f64; 3];
            for k in 0..=997 {
                let t = std::f64::consts::PI * k as f64 / 997.0;
                let [x, v, a] = motion.eval(t)[0];
                let exact = [t.sin(), t.cos(), -t.sin()];
                for (w, (got, want)) in worst.iter_mut().zip([x, v, a].iter().zip(exact)) {
                    *w = w.max((got - want).abs());
                }
            }
            worst
        };
        let (coarse, fine) = (error(20), error(40));
        for (d, order) in [(0, 4.0), (1, 3.0), (2, 2.0)] {
            let measured = (coarse[d] / fine[d]).log2();
            assert!(
                measured > order - 0.3,
                "derivative {d}: order {measured} (errors {} -> {})",
                coarse[d],
                fine[d]
            );
        }
        assert!(coarse[0] < 1e-5 && coarse[2] < 1e-2, "{coarse:?}");
    }

    #[test]
    fn two_samples_are_a_straight_line() {
        let motion = table(vec![1.0, 3.0], vec![2.0, 6.0]).splines();
        let [x, v, a] = motion.eval(2.5)[0];
        assert!((x - 5.0).abs() < 1e-12 && (v - 2.0).abs() < 1e-12 && a == 0.0);
        assert_eq!(motion.eval(2.5)[1], [0.0; 3]);
    }

    #[test]
    fn bad_tables_are_refused_by_key() {
        let cases = [
            (table(vec![0.0], vec![1.0]), "motion_table.time"),
            (
                table(vec![0.0, 0.0], vec![1.0, 2.0]),
                "motion_table.time[1]",
            ),
            (table(vec![0.0, 1.0], vec![1.0]), "motion_table.surge"),
            (
                table(vec![0.0, 1.0], vec![1.0, f64::NAN]),
                "motion_table.surge[1]",
            ),
        ];
        for (t, key) in cases {
            let message = t.validate("motion_table").unwrap_err().to_string();
            assert!(message.contains(&format!("`{key}`")), "{key}: {message}");
        }
        let mut empty = table(vec![0.0, 1.0], vec![0.0, 1.0]);
        empty.surge = None;
        assert!(empty.validate("motion_table").is_err());
        let motion = table(vec![0.0, 10.0], vec![0.0, 1.0]).splines();
        assert!(motion.require_within(10.0, "the step's end").is_ok());
        let late = motion.require_within(10.5, "the step's end").unwrap_err();
        assert!(late.to_string().contains("covers 0 s to 10 s"), "{late}");
    }
}
