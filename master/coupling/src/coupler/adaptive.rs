//! The adaptive coupling step (`[master.adaptive]`).
//!
//! Within each synchronisation step `H` (the scene's `step`, at which outputs
//! are recorded) the master steps at `H / 2^k`, `k` from 0 to the halvings
//! that keep the step at least `min_step`. Every step starts from saved units;
//! it is repeated at half the size when
//! - it fails: a unit's error, no convergence within `max_iterations`, a
//!   non-finite value or a singular interface Jacobian, or
//! - its error estimate exceeds 1, the larger of
//!   - the interface's: each judged connection's accepted value against its
//!     quadratic extrapolation from the three accepted values before it
//!     (unequally spaced times allowed), over `tolerance` times the
//!     structure's scale of its kind (the largest force, moment, velocity...
//!     any connection of that kind has carried: a cut moment near zero is not
//!     judged on its own size; a port without a unit of measure on its own
//!     connection's) and never below ten of its convergence tolerances (the
//!     iteration's noise, amplified by the extrapolation). The miss is third
//!     order in the step, as the units' HHT-alpha and Newmark local errors
//!     are: it grows where the interface's third derivative does (contact, a
//!     snap, a sudden load) and falls where the motion is smooth;
//!   - the units' own (`displacement`): each unit's estimate of its step's
//!     local displacement error (`Unit::local_error`, Zienkiewicz and Xie's
//!     for HHT-alpha) over the metres allowed.
//!
//! A run starts at the smallest step (its first two steps cannot be judged:
//! three accepted values are needed). After `calm_steps` accepted steps with
//! estimates under a sixteenth of 1 (twice the step should then pass: 2^3 = 8
//! times the miss), the step doubles where the time is a multiple of the
//! doubled step, so that every synchronisation time is met exactly. At the
//! smallest step an estimate over 1 is accepted and counted; a failure there
//! is the run's error.

use super::Master;
use crate::counters::StepSizes;
use crate::error::MasterError;
use crate::settings::{AdaptiveStep, Extrapolation};
use crate::system::Connection;
use slender_contract::{PortKind, Time};

/// The deepest halving allowed, whatever `min_step` says (2^20 steps in one).
const MAX_HALVINGS: u32 = 20;

/// Factor below the tolerance under which a step counts as calm: a third-order
/// miss grows eightfold when the step doubles, with a margin of two.
const CALM_FRACTION: f64 = 1.0 / 16.0;

/// An error estimate is never judged against less than this many convergence
/// tolerances of the connection.
const NOISE_TOLERANCES: f64 = 10.0;

/// The adaptive step's state between steps.
pub(crate) struct Adaptive {
    settings: AdaptiveStep,
    /// `sizes[k]`: the synchronisation step / 2^k.
    sizes: Vec<Time>,
    /// The halvings in force.
    level: usize,
    /// Calm steps in a row at this level.
    calm: u32,
    /// Times of the accepted values (s): the last, the one before, the one
    /// before that; `known` of them are real.
    times: [f64; 3],
    known: usize,
    /// Per connection: the group whose scale judges it (its port kind, or
    /// itself for a port without a unit of measure).
    group: Vec<usize>,
    /// Per connection: whether the estimate judges it (`kinds`).
    judged: Vec<bool>,
    /// Per group: the largest |value| accepted so far.
    scale: Vec<f64>,
    pub(crate) counters: StepSizes,
}

/// Where an error estimate comes from.
#[derive(Copy, Clone)]
enum Source {
    Connection(usize),
    Unit(usize),
}

/// What became of an attempted step.
enum Verdict {
    Accept {
        over_tolerance: bool,
    },
    Repeat {
        failed: bool,
    },
    /// Failed at the smallest step: the run's error.
    Fail,
}

impl Adaptive {
    /// The steps `settings` allows within the synchronisation step `step`.
    pub(crate) fn new(
        settings: AdaptiveStep,
        step: Time,
        connections: &[Connection],
    ) -> Result<Adaptive, MasterError> {
        let min = settings.min_step;
        if min > step.as_secs() {
            return Err(MasterError::Invalid(format!(
                "adaptive.min_step {min} s: expected at most the synchronisation step ({} s), the largest step",
                step.as_secs()
            )));
        }
        let mut sizes = vec![step];
        while sizes.len() <= MAX_HALVINGS as usize {
            let last = sizes[sizes.len() - 1];
            if 0.5 * last.as_secs() < min * (1.0 - 1e-12) {
                break;
            }
            match last.split(2) {
                Some(half) => sizes.push(half),
                None => {
                    return Err(MasterError::Invalid(format!(
                        "adaptive.min_step {min} s: {} s halved is not a whole number of nanoseconds; choose a synchronisation step with more factors of two or a larger min_step",
                        last.as_secs()
                    )));
                }
            }
        }
        let group = groups(connections);
        let judged = (connections.iter())
            .map(|c| settings.kinds.is_empty() || settings.kinds.contains(&c.kind))
            .collect();
        let counters = StepSizes {
            accepted: vec![0; sizes.len()],
            sizes_s: sizes.iter().map(|h| h.as_secs()).collect(),
            ..StepSizes::default()
        };
        Ok(Adaptive {
            settings,
            sizes,
            level: 0,
            calm: 0,
            times: [0.0; 3],
            known: 0,
            scale: vec![0.0; group.iter().max().map_or(0, |g| g + 1)],
            group,
            judged,
            counters,
        })
    }

