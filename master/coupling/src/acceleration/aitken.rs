//! Aitken's dynamic relaxation.

use super::Accelerator;

/// Aitken's dynamic relaxation: the factor is updated from two successive residuals,
/// `w_k = -w_{k-1} r_{k-1}.(r_k - r_{k-1}) / |r_k - r_{k-1}|^2`, and restarts at
/// `initial` every step.
pub struct Aitken {
    initial: f64,
    factor: f64,
    first: bool,
    previous_residual: Vec<f64>,
}

impl Aitken {
    /// Aitken's relaxation of `n` coupled values, its factor starting at
    /// `initial` each step.
    pub fn new(initial: f64, n: usize) -> Aitken {
        Aitken {
            initial,
            factor: initial,
            first: true,
            previous_residual: vec![0.0; n],
        }
    }
}

impl Accelerator for Aitken {
    fn start_step(&mut self) {
        self.factor = self.initial;
        self.first = true;
    }

    fn next(&mut self, x: &[f64], gx: &[f64], next: &mut [f64]) {
        if !self.first {
            let (mut num, mut den) = (0.0, 0.0);
            for ((&x, &g), &rp) in x.iter().zip(gx).zip(&self.previous_residual) {
                let dr = (g - x) - rp;
                num += rp * dr;
                den += dr * dr;
            }
            if den > 0.0 && num.is_finite() {
                self.factor = -self.factor * num / den;
            }
        }
        self.first = false;
        for (((n, &x), &g), rp) in next
            .iter_mut()
            .zip(x)
            .zip(gx)
            .zip(&mut self.previous_residual)
        {
            *rp = g - x;
            *n = x + self.factor * (g - x);
        }
    }
}
