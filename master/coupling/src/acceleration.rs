//! Fixed-point acceleration of the interface iteration.
//!
//! The master iterates `x -> G(x)`, where `x` are the values of the torn
//! connections used as inputs and `G(x)` the values the sweep returns. Vectors here
//! are scaled by each connection's tolerance, so forces in N and velocities in m/s
//! weigh alike (a residual of 1 is exactly "at tolerance").

use crate::settings::Acceleration;

/// Proposes the next iterate from the last one and what the sweep made of it.
pub trait Accelerator: Send {
    /// Called at the start of every synchronisation step.
    fn start_step(&mut self);
    /// `x`: iterate used; `gx`: sweep result `G(x)`; writes the next iterate.
    fn next(&mut self, x: &[f64], gx: &[f64], next: &mut [f64]);
}

/// Builds the accelerator of a fixed-point scheme for `n` torn values.
pub fn accelerator(setting: &Acceleration, n: usize) -> Box<dyn Accelerator> {
    match *setting {
        Acceleration::None | Acceleration::Newton { .. } => Box::new(Constant { factor: 1.0 }),
        Acceleration::Constant { factor } => Box::new(Constant { factor }),
        Acceleration::Aitken { initial_factor } => Box::new(Aitken::new(initial_factor, n)),
        Acceleration::IqnIls {
            initial_factor,
            reuse_steps,
        } => Box::new(IqnIls::new(initial_factor, reuse_steps, n)),
    }
}

/// `x + factor (G(x) - x)`; factor 1 is plain fixed-point iteration.
pub struct Constant {
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

/// One secant pair of IQN-ILS: differences of residuals (`v`) and of sweep results
/// (`w`) between two iterations, tagged with the step they come from.
struct Secant {
    step: u64,
    v: Vec<f64>,
    w: Vec<f64>,
}

/// Interface quasi-Newton with an inverse Jacobian from least squares (IQN-ILS,
/// Degroote et al. 2009; Anderson mixing): `x_{k+1} = G(x_k) + W a` with `a`
/// minimising `|V a + r_k|`, columns of `V` and `W` being the differences of
/// residuals and of sweep results. Nearly dependent columns are filtered (QR1).
pub struct IqnIls {
    initial: f64,
    reuse_steps: u64,
    step: u64,
    first_in_step: bool,
    /// Newest first; at most `n` pairs are kept.
    secants: Vec<Secant>,
    spare: Vec<Secant>,
    previous_residual: Vec<f64>,
    previous_gx: Vec<f64>,
    q: Vec<Vec<f64>>,
    r: Vec<f64>,
    kept: Vec<usize>,
    residual: Vec<f64>,
    coefficients: Vec<f64>,
}

impl IqnIls {
    pub fn new(initial: f64, reuse_steps: u32, n: usize) -> IqnIls {
        let columns = n.max(1);
        IqnIls {
            initial,
            reuse_steps: u64::from(reuse_steps),
            step: 0,
            first_in_step: true,
            secants: Vec::with_capacity(columns + 1),
            spare: (0..=columns)
                .map(|_| Secant {
                    step: 0,
                    v: vec![0.0; n],
                    w: vec![0.0; n],
                })
                .collect(),
            previous_residual: vec![0.0; n],
            previous_gx: vec![0.0; n],
            q: (0..columns).map(|_| vec![0.0; n]).collect(),
            r: vec![0.0; columns * columns],
            kept: Vec::with_capacity(columns),
            residual: vec![0.0; n],
            coefficients: vec![0.0; columns],
        }
    }

    fn forget_older_than(&mut self, oldest_step: u64) {
        let mut i = 0;
        while i < self.secants.len() {
            if self.secants[i].step < oldest_step {
                let s = self.secants.remove(i);
                self.spare.push(s);
            } else {
                i += 1;
            }
        }
    }

    fn push_secant(&mut self, gx: &[f64]) {
        let n = gx.len();
        let mut s = self
            .spare
            .pop()
            .or_else(|| self.secants.pop())
            .unwrap_or_else(|| Secant {
                step: 0,
                v: vec![0.0; n],
                w: vec![0.0; n],
            });
        s.step = self.step;
        for (v, (r, rp)) in
            s.v.iter_mut()
                .zip(self.residual.iter().zip(&self.previous_residual))
        {
            *v = r - rp;
        }
        for (w, (g, gp)) in s.w.iter_mut().zip(gx.iter().zip(&self.previous_gx)) {
            *w = g - gp;
        }
        self.secants.insert(0, s);
        if self.secants.len() > self.q.len()
            && let Some(old) = self.secants.pop()
        {
            self.spare.push(old);
        }
    }