    /// The values at `t0` are the first accepted ones; the run starts at the
    /// smallest step (nothing is known of the interface's derivatives yet).
    pub(crate) fn start(&mut self, t0: Time, values: &[f64]) {
        self.level = self.sizes.len() - 1;
        self.calm = 0;
        self.times = [t0.as_secs(), 0.0, 0.0];
        self.known = 1;
        self.scale.fill(0.0);
        self.follow(values);
    }

    /// Raises each group's scale to the values accepted.
    fn follow(&mut self, values: &[f64]) {
        for (&g, v) in self.group.iter().zip(values) {
            self.scale[g] = self.scale[g].max(v.abs());
        }
    }

    /// Weights of the accepted values (last, before, earlier) that extrapolate
    /// them to `t` with a polynomial of the extrapolation's order (at most
    /// what the known values allow).
    pub(crate) fn weights(&self, extrapolation: Extrapolation, t: f64) -> [f64; 3] {
        let order = match extrapolation {
            Extrapolation::Constant => 0,
            Extrapolation::Linear => 1,
            Extrapolation::Quadratic => 2,
        };
        self.lagrange(order.min(self.known - 1), t)
    }

    /// Lagrange weights through the last `order + 1` accepted times at `t`.
    fn lagrange(&self, order: usize, t: f64) -> [f64; 3] {
        let mut w = [0.0; 3];
        for (i, wi) in w.iter_mut().enumerate().take(order + 1) {
            *wi = (0..=order)
                .filter(|&j| j != i)
                .map(|j| (t - self.times[j]) / (self.times[i] - self.times[j]))
                .product();
        }
        w
    }

    /// The step's error estimate relative to the tolerance: the connections'
    /// (0 until three values are known) and the units' own, the largest and
    /// where it came from.
    fn estimate(&self, master: &Master, t: f64) -> (f64, Source) {
        let mut worst = (0.0_f64, Source::Connection(0));
        if self.settings.interface && self.known >= 3 {
            let w = self.lagrange(2, t);
            for c in (0..master.connections.len()).filter(|&c| self.judged[c]) {
                let predicted = w[0] * master.accepted[c]
                    + w[1] * master.accepted_before[c]
                    + w[2] * master.accepted_earlier[c];
                let allowed = (self.settings.tolerance * self.scale[self.group[c]])
                    .max(NOISE_TOLERANCES * master.tolerance[c]);
                let scaled = (master.value[c] - predicted).abs() / allowed;
                if scaled > worst.0 {
                    worst = (scaled, Source::Connection(c));
                }
            }
        }
        if let Some(allowed) = self.settings.displacement {
            for (u, unit) in master.units.iter().enumerate() {
                let scaled = unit.local_error().unwrap_or(0.0) / allowed;
                if scaled > worst.0 {
                    worst = (scaled, Source::Unit(u));
                }
            }
        }
        worst
    }

    /// The step accepted at `t` with `values`.
    fn accept(&mut self, t: f64, master: &Master, (estimate, source): (f64, Source)) {
        self.times = [t, self.times[0], self.times[1]];
        self.known = (self.known + 1).min(3);
        self.follow(&master.value);
        self.counters.accepted[self.level] += 1;
        if estimate > self.counters.largest_estimate {
            self.counters.largest_estimate = estimate;
            self.counters.largest_at = match source {
                Source::Connection(c) => master.connections[c].label.clone(),
                Source::Unit(u) => format!("unit `{}`", master.units[u].name),
            };
        }
        self.calm = if estimate < CALM_FRACTION {
            self.calm + 1
        } else {
            0
        };
    }

    /// An attempt's fate: repeated at half the size while a smaller step
    /// exists, else accepted (counted when over the tolerance) or the error.
    fn judge(&self, outcome: &Result<(u32, f64, bool), MasterError>, estimate: f64) -> Verdict {
        let finest = self.level + 1 == self.sizes.len();
        match outcome {
            Err(_) if finest => Verdict::Fail,
            Err(_) => Verdict::Repeat { failed: true },
            Ok(_) if estimate > 1.0 && !finest => Verdict::Repeat { failed: false },
            Ok(_) => Verdict::Accept {
                over_tolerance: estimate > 1.0,
            },
        }
    }
}

