//! The master: steps a coupled [`System`] with the configured scheme.
//!
//! One synchronisation step is one or more *sweeps*. A sweep steps every unit once
//! (in `order`), feeding each input from its connection: torn connections (see
//! [`crate::order::tears`]) take the current iterate `x`, the others the value just
//! produced upstream. Non-iterative schemes do one sweep with `x` predicted from
//! accepted values; iterative ones roll the units back and repeat until every
//! connection changes by less than its tolerance (seed 000 Algorithm 1), updating
//! `x` by plain fixed point, relaxation, Aitken, IQN-ILS or Newton.

use crate::acceleration::{Accelerator, accelerator};
use crate::adapter::UnitAdapter;
use crate::counters::Counters;
use crate::error::MasterError;
pub(crate) use crate::newton::Update;
use crate::order::{derive_order, reached_by_torn, torn_connections, wiring};
use crate::settings::{Extrapolation, MasterSettings, OnMaxIterations};
use crate::system::{Connection, System};
use slender_contract::{Hold, Time};
use std::time::Instant;

mod access;
mod adaptive;
mod fields;
mod initial;
mod parallel;
pub(crate) use parallel::share_out;
mod setup;
mod start_check;
mod tolerance;

pub use start_check::StartLoad;

use setup::{adapters, check_setup, explicit_order};
use tolerance::ConnectionTolerances;

/// Convergence of one sweep: the largest change relative to its tolerance, and where.
#[derive(Copy, Clone, Debug)]
pub(crate) struct Residual {
    pub scaled: f64,
    pub connection: usize,
    pub change: f64,
}

/// A coupled simulation in progress.
pub struct Master {
    pub(crate) units: Vec<UnitAdapter>,
    pub(crate) connections: Vec<Connection>,
    pub(crate) settings: MasterSettings,
    pub(crate) order: Vec<usize>,
    /// Per unit and input: the connection driving it.
    pub(crate) input_connection: Vec<Vec<Option<usize>>>,
    /// Per unit: connections leaving it.
    pub(crate) outgoing: Vec<Vec<usize>>,
    /// Per unit: whether a torn value reaches it, so it must be repeated in every
    /// iteration; the others are stepped once per step and never rolled back.
    pub(crate) iterated: Vec<bool>,
    /// Whether the current step (or initialisation) has had its first sweep.
    first_sweep_done: bool,
    /// Per connection: its tolerance now.
    pub(crate) tolerance: Vec<f64>,
    /// Where each tolerance comes from; relative ones follow the values.
    pub(super) tolerances: ConnectionTolerances,
    /// Per connection: index in the torn vector, or `None`.
    pub(crate) tear_index: Vec<Option<usize>>,
    /// The torn connections, in tear order.
    pub(crate) torn: Vec<usize>,
    /// Connection values of the latest sweep.
    pub(crate) value: Vec<f64>,
    /// Connection values of the sweep before (convergence check of untorn ones).
    pub(crate) previous: Vec<f64>,
    /// Accepted values at the start of the current step, of the step before,
    /// and of the one before that.
    pub(crate) accepted: Vec<f64>,
    pub(crate) accepted_before: Vec<f64>,
    pub(crate) accepted_earlier: Vec<f64>,
    /// The torn iterate `x` (physical units), the sweep result `G(x)`, scaled copies.
    pub(crate) x: Vec<f64>,
    pub(crate) gx: Vec<f64>,
    pub(crate) scaled_x: Vec<f64>,
    pub(crate) scaled_gx: Vec<f64>,
    pub(crate) scaled_next: Vec<f64>,
    /// The step's first iterate, for a restart.
    x_start: Vec<f64>,
    accelerator: Box<dyn Accelerator>,
    /// Whether a rollback hints the units that they repeat their last step
    /// (Newton on the units' Jacobians with `warm_start`).
    pub(crate) warm_repeats: bool,
    /// The threads of parallel Jacobi sweeps (`threads` > 1).
    pub(crate) pool: Option<std::sync::Arc<rayon::ThreadPool>>,
    pub(crate) newton: Option<crate::newton::NewtonWork>,
    pub(crate) time: Time,
    /// The synchronisation step: each `step` advances the time by it.
    pub(crate) step_size: Time,
    /// The coupling step in force: the synchronisation step, or a part of it
    /// chosen by the adaptive step.
    pub(crate) h: Time,
    /// The adaptive step's state (`[master.adaptive]`).
    adaptive: Option<adaptive::Adaptive>,
    /// Weights of the accepted values (last, before, earlier) that predict
    /// the next step's torn values when steps differ in size.
    weights: Option<[f64; 3]>,
    pub(crate) counters: Counters,
    initialized: bool,
    /// True while `initialize` runs: sweeps call `initialize` instead of `do_step`.
    pub(crate) initializing: bool,
    /// The connections into units' static inputs, with the value each was
    /// initialised under (see `start_check`).
    static_loads: Vec<(usize, f64)>,
}

