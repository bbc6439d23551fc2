//! Constant relaxation.

use super::Accelerator;

/// `x + factor (G(x) - x)`; factor 1 is plain fixed-point iteration.
pub struct Constant {
    /// The relaxation factor.
    pub factor: f64,
}

impl Accelerator for Constant {
    fn start_step(&mut self) {}

    fn next(&mut self, x: &[f64], gx: &[f64], next: &mut [f64]) {
        for ((n, &x), &g) in next.iter_mut().zip(x).zip(gx) {
            *n = x + self.factor * (g - x);
        }
    }
}
