//! Axes with the ticks of [`super::ticks`]: ranges padded for log and linear
//! scales and the key points plotters draws.

use super::ticks;
use plotters::coord::combinators::{BindKeyPoints, LogCoord, WithKeyPoints};
use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint};
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use std::ops::Range;

/// A linear axis ticked at given values (plotters' own `WithKeyPoints` over
/// f64 takes no label formatter).
pub struct Ticked {
    inner: RangedCoordf64,
    ticks: Vec<f64>,
}

impl Ranged for Ticked {
    type ValueType = f64;
    type FormatOption = DefaultFormatting;

    fn range(&self) -> Range<f64> {
        self.inner.range()
    }

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        self.inner.map(value, limit)
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            Vec::new()
        } else {
            self.ticks.clone()
        }
    }
}

/// A linear axis over `lo..hi` with about `target` 1-2-5 ticks, and its step
/// (for [`ticks::linear_label`]).
pub fn linear_axis(lo: f64, hi: f64, target: usize) -> (Ticked, f64) {
    let (ticks, step) = ticks::linear_ticks(lo, hi, target);
    (
        Ticked {
            inner: (lo..hi).into(),
            ticks,
        },
        step,
    )
}

/// The bounds of the positive finite values, widened for a log axis (by 1.5,
/// or 4 % of the decades shown) (a decade either side of one value; 1e-12 to 1 when there is none).
pub fn positive_range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|x| x.is_finite() && *x > 0.0)
        .fold((f64::INFINITY, 0.0f64), |(a, b), x| (a.min(x), b.max(x)));
    match (lo.is_finite(), hi > lo) {
        (true, true) => {
            let pad = (hi / lo).powf(0.04).max(1.5);
            (lo / pad, hi * pad)
        }
        (true, false) => (lo / 10.0, hi * 10.0),
        _ => (1e-12, 1.0),
    }
}

/// A log axis over `lo..hi` ticked at most `most` times (decades, else 1-2-5).
pub fn log_axis(lo: f64, hi: f64, most: usize) -> WithKeyPoints<LogCoord<f64>> {
    (lo..hi)
        .log_scale()
        .with_key_points(ticks::log_ticks(lo, hi, most))
}

/// A categorical axis of `n` bands, ticked at their centres (band k spans k..k+1).
pub fn band_axis(n: usize) -> Ticked {
    Ticked {
        inner: (0.0..n.max(1) as f64).into(),
        ticks: (0..n).map(|k| k as f64 + 0.5).collect(),
    }
}

/// The band whose centre a tick of [`band_axis`] is at.
pub fn band_of(v: f64) -> usize {
    (v - 0.5).round().max(0.0) as usize
}

/// How many labels of `chars` characters fit along `pixels` of axis.
pub fn fitting(pixels: i32, chars: usize) -> usize {
    (pixels / (super::labels::CHAR_WIDTH * chars.max(3) as i32 + 16)).max(2) as usize
}