/// Per connection, the group whose largest value is its scale: one per port
/// kind with a unit of measure, one per connection without.
fn groups(connections: &[Connection]) -> Vec<usize> {
    let kinds = PortKind::ALL.len();
    let mut own = kinds;
    connections
        .iter()
        .map(|c| match c.kind {
            PortKind::Generic => {
                own += 1;
                own - 1
            }
            kind => PortKind::ALL.iter().position(|&k| k == kind).unwrap_or(0),
        })
        .collect()
}

/// Whether a failed step may be repeated at a smaller step: the failures a
/// shorter step can cure, not a wrong set-up or a unit asking to end.
fn curable(error: &MasterError) -> bool {
    match error {
        MasterError::Unit { source, .. } => {
            !matches!(source, slender_contract::UnitError::EndRequested(_))
        }
        MasterError::NonFinite { .. }
        | MasterError::NotConverged { .. }
        | MasterError::SingularJacobian { .. } => true,
        _ => false,
    }
}

impl Master {
    /// One synchronisation step made of adaptive steps.
    pub(super) fn step_adaptive(&mut self) -> Result<(), MasterError> {
        let mut adaptive = self
            .adaptive
            .take()
            .ok_or_else(|| MasterError::Invalid("adaptive state missing".into()))?;
        let result = self.adaptive_steps(&mut adaptive);
        self.adaptive = Some(adaptive);
        result
    }

    fn adaptive_steps(&mut self, adaptive: &mut Adaptive) -> Result<(), MasterError> {
        let end = self.time + self.step_size;
        let start = self.time;
        while self.time < end {
            self.save_every_unit()?;
            self.adaptive_attempts(adaptive)?;
            self.maybe_double(adaptive, start);
        }
        Ok(())
    }

    /// Attempts the step from the saved units, halving until it is accepted.
    fn adaptive_attempts(&mut self, a: &mut Adaptive) -> Result<(), MasterError> {
        loop {
            self.h = a.sizes[a.level];
            let t_end = (self.time + self.h).as_secs();
            self.weights = Some(a.weights(self.settings.extrapolation, t_end));
            // A failed attempt's residual is not the run's: the step is
            // repeated shorter.
            let residuals = (self.counters.last_residual, self.counters.max_residual);
            let outcome = self.solve_step();
            if let Err(e) = &outcome
                && !curable(e)
            {
                return outcome.map(|_| ());
            }
            let estimate = match outcome {
                Ok(_) => a.estimate(self, t_end),
                Err(_) => (f64::INFINITY, Source::Connection(0)),
            };
            match a.judge(&outcome, estimate.0) {
                Verdict::Fail => return outcome.map(|_| ()),
                Verdict::Repeat { failed } => {
                    (self.counters.last_residual, self.counters.max_residual) = residuals;
                    self.restore_every_unit()?;
                    self.forget_step_history();
                    a.level += 1;
                    a.calm = 0;
                    if failed {
                        a.counters.failed += 1;
                    } else {
                        a.counters.rejected += 1;
                    }
                }
                Verdict::Accept { over_tolerance } => {
                    let solved = outcome?;
                    a.accept(t_end, self, estimate);
                    a.counters.over_tolerance += u64::from(over_tolerance);
                    return self.accept_step(solved);
                }
            }
        }
    }

    /// Doubles the step after enough calm steps, where the time since the
    /// synchronisation step's `start` is a multiple of the doubled step.
    fn maybe_double(&mut self, a: &mut Adaptive, start: Time) {
        if a.level == 0 || a.calm < a.settings.calm_steps {
            return;
        }
        let offset = (self.time - start).as_nanos();
        if offset % a.sizes[a.level - 1].as_nanos() == 0 {
            a.level -= 1;
            a.calm = 0;
            self.forget_step_history();
        }
    }

    /// Newton's kept Jacobian and the accelerator's reused secants belong to
    /// the step size they were found at.
    fn forget_step_history(&mut self) {
        self.accelerator.forget();
        if let Some(work) = self.newton.as_mut() {
            work.forget();
        }
    }

    /// Saves every unit at the step's start (a repeated step rolls back the
    /// units the iteration does not repeat too).
    fn save_every_unit(&mut self) -> Result<(), MasterError> {
        for unit in &mut self.units {
            unit.save(self.time)?;
        }
        Ok(())
    }

    fn restore_every_unit(&mut self) -> Result<(), MasterError> {
        for unit in &mut self.units {
            unit.restore(self.time, 0)?;
            self.counters.rollbacks += 1;
        }
        Ok(())
    }
}