impl Master {
    /// Prepares `system` for stepping with `settings` and synchronisation step
    /// `step_size`; checks the settings, the order and the units' capabilities.
    pub fn new(
        system: System,
        settings: MasterSettings,
        step_size: Time,
    ) -> Result<Master, MasterError> {
        check_setup(&system, &settings, step_size)?;
        let n_units = system.units.len();
        let order = if settings.order.is_empty() {
            derive_order(n_units, &system.connections)
        } else {
            explicit_order(&system, &settings.order)?
        };
        let (tear_index, torn) =
            torn_connections(&order, &system.connections, settings.scheme.is_sequential());
        let (input_connection, outgoing) = wiring(&system);
        let iterated = reached_by_torn(n_units, &system.connections, &torn);
        let (tolerances, tolerance) =
            ConnectionTolerances::new(&system.connections, &settings.tolerances);
        let n_conn = system.connections.len();
        let n_torn = torn.len();
        let counters = Counters::new(system.unit_names());
        let newton = settings
            .newton
            .map(|_| crate::newton::NewtonWork::new(n_torn, n_conn));
        let accelerator = accelerator(&settings.acceleration, n_torn);
        let adaptive = (settings.adaptive.clone())
            .map(|a| adaptive::Adaptive::new(a, step_size, &system.connections))
            .transpose()?;
        // One unit has nothing to step beside it: no pool (its hand-over to a
        // pool thread cost the monolithic riser a third of its step).
        let sequential = settings.scheme.is_sequential() || n_units < 2;
        let pool = Master::thread_pool(settings.threads, sequential)?;
        let units = adapters(system.units, &system.connections, &tolerance, &settings);
        Ok(Master {
            units,
            connections: system.connections,
            settings,
            order,
            input_connection,
            outgoing,
            iterated,
            first_sweep_done: false,
            tolerance,
            tolerances,
            tear_index,
            torn,
            value: vec![0.0; n_conn],
            previous: vec![0.0; n_conn],
            accepted: vec![0.0; n_conn],
            accepted_before: vec![0.0; n_conn],
            accepted_earlier: vec![0.0; n_conn],
            x: vec![0.0; n_torn],
            gx: vec![0.0; n_torn],
            scaled_x: vec![0.0; n_torn],
            scaled_gx: vec![0.0; n_torn],
            scaled_next: vec![0.0; n_torn],
            x_start: vec![0.0; n_torn],
            accelerator,
            warm_repeats: false,
            pool,
            newton,
            time: Time::ZERO,
            step_size,
            h: step_size,
            adaptive,
            weights: None,
            counters,
            initialized: false,
            initializing: false,
            static_loads: Vec::new(),
        })
    }

    /// Sets the input hold of every input of unit `unit` (before `initialize`).
    pub fn set_hold(&mut self, unit: usize, hold: Hold) -> Result<(), MasterError> {
        self.units[unit].set_hold_all(hold)
    }

