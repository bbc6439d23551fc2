//! Fixed-point acceleration of the interface iteration.
//!
//! The master iterates `x -> G(x)`, where `x` are the values of the torn
//! connections used as inputs and `G(x)` the values the sweep returns. Vectors here
//! are scaled by each connection's tolerance, so forces in N and velocities in m/s
//! weigh alike (a residual of 1 is exactly "at tolerance").

mod aitken;
mod constant;
mod iqn_ils;

pub use aitken::Aitken;
pub use constant::Constant;
pub use iqn_ils::IqnIls;

use crate::settings::Acceleration;

/// Proposes the next iterate from the last one and what the sweep made of it.
pub trait Accelerator: Send {
    /// Called at the start of every synchronisation step.
    fn start_step(&mut self);
    /// `x`: iterate used; `gx`: sweep result `G(x)`; writes the next iterate.
    fn next(&mut self, x: &[f64], gx: &[f64], next: &mut [f64]);
    /// Forgets everything learnt (the step starts afresh); true when that
    /// included what earlier steps taught, so that a repeat can differ.
    fn forget(&mut self) -> bool {
        false
    }
}

/// Builds the accelerator of a fixed-point scheme for `n` torn values.
pub fn accelerator(setting: &Acceleration, n: usize) -> Box<dyn Accelerator> {
    match *setting {
        Acceleration::None => Box::new(Constant { factor: 1.0 }),
        Acceleration::Constant { factor } => Box::new(Constant { factor }),
        Acceleration::Aitken { initial_factor } => Box::new(Aitken::new(initial_factor, n)),
        Acceleration::IqnIls {
            initial_factor,
            reuse_steps,
        } => Box::new(IqnIls::new(initial_factor, reuse_steps, n)),
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

    #[test]
    fn forgetting_says_whether_the_step_began_with_reused_secants() {
        // Without reuse nothing from earlier steps is there to forget.
        let mut plain = IqnIls::new(0.5, 0, 2);
        iterations(&mut plain, &A, B).unwrap();
        plain.start_step();
        assert!(!plain.forget());
        // With reuse the next step begins with the last step's secants; once
        // forgotten, the step iterates as the very first one did.
        let mut reusing = IqnIls::new(0.5, 1, 2);
        let first = iterations(&mut reusing, &A, B).unwrap();
        reusing.start_step();
        assert!(reusing.forget());
        assert!(!reusing.forget());
        let mut x = [0.0; 2];
        let mut next = [0.0; 2];
        let mut k = 1;
        loop {
            let gx = [
                A[0][0] * x[0] + A[0][1] * x[1] + B[0],
                A[1][0] * x[0] + A[1][1] * x[1] + B[1],
            ];
            if (gx[0] - x[0]).abs().max((gx[1] - x[1]).abs()) < 1e-10 || k > 200 {
                break;
            }
            reusing.next(&x, &gx, &mut next);
            x = next;
            k += 1;
        }
        assert_eq!(k, first);
        // Aitken and constant relaxation learn nothing across steps.
        assert!(!Aitken::new(0.5, 2).forget());
    }
}