    /// Least squares `min |V a + r|` by modified Gram-Schmidt on the secants, newest
    /// first, dropping a column whose new direction is below 1e-10 of its length.
    fn solve_least_squares(&mut self) {
        let n = self.residual.len();
        let m = self.q.len();
        self.kept.clear();
        for (j, s) in self.secants.iter().enumerate() {
            let col = self.kept.len();
            let q = &mut self.q[col];
            q.copy_from_slice(&s.v);
            let norm0 = q.iter().map(|a| a * a).sum::<f64>().sqrt();
            for (i, _) in self.kept.iter().enumerate() {
                let (head, tail) = self.q.split_at_mut(col);
                let qi = &head[i];
                let dot: f64 = qi.iter().zip(tail[0].iter()).map(|(a, b)| a * b).sum();
                self.r[i * m + col] = dot;
                for (a, b) in tail[0].iter_mut().zip(qi) {
                    *a -= dot * b;
                }
            }
            let q = &mut self.q[col];
            let norm = q.iter().map(|a| a * a).sum::<f64>().sqrt();
            if norm > 1e-10 * norm0 && norm > 0.0 {
                q.iter_mut().for_each(|a| *a /= norm);
                self.r[col * m + col] = norm;
                self.kept.push(j);
            }
        }
        // R a = -Q^T r, back substitution.
        let k = self.kept.len();
        for i in (0..k).rev() {
            let mut rhs: f64 = -(0..n).map(|l| self.q[i][l] * self.residual[l]).sum::<f64>();
            for j in i + 1..k {
                rhs -= self.r[i * m + j] * self.coefficients[j];
            }
            self.coefficients[i] = rhs / self.r[i * m + i];
        }
    }
}

impl Accelerator for IqnIls {
    fn start_step(&mut self) {
        self.step += 1;
        self.first_in_step = true;
        let oldest = self.step.saturating_sub(self.reuse_steps);
        self.forget_older_than(oldest);
    }

    fn next(&mut self, x: &[f64], gx: &[f64], next: &mut [f64]) {
        for i in 0..x.len() {
            self.residual[i] = gx[i] - x[i];
        }
        // A secant whose residual change is at the round-off level of the values
        // carries no information, only noise: with a tolerance beyond reach, such
        // secants gave coefficients of any size and sent the iterate to NaN.
        if !self.first_in_step {
            let scale = gx.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let change = self
                .residual
                .iter()
                .zip(&self.previous_residual)
                .fold(0.0f64, |m, (r, p)| m.max((r - p).abs()));
            if change > 1e-13 * scale {
                self.push_secant(gx);
            }
        }
        if !self.secants.is_empty() {
            self.solve_least_squares();
            next.copy_from_slice(gx);
            for (c, &j) in self.kept.iter().enumerate() {
                let a = self.coefficients[c];
                for (n, w) in next.iter_mut().zip(&self.secants[j].w) {
                    *n += a * w;
                }
            }
        } else {
            for i in 0..x.len() {
                next[i] = x[i] + self.initial * self.residual[i];
            }
        }
        self.first_in_step = false;
        self.previous_residual.copy_from_slice(&self.residual);
        self.previous_gx.copy_from_slice(gx);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Iterates a linear map G(x) = A x + b and returns the iterations to reach
    /// |G(x) - x| < 1e-10.
    fn iterations(acc: &mut dyn Accelerator, a: &[[f64; 2]; 2], b: [f64; 2]) -> Option<usize> {
        acc.start_step();
        let mut x = [0.0; 2];
        let mut next = [0.0; 2];
        for k in 1..=200 {
            let gx = [
                a[0][0] * x[0] + a[0][1] * x[1] + b[0],
                a[1][0] * x[0] + a[1][1] * x[1] + b[1],
            ];
            if (gx[0] - x[0]).abs().max((gx[1] - x[1]).abs()) < 1e-10 {
                return Some(k);
            }
            acc.next(&x, &gx, &mut next);
            x = next;
        }
        None
    }

    // A contraction with factor -1.5 on one direction: plain iteration diverges.
    const A: [[f64; 2]; 2] = [[-1.5, 0.2], [0.1, 0.5]];
    const B: [f64; 2] = [1.0, 2.0];

    #[test]
    fn plain_iteration_diverges_where_aitken_and_iqn_converge() {
        assert_eq!(iterations(&mut Constant { factor: 1.0 }, &A, B), None);
        assert!(iterations(&mut Constant { factor: 0.4 }, &A, B).is_some());
        assert!(iterations(&mut Aitken::new(0.5, 2), &A, B).is_some());
        // A secant method solves a linear 2-D problem in n + 2 sweeps.
        let k = iterations(&mut IqnIls::new(0.5, 0, 2), &A, B).unwrap();
        assert!(k <= 4, "IQN-ILS took {k} iterations");
    }

    #[test]
    fn reused_secants_make_the_next_step_converge_at_once() {
        let mut acc = IqnIls::new(0.5, 1, 2);
        iterations(&mut acc, &A, B).unwrap();
        let k = iterations(&mut acc, &A, [1.5, 2.5]).unwrap();
        assert!(k <= 3, "with reuse IQN-ILS took {k} iterations");
    }
}
