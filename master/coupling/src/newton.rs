//! Newton's method on the interface residual `R(x) = G(x) - x` of the torn
//! values. Its Jacobian `dG/dx - I` comes either from whole sweeps (finite
//! differences: one extra sweep per torn value from the rolled-back step start;
//! for loops that fixed-point iteration cannot solve, benchmark B6) or from the
//! units (the interface-Jacobian method of Kübler and Schiehlen 2000 and
//! Sicklinger et al. 2014): each unit's derivative of its outputs after the step
//! with respect to its inputs, chained through the connections in the sweep
//! order. A Jacobian may be kept across steps and evaluated anew when an
//! iteration converges slowly, since the interface of one structure changes
//! little from one step to the next.

use crate::coupler::{Master, link_value};
use crate::error::MasterError;
use crate::settings::{Derivatives, JacobianUpdate, NewtonSettings};
use nalgebra::{DMatrix, DVector, Dyn, linalg::LU};

/// What an iteration's update did: proposed the next iterate to sweep with,
/// or closed the step itself by the units' linear correction
/// (`newton.one_sweep`), whose residual is then checked.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum Update {
    /// The next sweep takes the new iterate.
    Sweep,
    /// The units were moved to the new iterate to first order.
    Corrected,
}

/// Buffers of the Newton scheme, sized once for the torn values.
pub(crate) struct NewtonWork {
    jacobian: DMatrix<f64>,
    factorised: Option<LU<f64, Dyn, Dyn>>,
    correction: DVector<f64>,
    base_gx: Vec<f64>,
    /// Steps the current Jacobian has served (`jacobian = "reuse"`).
    age: u32,
    /// The scaled torn residual of the step's previous iteration.
    last_residual: f64,
    /// Per connection, the derivative of its value with respect to the torn
    /// values (row-major, `connections x torn`).
    dv: Vec<f64>,
    /// The same for the inputs of the unit being chained (`inputs x torn`).
    du: Vec<f64>,
    /// Scratch: one unit's input change in a linear correction.
    change: Vec<f64>,
}

impl NewtonWork {
    pub(crate) fn new(n_torn: usize, n_connections: usize) -> NewtonWork {
        NewtonWork {
            jacobian: DMatrix::zeros(n_torn, n_torn),
            factorised: None,
            correction: DVector::zeros(n_torn),
            base_gx: vec![0.0; n_torn],
            age: 0,
            last_residual: f64::INFINITY,
            dv: vec![0.0; n_connections * n_torn],
            du: Vec::new(),
            change: Vec::new(),
        }
    }
}

impl NewtonWork {
    /// Drops the kept Jacobian (it belongs to another step size).
    pub(crate) fn forget(&mut self) {
        self.factorised = None;
    }
}

impl Master {
    /// One synchronisation step (or the initialisation) solved by Newton on the
    /// torn values.
    pub(crate) fn step_newton(&mut self) -> Result<(u32, f64, bool), MasterError> {
        let Some(settings) = self.settings.newton else {
            return Err(MasterError::Invalid(
                "step_newton without Newton settings".into(),
            ));
        };
        let mut work = self
            .newton
            .take()
            .ok_or_else(|| MasterError::Invalid("Newton buffers missing".into()))?;
        let keep = settings.jacobian == JacobianUpdate::Reuse
            && !self.initializing
            && work.age < settings.refresh_steps;
        if !keep {
            // The initialisation's Jacobian (a zero-length step) serves no step.
            work.factorised = None;
        }
        work.age += 1;
        work.last_residual = f64::INFINITY;
        let own_derivatives = settings.derivatives == Derivatives::Units && !self.initializing;
        self.warm_repeats = settings.warm_start && own_derivatives;
        self.defer_step_ends(settings.one_sweep && own_derivatives);
        let result = self.newton_iterations(&mut work, settings);
        self.warm_repeats = false;
        self.defer_step_ends(false);
        self.newton = Some(work);
        result
    }