    /// Steps unit `unit` in `n` sub-steps per synchronisation step, its inputs
    /// interpolated within the step (before `initialize`).
    pub fn set_substeps(&mut self, unit: usize, n: u32) -> Result<(), MasterError> {
        self.units[unit].set_substeps(n)
    }

    /// Advances every unit by one synchronisation step.
    ///
    /// With a thread pool the whole step runs on one of its threads, so the
    /// sweeps' units are shared out from inside the pool: the calling thread
    /// is handed over once a step instead of at every sweep and Jacobian.
    pub fn step(&mut self) -> Result<(), MasterError> {
        self.on_pool(Master::step_here)
    }

    /// Runs `work` (a run's loop of steps) on a thread of the master's pool
    /// when it has one, so that its steps hand no thread over between them:
    /// on a virtual machine waking a thread costs tens of microseconds, as
    /// much as a line's wave sums. Without a pool, on the calling thread.
    pub fn on_pool<R: Send>(&mut self, work: impl FnOnce(&mut Master) -> R + Send) -> R {
        match self.pool.clone() {
            Some(pool) => pool.install(|| work(self)),
            None => work(self),
        }
    }

    /// [`Master::step`] on the calling thread.
    fn step_here(&mut self) -> Result<(), MasterError> {
        if !self.initialized {
            return Err(MasterError::Invalid(
                "Master::step called before Master::initialize".into(),
            ));
        }
        if self.adaptive.is_some() {
            return self.step_adaptive();
        }
        let solved = self.solve_step()?;
        self.accept_step(solved)
    }

    /// Solves the step of size `h` from the current time: the prediction and
    /// the scheme's sweeps; returns iterations, residual and convergence.
    fn solve_step(&mut self) -> Result<(u32, f64, bool), MasterError> {
        self.tolerances.follow(
            &self.accepted,
            &self.connections,
            &mut self.tolerance,
            &mut self.units,
        );
        self.predict();
        self.first_sweep_done = false;
        if !self.settings.scheme.is_iterative() {
            self.sweep(1)?;
            Ok((1, 0.0, true))
        } else if self.newton.is_some() {
            self.step_newton()
        } else {
            self.step_fixed_point()
        }
    }

    /// Takes the solved step's values as accepted and moves the time on.
    fn accept_step(
        &mut self,
        (iterations, residual, converged): (u32, f64, bool),
    ) -> Result<(), MasterError> {
        self.counters.record_step(iterations, residual, converged);
        self.accepted_earlier.copy_from_slice(&self.accepted_before);
        self.accepted_before.copy_from_slice(&self.accepted);
        self.accepted.copy_from_slice(&self.value);
        self.time += self.h;
        if self.counters.steps == 1 {
            self.check_start()?;
        }
        Ok(())
    }

    /// Steps until `end` (inclusive), calling `observe` after every step.
    pub fn run_until(
        &mut self,
        end: Time,
        mut observe: impl FnMut(&Master),
    ) -> Result<(), MasterError> {
        while self.time + self.step_size <= end {
            self.step()?;
            observe(self);
        }
        Ok(())
    }

    /// First iterate of the torn values: extrapolated from accepted values.
    fn predict(&mut self) {
        if let Some(w) = self.weights {
            for (i, &c) in self.torn.iter().enumerate() {
                self.x[i] = w[0] * self.accepted[c]
                    + w[1] * self.accepted_before[c]
                    + w[2] * self.accepted_earlier[c];
            }
            self.previous.copy_from_slice(&self.accepted);
            return;
        }
        for (i, &c) in self.torn.iter().enumerate() {
            self.x[i] = match self.settings.extrapolation {
                Extrapolation::Constant => self.accepted[c],
                Extrapolation::Linear => 2.0 * self.accepted[c] - self.accepted_before[c],
                Extrapolation::Quadratic => {
                    3.0 * (self.accepted[c] - self.accepted_before[c]) + self.accepted_earlier[c]
                }
            };
        }
        self.previous.copy_from_slice(&self.accepted);
    }

