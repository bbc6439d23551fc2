//! The sensitivity of a converged HHT-alpha step to its coupled end values: what
//! a unit's step Jacobian (`Unit::step_jacobian`) needs, by back-substitutions
//! with the step's own factorised Newton matrix.
//!
//! At the converged step the free DOFs satisfy `R(q1; u) = 0`, with a1 and v1
//! from q1 by Newmark. A unit change of an input either moves a held DOF (its q,
//! v and a as the unit's end condition prescribes them, not necessarily
//! Newmark's) or loads a DOF; then `S dq_free = -dR/du`. The Newton matrix `S =
//! M / (beta h^2) + (1 - alpha) (gamma / (beta h) (C + C_t) + K_t)`, kept with
//! its held rows in place, gives K_t where the unit knows M and C + C_t:
//! `dR_f = S dq + M (da - dq / (beta h^2)) + (1 - alpha) (C + C_t) (dv - gamma /
//! (beta h) dq)` for a held DOF's column, and the change of the reaction `M a +
//! (C + C_t) v + K_t q` at any DOF.

use super::hht::HhtAlpha;
use crate::contract::UnitError;
use crate::numerics::banded::{BandLdlt, SymmetricBand};

/// One input's effect on the step: a held DOF moved by (dq, dv, da), or a DOF
/// loaded with the weight the load has in the residual.
#[derive(Copy, Clone, Debug)]
pub enum Drive {
    /// A held DOF moved by its (dq, dv, da).
    Motion {
        /// The DOF moved.
        dof: usize,
        /// Its change of displacement, velocity and acceleration per unit input.
        change: [f64; 3],
    },
    /// A DOF loaded by the input.
    Load {
        /// The DOF loaded.
        dof: usize,
        /// The load's weight in the residual per unit input.
        weight: f64,
    },
}

/// A converged step as its sensitivity needs it.
pub struct StepSensitivity<'a> {
    /// The Newton matrix with the held rows in place, and its factor with the
    /// held DOFs as identity rows.
    pub newton: &'a SymmetricBand,
    /// The factor of the Newton matrix, held DOFs as identity rows.
    pub factor: &'a BandLdlt,
    /// Mass matrix M.
    pub mass: &'a SymmetricBand,
    /// The damping of the step's end, C + C_t, at (i, k).
    pub damping: &'a dyn Fn(usize, usize) -> f64,
    /// (alpha, beta, gamma) and the step (s).
    pub parameters: (f64, f64, f64),
    /// The step (s).
    pub h: f64,
}

impl<'a> StepSensitivity<'a> {
    /// The sensitivity of `hht`'s last step of `h` seconds (its kept Newton
    /// matrix) for a system of `mass` and `damping`; `label` names the unit
    /// when the step kept no matrix.
    pub fn of_last_step(
        hht: &'a HhtAlpha,
        label: &str,
        (mass, damping): (&'a SymmetricBand, &'a dyn Fn(usize, usize) -> f64),
        h: f64,
    ) -> Result<StepSensitivity<'a>, UnitError> {
        let (newton, factor) = hht.last_newton_of(label)?;
        Ok(StepSensitivity {
            newton,
            factor,
            mass,
            damping,
            parameters: hht.parameters(),
            h,
        })
    }
}

/// The motion's change per unit input: dq, dv, da of every DOF.
#[derive(Default)]
pub struct Change {
    /// Change of the displacements (per unit input).
    pub dq: Vec<f64>,
    /// Change of the velocities (per unit input).
    pub dv: Vec<f64>,
    /// Change of the accelerations (per unit input).
    pub da: Vec<f64>,
}

impl Change {
    /// No change of any of `n` DOFs.
    pub fn clear(&mut self, n: usize) {
        for v in [&mut self.dq, &mut self.dv, &mut self.da] {
            v.clear();
            v.resize(n, 0.0);
        }
    }
}