    fn newton_iterations(
        &mut self,
        work: &mut NewtonWork,
        settings: NewtonSettings,
    ) -> Result<(u32, f64, bool), MasterError> {
        self.iterate(&mut |m, k| {
            work.base_gx.copy_from_slice(&m.gx);
            let residual = m.torn_residual();
            let slow = residual > settings.refresh_rate * work.last_residual;
            work.last_residual = residual;
            let stale = match settings.jacobian {
                JacobianUpdate::EveryIteration => true,
                JacobianUpdate::OncePerStep => work.factorised.is_none(),
                JacobianUpdate::Reuse => work.factorised.is_none() || slow,
            };
            if stale {
                m.evaluate_jacobian(work, settings, k)?;
                work.age = 1;
            }
            // Scaled residual r = (G(x) - x) / tol; solve J dz = -r.
            for (i, &c) in m.torn.iter().enumerate() {
                work.correction[i] = -(work.base_gx[i] - m.x[i]) / m.tolerance[c];
            }
            let lu = work
                .factorised
                .as_ref()
                .ok_or(MasterError::SingularJacobian {
                    time: m.target_time(),
                    iteration: k,
                })?;
            lu.solve_mut(&mut work.correction);
            for (i, &c) in m.torn.iter().enumerate() {
                m.x[i] += work.correction[i] * m.tolerance[c];
            }
            if settings.one_sweep && m.units_can_correct() {
                m.correct_units(&mut work.change, k)?;
                return Ok(Update::Corrected);
            }
            Ok(Update::Sweep)
        })
    }

    /// With `newton.one_sweep`: the first iterated unit that cannot correct
    /// its step (its kind offers no `Unit::correct_step`, or it steps in
    /// sub-steps), so every step is iterated as without it; None otherwise.
    pub fn one_sweep_blocked_by(&self) -> Option<&str> {
        if !self.settings.newton.is_some_and(|n| n.one_sweep) {
            return None;
        }
        (self.units.iter().enumerate())
            .find(|(u, unit)| self.iterated[*u] && !unit.declares_step_correction())
            .map(|(_, unit)| unit.name.as_str())
    }

    /// With `on`, tells every iterated unit that can correct its steps that
    /// they will be corrected, so it may leave each step's end pending (the
    /// correction takes it again at the moved state).
    fn defer_step_ends(&mut self, on: bool) {
        for (u, unit) in self.units.iter_mut().enumerate() {
            unit.defer_end = on && self.iterated[u] && unit.declares_step_correction();
        }
    }

    /// Whether every iterated unit can move its last step to the new iterate
    /// to first order (its own Jacobian of that step, `Unit::correct_step`).
    fn units_can_correct(&self) -> bool {
        (self.units.iter().enumerate())
            .all(|(u, unit)| !self.iterated[u] || unit.can_correct_step())
    }

    /// Moves every iterated unit's last step, in the sweep order, to its
    /// inputs at the new torn values `x` (the others' at the values the units
    /// upstream now give), to first order, and takes their outputs at the
    /// moved state: the sweep's values move to the corrected ones, and the
    /// residual that follows compares the torn ones with `x`. `change`: scratch.
    fn correct_units(&mut self, change: &mut Vec<f64>, iteration: u32) -> Result<(), MasterError> {
        let t_end = self.time + self.h;
        for i in 0..self.order.len() {
            let u = self.order[i];
            if !self.iterated[u] {
                continue;
            }
            let unit = &mut self.units[u];
            change.clear();
            change.resize(unit.inputs.len(), 0.0);
            for (p, source) in self.input_connection[u].iter().enumerate() {
                if let Some(c) = *source {
                    let value = match self.tear_index[c] {
                        Some(k) => self.x[k],
                        None => self.value[c],
                    };
                    change[p] = value - unit.inputs[p];
                }
            }
            if change.iter().all(|d| *d == 0.0) {
                continue;
            }
            unit.correct_step(change, t_end, iteration)?;
            for &c in &self.outgoing[u] {
                self.value[c] = link_value(&self.connections[c], &unit.outputs);
            }
        }
        for (k, &c) in self.torn.iter().enumerate() {
            self.gx[k] = self.value[c];
        }
        // The connections that are not torn were taken as they now are.
        self.previous.copy_from_slice(&self.value);
        Ok(())
    }

    /// The largest |G(x) - x| / tolerance over the torn values.
    fn torn_residual(&self) -> f64 {
        self.torn
            .iter()
            .enumerate()
            .map(|(k, &c)| (self.gx[k] - self.x[k]).abs() / self.tolerance[c])
            .fold(0.0, f64::max)
    }

    /// Fills the scaled Jacobian of the residual at the current iterate (the
    /// units stepped with it) and factorises it. The initialisation, a
    /// zero-length step with no rollback, always takes it from sweeps.
    fn evaluate_jacobian(
        &mut self,
        work: &mut NewtonWork,
        settings: NewtonSettings,
        iteration: u32,
    ) -> Result<(), MasterError> {
        if settings.derivatives == Derivatives::Units && !self.initializing {
            self.chain_unit_jacobians(work, settings.perturbation, iteration)?;
        } else {
            self.probe_jacobian(work, settings.perturbation, iteration)?;
        }
        self.counters.jacobian_evaluations += 1;
        let lu = work.jacobian.clone().lu();
        if !lu.is_invertible() {
            return Err(MasterError::SingularJacobian {
                time: self.target_time(),
                iteration,
            });
        }
        work.factorised = Some(lu);
        Ok(())
    }

