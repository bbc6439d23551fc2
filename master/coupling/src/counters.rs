//! What a run did: steps, iterations, rollbacks, residuals and time per unit.

use serde::Serialize;

/// Per-unit counters.
#[derive(Clone, Debug, Default, Serialize)]
pub struct UnitCounters {
    /// The unit's name.
    pub name: String,
    /// `do_step` calls, including repeated and Jacobian-probing ones.
    pub do_step_calls: u64,
    /// Wall time of its `set_inputs`, `do_step` and `outputs` calls in the sweeps,
    /// with the copying of its inputs (s).
    pub step_time_s: f64,
    /// Internal solver iterations the unit reported (e.g. Newton iterations).
    pub solver_iterations: u64,
}

/// Counters of a whole run.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Counters {
    /// Iterations needed to make the initial values of loops consistent.
    pub initialization_iterations: u32,
    /// Residual at the exit of initialisation (see `last_residual`).
    pub initialization_residual: f64,
    /// Synchronisation steps taken.
    pub steps: u64,
    /// Iterations over all steps (1 per step for non-iterative schemes; Newton
    /// iterations for Newton, not counting the Jacobian probes).
    pub iterations: u64,
    /// `iteration_histogram[k]`: steps that took k iterations.
    pub iteration_histogram: Vec<u64>,
    /// Units restored to the start of a step (one per unit per repetition).
    pub rollbacks: u64,
    /// Steps (initialisation included) accepted without meeting the tolerances
    /// (`on_max_iterations = "accept"`).
    pub non_converged_steps: u64,
    /// Interface Jacobians evaluated by Newton.
    pub jacobian_evaluations: u64,
    /// Steps started again without the secants reused from earlier steps, after
    /// a unit failed on an iterate they proposed (IQN-ILS with `reuse_steps`).
    /// Left out of the summary while zero.
    #[serde(skip_serializing_if = "is_zero")]
    pub restarts: u64,
    /// Steps closed after one sweep by the units' linear correction
    /// (`newton.one_sweep`). Left out of the summary while zero.
    #[serde(skip_serializing_if = "is_zero")]
    pub corrected_steps: u64,
    /// Residual at the exit of the last step: the largest |change| / tolerance over
    /// the connections (<= 1 means converged); 0 for non-iterative schemes.
    pub last_residual: f64,
    /// Largest residual at exit over all steps.
    pub max_residual: f64,
    /// The coupled load a unit's statics were solved under that changed most
    /// over the first step (see the master's start check); absent when no
    /// unit solves its statics under a coupled load.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub start_load: Option<crate::coupler::StartLoad>,
    /// The steps an adaptive coupling step took (`[master.adaptive]`);
    /// absent with a fixed step.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub adaptive: Option<StepSizes>,
    /// Per unit, in the system's order.
    pub units: Vec<UnitCounters>,
}

/// What an adaptive coupling step did: the steps accepted at each size, the
/// steps rejected and why, the largest error estimate accepted.
#[derive(Clone, Debug, Default, Serialize)]
pub struct StepSizes {
    /// `accepted[k]`: steps accepted at the synchronisation step / 2^k.
    pub accepted: Vec<u64>,
    /// The step sizes of `accepted` (s).
    pub sizes_s: Vec<f64>,
    /// Steps repeated at half the size because the error estimate exceeded
    /// the tolerance.
    pub rejected: u64,
    /// Steps repeated at half the size because they failed (a unit's error,
    /// no convergence within `max_iterations`, a non-finite value).
    pub failed: u64,
    /// Steps accepted at the smallest size with an estimate over the
    /// tolerance (nothing smaller was allowed).
    pub over_tolerance: u64,
    /// The largest error estimate of an accepted step, relative to the
    /// tolerance (<= 1 unless `over_tolerance` > 0).
    pub largest_estimate: f64,
    /// The connection that gave `largest_estimate` (absent while none did).
    #[serde(skip_serializing_if = "String::is_empty")]
    pub largest_at: String,
}

impl StepSizes {
    /// All steps accepted, whatever their size.
    pub fn accepted_steps(&self) -> u64 {
        self.accepted.iter().sum()
    }
}

fn is_zero(n: &u64) -> bool {
    *n == 0
}

impl Counters {
    /// Counters for the named units, all zero.
    pub fn new<'a>(names: impl Iterator<Item = &'a str>) -> Counters {
        Counters {
            units: names
                .map(|n| UnitCounters {
                    name: n.to_owned(),
                    ..UnitCounters::default()
                })
                .collect(),
            ..Counters::default()
        }
    }

    /// Records a finished step.
    pub fn record_step(&mut self, iterations: u32, residual: f64, converged: bool) {
        self.steps += 1;
        self.iterations += u64::from(iterations);
        let k = iterations as usize;
        if self.iteration_histogram.len() <= k {
            self.iteration_histogram.resize(k + 1, 0);
        }
        self.iteration_histogram[k] += 1;
        self.record_residual(residual);
        if !converged {
            self.non_converged_steps += 1;
        }
    }

    /// Records the residual at the exit of a step (also of one that failed).
    pub fn record_residual(&mut self, residual: f64) {
        self.last_residual = residual;
        self.max_residual = self.max_residual.max(residual);
    }

    /// `do_step` calls of all units.
    pub fn do_step_calls(&self) -> u64 {
        self.units.iter().map(|u| u.do_step_calls).sum()
    }

    /// Time inside all units' `do_step` (s).
    pub fn unit_time_s(&self) -> f64 {
        self.units.iter().map(|u| u.step_time_s).sum()
    }

    /// Mean iterations per step.
    pub fn mean_iterations(&self) -> f64 {
        if self.steps == 0 {
            0.0
        } else {
            self.iterations as f64 / self.steps as f64
        }
    }
}
