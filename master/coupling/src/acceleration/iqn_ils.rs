//! Interface quasi-Newton with least-squares inverse Jacobian (IQN-ILS).

use super::Accelerator;

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
    /// The step began with secants of earlier steps (what `forget` reports).
    step_began_with_reuse: bool,
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
    /// IQN-ILS on `n` coupled values: relaxed by `initial` until it has
    /// differences, keeping those of the last `reuse_steps` steps.
    pub fn new(initial: f64, reuse_steps: u32, n: usize) -> IqnIls {
        let columns = n.max(1);
        IqnIls {
            initial,
            reuse_steps: u64::from(reuse_steps),
            step: 0,
            first_in_step: true,
            step_began_with_reuse: false,
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
        self.step_began_with_reuse = !self.secants.is_empty();
    }

    fn forget(&mut self) -> bool {
        self.spare.append(&mut self.secants);
        self.first_in_step = true;
        std::mem::take(&mut self.step_began_with_reuse)
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
