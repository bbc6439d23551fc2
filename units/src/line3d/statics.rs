//! The 3D line's start: a first shape from the elastic catenary in the
//! vertical plane through its ends (a straight line where the catenary does
//! not apply), then Newton on the static equilibrium under weight, seabed
//! and current (no friction: the static Coulomb force is undetermined; no
//! waves) with the ends held or loaded as at t0. Newton's corrections are
//! limited to a fifth of an element per iteration, so a poor first shape
//! approaches the equilibrium instead of jumping past it.

use super::Line3d;
use super::catenary::CatenaryLine;
use super::mechanics::{BAND, DOF, node};
use crate::contract::UnitError;
use crate::numerics::banded::{BandLdlt, SymmetricBand};

/// Newton's iteration bound for the statics.
const STATIC_ITERATIONS: usize = 400;

/// The iterations after which a correction that does not shrink shortens
/// Newton's steps.
const CYCLING_AFTER: usize = 100;

impl Line3d {
    /// The first shape: node positions (m) from the catenary through the
    /// ends, or the straight line between them.
    pub(super) fn first_shape(&self) -> Vec<f64> {
        let p = &self.params;
        let (a, b) = (p.start.position, p.end.position);
        let across = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
        let up = b[2] - a[2];
        let n = self.mechanics.nodes;
        let straight = |s: f64| -> [f64; 3] {
            let f = s / p.length;
            [
                a[0] + f * (b[0] - a[0]),
                a[1] + f * (b[1] - a[1]),
                a[2] + f * (b[2] - a[2]),
            ]
        };
        let line = CatenaryLine {
            length: p.length,
            axial_stiffness: p.axial_stiffness,
            weight: p.submerged_weight,
            seabed: self.environment.seabed.is_some(),
        };
        let catenary = (p.submerged_weight > 0.0 && across > 1e-6 * p.length && up > 0.0)
            .then(|| line.solve(across, up).ok())
            .flatten();
        let mut q = vec![0.0; DOF * n];
        for i in 0..n {
            let s = i as f64 * self.mechanics.element_length;
            let x = match &catenary {
                Some(c) => {
                    let [h, z] = c.point(s);
                    let (dx, dy) = ((b[0] - a[0]) / across, (b[1] - a[1]) / across);
                    [a[0] + h * dx, a[1] + h * dy, a[2] + z]
                }
                None => straight(s),
            };
            q[DOF * i..DOF * i + DOF].copy_from_slice(&x);
        }
        // The ends exactly where they are given.
        q[..DOF].copy_from_slice(&a);
        q[DOF * (n - 1)..].copy_from_slice(&b);
        q
    }

    /// Newton on the static equilibrium from `q`; `loads` holds the end loads
    /// (N) applied on loaded ends; the held DOFs keep their values.
    pub(super) fn solve_statics(
        &mut self,
        q: &mut [f64],
        loads: &[f64],
        t0: f64,
    ) -> Result<usize, UnitError> {
        let n = q.len();
        let zeros = vec![0.0; n];
        let mut band = SymmetricBand::zeros(n, BAND);
        let mut residual = vec![0.0; n];
        let mut factor = BandLdlt::zeros(n, BAND);
        let held = self.held_dofs();
        let limit = 0.2 * self.mechanics.element_length;
        let statics = self.environment.without_waves();
        let (mut trust, mut previous) = (1.0_f64, f64::INFINITY);
        for iteration in 1..=STATIC_ITERATIONS {
            band.fill_zero();
            residual.fill(0.0);
            self.mechanics
                .add_force(q, &zeros, 1.0, Some((&mut band, 1.0, 0.0)), &mut residual);
            statics.add_force(
                q,
                &zeros,
                t0,
                1.0,
                Some((&mut band, 1.0, 0.0)),
                &mut residual,
            );
            for ((r, w), l) in residual.iter_mut().zip(&self.weight).zip(loads) {
                *r -= w + l;
            }
            for &d in &held {
                band.set_identity_row(d);
                residual[d] = 0.0;
            }
            if !factor.refactorise_nonsingular(&band) {
                return Err(self.static_failure(iteration, "the tangent stiffness is singular"));
            }
            for r in residual.iter_mut() {
                *r = -*r;
            }
            factor.solve_in_place(&mut residual);
            let largest = (0..n / DOF)
                .map(|i| node(&residual, i).norm())
                .fold(0.0, f64::max);
            if !largest.is_finite() {
                return Err(self.static_failure(iteration, "a correction became non-finite"));
            }
            let size = q.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            if largest < 1e-11 * size && (largest <= limit) {
                for (x, dx) in q.iter_mut().zip(&residual) {
                    *x += dx;
                }
                return Ok(iteration);
            }
            // Past the iterations a solve usually takes, a correction that
            // does not shrink is Newton cycling between contact states at
            // the touchdown: its steps are shortened until it settles.
            if iteration > CYCLING_AFTER {
                trust = if largest > 0.9 * previous {
                    (0.5 * trust).max(1.0 / 1024.0)
                } else {
                    (2.0 * trust).min(1.0)
                };
            }
            previous = largest;
            let damp = trust
                * if largest > limit {
                    limit / largest
                } else {
                    1.0
                };
            for (x, dx) in q.iter_mut().zip(&residual) {
                *x += damp * dx;
            }
        }
        Err(self.static_failure(STATIC_ITERATIONS, "Newton did not converge"))
    }

    fn static_failure(&self, iteration: usize, why: &str) -> UnitError {
        UnitError::Numerical(format!(
            "line3d statics: {why} (iteration {iteration}); check that the ends are {} m apart or less, the weight and stiffnesses",
            self.params.length
        ))
    }
}