    /// The Jacobian column by column, one sweep per torn value.
    fn probe_jacobian(
        &mut self,
        work: &mut NewtonWork,
        perturbation: f64,
        iteration: u32,
    ) -> Result<(), MasterError> {
        for j in 0..self.torn.len() {
            let xj = self.x[j];
            let delta = perturbation * xj.abs().max(1.0);
            self.restore_all(iteration)?;
            self.x[j] = xj + delta;
            let probe = self.sweep(iteration);
            self.x[j] = xj;
            probe?;
            let tol_j = self.tolerance[self.torn[j]];
            for (i, &c) in self.torn.iter().enumerate() {
                let dg = (self.gx[i] - work.base_gx[i]) / self.tolerance[c];
                let identity = if i == j { 1.0 } else { 0.0 };
                work.jacobian[(i, j)] = dg / (delta / tol_j) - identity;
            }
        }
        Ok(())
    }

    /// The Jacobian from the units' interface Jacobians, chained in the sweep
    /// order: a unit's inputs depend on the torn values directly (torn
    /// connections) or through the units upstream of it, and its outgoing
    /// connections by its Jacobian times those dependencies.
    fn chain_unit_jacobians(
        &mut self,
        work: &mut NewtonWork,
        perturbation: f64,
        iteration: u32,
    ) -> Result<(), MasterError> {
        let n = self.torn.len();
        self.unit_jacobians(perturbation, iteration)?;
        work.dv.fill(0.0);
        for i in 0..self.order.len() {
            let u = self.order[i];
            // Units no torn value reaches have no derivative with respect to x.
            if !self.iterated[u] {
                continue;
            }
            let n_in = self.units[u].inputs.len();
            work.du.resize(n_in * n, 0.0);
            for (p, row) in work.du.chunks_exact_mut(n.max(1)).enumerate() {
                row.fill(0.0);
                if let Some(c) = self.input_connection[u][p] {
                    match self.tear_index[c] {
                        Some(k) => row[k] = 1.0,
                        None => row.copy_from_slice(&work.dv[c * n..(c + 1) * n]),
                    }
                }
            }
            let jacobian = &self.units[u].jacobian;
            for &c in &self.outgoing[u] {
                let conn = &self.connections[c];
                let row = &mut work.dv[c * n..(c + 1) * n];
                for p in 0..n_in {
                    let d = conn.link.gain * jacobian[conn.from.port * n_in + p];
                    if d != 0.0 {
                        for (r, du) in row.iter_mut().zip(&work.du[p * n..(p + 1) * n]) {
                            *r += d * du;
                        }
                    }
                }
            }
        }
        for (i, &ci) in self.torn.iter().enumerate() {
            for (j, &cj) in self.torn.iter().enumerate() {
                let identity = if i == j { 1.0 } else { 0.0 };
                work.jacobian[(i, j)] =
                    work.dv[ci * n + j] * self.tolerance[cj] / self.tolerance[ci] - identity;
            }
        }
        Ok(())
    }
}

impl Master {
    /// Every iterated unit's interface Jacobian of the step it just took (on
    /// the sweep threads when there are several: each unit alone, so the result
    /// is the same), shared out as a sweep's steps are.
    fn unit_jacobians(&mut self, perturbation: f64, iteration: u32) -> Result<(), MasterError> {
        let (t, h) = (self.time, self.h);
        let evaluate = |unit: &mut crate::adapter::UnitAdapter| {
            unit.failure = unit.step_jacobian((t, h), perturbation, iteration).err();
        };
        let iterated = &self.iterated;
        match &self.pool {
            Some(pool) => pool.install(|| {
                crate::coupler::share_out(&mut self.units, &|u| iterated[u], &evaluate);
            }),
            None => self
                .units
                .iter_mut()
                .enumerate()
                .filter(|(u, _)| iterated[*u])
                .for_each(|(_, unit)| evaluate(unit)),
        }
        for &u in &self.order {
            if let Some(failure) = self.units[u].failure.take() {
                return Err(failure);
            }
        }
        Ok(())
    }
}