impl StepSensitivity<'_> {
    fn rows(&self, d: usize) -> std::ops::Range<usize> {
        let (n, w) = (self.newton.size(), self.newton.half_bandwidth());
        d.saturating_sub(w)..(d + w + 1).min(n)
    }

    /// The change of every DOF's motion under `drive`; `held` lists the DOFs
    /// the step held.
    pub fn solve(&self, drive: Drive, held: &[usize], out: &mut Change) {
        out.clear(self.newton.size());
        self.load_of(drive, held, &mut out.dq);
        self.factor.solve_in_place(&mut out.dq);
        self.rates(drive, held, out);
    }

    /// The displacements' change under each of `drives` (None: no change),
    /// into `columns` (column-major, one of every DOF per drive), solved
    /// together: each column to the bit what [`Self::solve`] gives, at less
    /// cost. [`Self::change_of`] then gives each column's whole motion.
    pub fn solve_columns(&self, drives: &[Option<Drive>], held: &[usize], columns: &mut Vec<f64>) {
        let n = self.newton.size();
        columns.clear();
        columns.resize(n * drives.len(), 0.0);
        for (drive, column) in drives.iter().zip(columns.chunks_exact_mut(n.max(1))) {
            if let Some(drive) = drive {
                self.load_of(*drive, held, column);
            }
        }
        self.factor.solve_columns_in_place(columns);
    }

    /// The whole motion's change under `drive` from its solved displacements
    /// `column` (by [`Self::solve_columns`]), into `out`.
    pub fn change_of(
        &self,
        drive: Option<Drive>,
        held: &[usize],
        column: &[f64],
        out: &mut Change,
    ) {
        out.clear(self.newton.size());
        if let Some(drive) = drive {
            out.dq.copy_from_slice(column);
            self.rates(drive, held, out);
        }
    }

    /// The right-hand side of the displacements' change under `drive` into
    /// `dq` (zero on entry).
    fn load_of(&self, drive: Drive, held: &[usize], dq: &mut [f64]) {
        let (alpha, beta, gamma) = self.parameters;
        let h = self.h;
        match drive {
            Drive::Load { dof, weight } => dq[dof] = weight,
            Drive::Motion {
                dof: d,
                change: [q, v, a],
            } => {
                for f in self.rows(d) {
                    dq[f] = -(self.newton.get(f, d) * q
                        + self.mass.get(f, d) * (a - q / (beta * h * h))
                        + (1.0 - alpha) * (self.damping)(f, d) * (v - gamma / (beta * h) * q));
                }
                for &k in held {
                    dq[k] = 0.0;
                }
                dq[d] = q;
            }
        }
    }

    /// The velocities' and accelerations' change by Newmark from the solved
    /// `out.dq`, a held DOF's as `drive` moves it.
    fn rates(&self, drive: Drive, held: &[usize], out: &mut Change) {
        let (_, beta, gamma) = self.parameters;
        let h = self.h;
        for i in 0..out.dq.len() {
            out.da[i] = out.dq[i] / (beta * h * h);
            out.dv[i] = gamma / (beta * h) * out.dq[i];
        }
        for &k in held {
            out.dv[k] = 0.0;
            out.da[k] = 0.0;
        }
        if let Drive::Motion {
            dof,
            change: [_, dv, da],
        } = drive
        {
            out.dv[dof] = dv;
            out.da[dof] = da;
        }
    }

    /// The change of the reaction `M a + (C + C_t) v + K_t q` at DOF `i`.
    pub fn reaction_change(&self, change: &Change, i: usize) -> f64 {
        let (alpha, beta, gamma) = self.parameters;
        let h = self.h;
        self.rows(i)
            .map(|k| {
                let (m, c) = (self.mass.get(i, k), (self.damping)(i, k));
                let kt = (self.newton.get(i, k) - m / (beta * h * h)) / (1.0 - alpha)
                    - gamma / (beta * h) * c;
                m * change.da[k] + c * change.dv[k] + kt * change.dq[k]
            })
            .sum()
    }
}