    /// Steps every unit once with the torn inputs at `self.x`; fills `self.value` and
    /// `self.gx`.
    ///
    /// Each unit is charged the wall time from the end of the previous unit's
    /// outputs to the end of its own: one clock read per unit (about 26 ns here)
    /// instead of two, at the price of counting the copying of its inputs.
    pub(crate) fn sweep(&mut self, iteration: u32) -> Result<(), MasterError> {
        if self.pool.is_some() && !self.initializing {
            return self.sweep_parallel(iteration);
        }
        let (t, h) = (self.time, self.h);
        let mut stamp = Instant::now();
        let repeat = self.first_sweep_done;
        self.first_sweep_done = true;
        for i in 0..self.order.len() {
            let u = self.order[i];
            if repeat && !self.iterated[u] {
                continue;
            }
            let unit = &mut self.units[u];
            for (p, source) in self.input_connection[u].iter().enumerate() {
                if let Some(c) = *source {
                    unit.inputs[p] = match self.tear_index[c] {
                        Some(k) => self.x[k],
                        None => self.value[c],
                    };
                }
            }
            if self.initializing {
                unit.initialize(t, iteration)?;
            } else {
                unit.step(t, h, iteration)?;
                let now = Instant::now();
                unit.step_time += now - stamp;
                stamp = now;
            }
            for &c in &self.outgoing[u] {
                self.value[c] = link_value(&self.connections[c], &unit.outputs);
            }
        }
        for (k, &c) in self.torn.iter().enumerate() {
            self.gx[k] = self.value[c];
        }
        Ok(())
    }

    /// How far the latest sweep is from converged: torn connections compare what
    /// came out with what went in, the others with the sweep before. Moves the
    /// latest values to `previous`.
    pub(crate) fn residual(&mut self) -> Residual {
        let mut worst = Residual {
            scaled: 0.0,
            connection: 0,
            change: 0.0,
        };
        for c in 0..self.connections.len() {
            let reference = match self.tear_index[c] {
                Some(k) => self.x[k],
                None => self.previous[c],
            };
            let change = (self.value[c] - reference).abs();
            let scaled = change / self.tolerance[c];
            if scaled > worst.scaled || scaled.is_nan() {
                worst = Residual {
                    scaled,
                    connection: c,
                    change,
                };
            }
        }
        self.previous.copy_from_slice(&self.value);
        worst
    }

    /// Saves every unit's state at the start of the step (nothing to save while
    /// initialising).
    pub(crate) fn save_all(&mut self) -> Result<(), MasterError> {
        if self.initializing {
            return Ok(());
        }
        for (u, unit) in self.units.iter_mut().enumerate() {
            if self.iterated[u] {
                unit.save(self.time)?;
            }
        }
        Ok(())
    }

    /// Takes the step ends the units left pending for a correction that did
    /// not come (the step closed without one, or not for that unit).
    fn complete_steps(&mut self, iteration: u32) -> Result<(), MasterError> {
        let t_end = self.time + self.h;
        for unit in &mut self.units {
            unit.complete_step(t_end, iteration)?;
        }
        Ok(())
    }

    /// Rolls every unit back to the start of the step.
    pub(crate) fn restore_all(&mut self, iteration: u32) -> Result<(), MasterError> {
        if self.initializing {
            return Ok(());
        }
        for (u, unit) in self.units.iter_mut().enumerate() {
            if self.iterated[u] {
                unit.restore_hinted(self.time, iteration, self.warm_repeats)?;
                self.counters.rollbacks += 1;
            }
        }
        Ok(())
    }

