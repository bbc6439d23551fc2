//! Simulation time as an integer count of nanoseconds.
//!
//! Synchronisation points, sub-steps and rollback comparisons use [`Time`] so that
//! `t + h` after a thousand steps is still exactly a multiple of `h`. Physics kernels
//! convert to seconds (`f64`) with [`Time::as_secs`].

use serde::{Deserialize, Serialize};
use std::fmt;
use std::ops::{Add, AddAssign, Mul, Sub};

/// A point in simulation time, or a duration, in integer nanoseconds.
#[derive(
    Copy, Clone, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize,
)]
pub struct Time(i64);

const NANOS_PER_SEC: f64 = 1e9;

impl Time {
    /// t = 0.
    pub const ZERO: Time = Time(0);

    /// The latest representable time, about 9.22e9 s (292 years); the earliest is
    /// its negative.
    pub const MAX: Time = Time(i64::MAX);

    /// `self / n` when it is a whole number of nanoseconds, else `None` (a
    /// step split into `n` equal sub-steps).
    pub fn split(self, n: u32) -> Option<Time> {
        let n = i64::from(n);
        (n > 0 && self.0 % n == 0).then(|| Time(self.0 / n))
    }

    /// `self + other`, or `None` beyond the representable range.
    pub fn checked_add(self, other: Time) -> Option<Time> {
        self.0.checked_add(other.0).map(Time)
    }

    /// From a whole number of nanoseconds.
    pub const fn from_nanos(nanos: i64) -> Time {
        Time(nanos)
    }

    /// From seconds, rounded to the nearest nanosecond; `None` for NaN, infinities and
    /// values beyond about 292 years.
    pub fn from_secs(seconds: f64) -> Option<Time> {
        let nanos = (seconds * NANOS_PER_SEC).round();
        (nanos.is_finite() && nanos.abs() < i64::MAX as f64).then_some(Time(nanos as i64))
    }

    /// Whole nanoseconds.
    pub const fn as_nanos(self) -> i64 {
        self.0
    }

    /// Seconds, for physics kernels and output.
    pub fn as_secs(self) -> f64 {
        self.0 as f64 / NANOS_PER_SEC
    }
}

impl Add for Time {
    type Output = Time;
    fn add(self, rhs: Time) -> Time {
        Time(self.0 + rhs.0)
    }
}

impl AddAssign for Time {
    fn add_assign(&mut self, rhs: Time) {
        self.0 += rhs.0;
    }
}

impl Sub for Time {
    type Output = Time;
    fn sub(self, rhs: Time) -> Time {
        Time(self.0 - rhs.0)
    }
}

impl Mul<i64> for Time {
    type Output = Time;
    fn mul(self, rhs: i64) -> Time {
        Time(self.0 * rhs)
    }
}

impl fmt::Display for Time {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} s", self.as_secs())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_thousand_steps_of_ten_ms_land_exactly_on_ten_seconds() {
        let h = Time::from_secs(0.01).unwrap();
        let mut t = Time::ZERO;
        for _ in 0..1000 {
            t += h;
        }
        assert_eq!(t, Time::from_secs(10.0).unwrap());
    }

    #[test]
    fn non_finite_seconds_are_refused() {
        assert!(Time::from_secs(f64::NAN).is_none());
        assert!(Time::from_secs(f64::INFINITY).is_none());
        assert!(Time::from_secs(1e12).is_none());
    }
}