    /// The iteration shared by every iterative scheme: save the units, then sweep,
    /// check convergence and, if not converged, let `update` propose the next `x`
    /// and roll the units back, until converged or out of iterations.
    pub(crate) fn iterate(
        &mut self,
        update: &mut dyn FnMut(&mut Master, u32) -> Result<Update, MasterError>,
    ) -> Result<(u32, f64, bool), MasterError> {
        self.save_all()?;
        let max = self.settings.max_iterations;
        let mut k = 1;
        loop {
            if k > 1 {
                self.restore_all(k)?;
            }
            self.sweep(k)?;
            let residual = self.residual();
            if residual.scaled <= 1.0 {
                self.complete_steps(k)?;
                return Ok((k, residual.scaled, true));
            }
            if k == max {
                self.complete_steps(k)?;
                return self.give_up(k, residual);
            }
            if update(self, k)? == Update::Corrected {
                let corrected = self.residual();
                if corrected.scaled <= 1.0 {
                    self.counters.corrected_steps += 1;
                    self.complete_steps(k)?;
                    return Ok((k, corrected.scaled, true));
                }
            }
            k += 1;
        }
    }

    /// Iterative Jacobi or Gauss-Seidel with fixed-point updates of `x`. When a
    /// unit fails on an iterate and the accelerator had learnt from earlier
    /// steps (IQN-ILS's reused secants can propose a value far outside what
    /// this step needs), the step starts once more from its first iterate
    /// without them; a second failure is the run's error.
    fn step_fixed_point(&mut self) -> Result<(u32, f64, bool), MasterError> {
        self.accelerator.start_step();
        self.x_start.copy_from_slice(&self.x);
        match self.iterate_fixed_point() {
            // Only a later iterate comes from the accelerator (the first one is
            // the prediction, and its sweep steps the units outside the loop).
            Err(MasterError::Unit { iteration, .. } | MasterError::NonFinite { iteration, .. })
                if iteration > 1 && self.accelerator.forget() =>
            {
                self.counters.restarts += 1;
                self.restore_all(0)?;
                self.x.copy_from_slice(&self.x_start);
                self.previous.copy_from_slice(&self.accepted);
                self.iterate_fixed_point()
            }
            other => other,
        }
    }

    fn iterate_fixed_point(&mut self) -> Result<(u32, f64, bool), MasterError> {
        self.iterate(&mut |m, _| {
            m.scale_iterate();
            m.accelerator
                .next(&m.scaled_x, &m.scaled_gx, &mut m.scaled_next);
            m.unscale_next();
            Ok(Update::Sweep)
        })
    }

    /// What happens when a step runs out of iterations.
    pub(crate) fn give_up(
        &mut self,
        iterations: u32,
        residual: Residual,
    ) -> Result<(u32, f64, bool), MasterError> {
        match self.settings.on_max_iterations {
            OnMaxIterations::Accept => Ok((iterations, residual.scaled, false)),
            OnMaxIterations::Error => {
                // The failed step's residual is the run's last and (likely) largest.
                self.counters.record_residual(residual.scaled);
                Err(MasterError::NotConverged {
                    time: self.target_time(),
                    iterations,
                    connection: self.connections[residual.connection].label.clone(),
                    change: residual.change,
                    tolerance: self.tolerance[residual.connection],
                    key: self
                        .tolerances
                        .key(residual.connection, &self.connections[residual.connection]),
                })
            }
        }
    }

    /// `x` and `G(x)` divided by their connections' tolerances.
    pub(crate) fn scale_iterate(&mut self) {
        for (k, &c) in self.torn.iter().enumerate() {
            self.scaled_x[k] = self.x[k] / self.tolerance[c];
            self.scaled_gx[k] = self.gx[k] / self.tolerance[c];
        }
    }

    /// `x` from the scaled next iterate.
    pub(crate) fn unscale_next(&mut self) {
        for (k, &c) in self.torn.iter().enumerate() {
            self.x[k] = self.scaled_next[k] * self.tolerance[c];
        }
    }

    /// The time the current iterations solve for (s): the step's end, or the
    /// initial time while initialising.
    pub(crate) fn target_time(&self) -> f64 {
        if self.initializing {
            self.time.as_secs()
        } else {
            (self.time + self.h).as_secs()
        }
    }
}

/// The value a connection passes on, from its source unit's outputs.
pub(crate) fn link_value(c: &Connection, outputs: &[f64]) -> f64 {
    c.link.gain * outputs[c.from.port] + c.link.offset
}
