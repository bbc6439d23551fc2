//! Paced real-time runs (`slender run --realtime`): each synchronisation step
//! must be computed before the wall clock reaches its end, as when a scene
//! drives a rig. The run waits for the clock when it is ahead (sleeping, then
//! spinning for the last 0.2 ms) and never waits to catch up when it is behind:
//! the schedule stays absolute, like a rig's. It reports the computing time per
//! step (histogram in tenths of the step, median, 99th and 99.9th percentiles,
//! worst) and its overruns, so a user knows whether the scene can drive a rig.
//! Its memory is bounded whatever the run's length: quantiles come from a
//! log-spaced histogram, the overrun log keeps the first `KEPT_OVERRUNS` and
//! counts the rest, and more than `[simulation] max_overruns` overruns stop
//! the run.

use serde::Serialize;
use std::time::{Duration, Instant};

/// Overruns listed one by one; later ones are only counted.
pub const KEPT_OVERRUNS: usize = 1000;

/// Bins of the computing-time histogram per decade, from 1 ns to 1000 s:
/// quantiles to within 1.2 % (one bin).
const BINS_PER_DECADE: f64 = 200.0;
const DECADES: f64 = 12.0;

/// A step that finished after its deadline.
#[derive(Clone, Debug, Serialize)]
pub struct Overrun {
    /// Step index (0 is the first step after initialisation).
    pub step: usize,
    /// Simulated time at the step's end (s).
    pub time_s: f64,
    /// Its computing time (s).
    pub compute_s: f64,
    /// How late it finished (s).
    pub late_s: f64,
}

/// The computing times of a paced run.
#[derive(Clone, Debug, Serialize)]
pub struct RealtimeReport {
    /// The synchronisation step (s): each step's deadline.
    pub step_s: f64,
    /// Steps timed.
    pub steps: usize,
    /// Median computing time of a step (s).
    pub median_s: f64,
    /// Its 99th percentile (s).
    pub p99_s: f64,
    /// Its 99.9th percentile (s).
    pub p999_s: f64,
    /// The worst step's computing time (s).
    pub worst_s: f64,
    /// Step whose computing time was the worst.
    pub worst_step: usize,
    /// Steps per tenth of the synchronisation step: bin k counts computing
    /// times in [k, k + 1) tenths; the last bin everything from one step on.
    pub histogram: Vec<usize>,
    /// Steps that finished after their deadline.
    pub overrun_count: usize,
    /// The first `KEPT_OVERRUNS` of them.
    pub overruns: Vec<Overrun>,
}

/// Keeps the schedule and records each step.
pub struct Pacer {
    start: Instant,
    step: Duration,
    /// Computing times per log-spaced bin (see `BINS_PER_DECADE`).
    fine: Vec<usize>,
    histogram: Vec<usize>,
    steps: usize,
    worst: (usize, f64),
    overruns: Vec<Overrun>,
    overrun_count: usize,
    max_overruns: u64,
    began: Instant,
}

/// How long before a deadline the pacer stops sleeping and spins.
const SPIN: Duration = Duration::from_micros(200);

impl Pacer {
    /// A schedule of steps of `step_s` seconds from now, stopped after more
    /// than `max_overruns` overruns.
    pub fn new(step_s: f64, max_overruns: u64) -> Pacer {
        let now = Instant::now();
        Pacer {
            start: now,
            step: Duration::from_secs_f64(step_s),
            fine: vec![0; (BINS_PER_DECADE * DECADES) as usize + 1],
            histogram: vec![0; 11],
            steps: 0,
            worst: (0, 0.0),
            overruns: Vec::new(),
            overrun_count: 0,
            max_overruns,
            began: now,
        }
    }

    /// Counts a step's computing time `c` (s).
    fn record(&mut self, index: usize, c: f64) {
        self.steps += 1;
        let step = self.step.as_secs_f64();
        self.histogram[((c / step * 10.0) as usize).min(10)] += 1;
        let bin = ((c.max(1e-9).log10() + 9.0) * BINS_PER_DECADE).ceil();
        let last = self.fine.len() - 1;
        self.fine[(bin.max(0.0) as usize).min(last)] += 1;
        if c > self.worst.1 {
            self.worst = (index, c);
        }
    }

    /// Marks the start of a step's computation.
    pub fn begin(&mut self) {
        self.began = Instant::now();
    }

    /// Marks the end of step `index` (simulated time `time_s` at its end), then
    /// waits for its deadline if it is early. An error once more than
    /// `max_overruns` steps overran: the run cannot keep pace.
    pub fn end(&mut self, index: usize, time_s: f64) -> Result<(), crate::run::RunError> {
        let done = Instant::now();
        let compute = done.duration_since(self.began).as_secs_f64();
        self.record(index, compute);
        let deadline = self.start
            + self
                .step
                .saturating_mul(u32::try_from(index + 1).unwrap_or(u32::MAX));
        if done > deadline {
            self.overrun_count += 1;
            if self.overruns.len() < KEPT_OVERRUNS {
                self.overruns.push(Overrun {
                    step: index,
                    time_s,
                    compute_s: compute,
                    late_s: done.duration_since(deadline).as_secs_f64(),
                });
            }
            if self.overrun_count as u64 > self.max_overruns {
                let first = &self.overruns[0];
                return Err(crate::run::RunError::Pace(format!(
                    "the paced run cannot keep pace: {} of {} steps finished after their deadline (the first at t = {} s, {:.3e} s late; the step is {} s), more than simulation.max_overruns = {}; raise it to go on regardless",
                    self.overrun_count,
                    self.steps,
                    first.time_s,
                    first.late_s,
                    self.step.as_secs_f64(),
                    self.max_overruns
                )));
            }
            return Ok(());
        }
        let left = deadline - done;
        if left > SPIN {
            std::thread::sleep(left - SPIN);
        }
        while Instant::now() < deadline {
            std::hint::spin_loop();
        }
        Ok(())
    }

    /// The figures so far.
    pub fn report(&self) -> RealtimeReport {
        // The quantile's bin's upper edge: within one bin of the exact value.
        let quantile = |p: f64| {
            let rank = (p * self.steps as f64).ceil().max(1.0) as usize;
            let mut seen = 0;
            for (bin, &count) in self.fine.iter().enumerate() {
                seen += count;
                if seen >= rank {
                    let edge = 10f64.powf(bin as f64 / BINS_PER_DECADE - 9.0);
                    return edge.min(self.worst.1);
                }
            }
            self.worst.1
        };
        let empty = self.steps == 0;
        RealtimeReport {
            step_s: self.step.as_secs_f64(),
            steps: self.steps,
            median_s: if empty { 0.0 } else { quantile(0.5) },
            p99_s: if empty { 0.0 } else { quantile(0.99) },
            p999_s: if empty { 0.0 } else { quantile(0.999) },
            worst_s: self.worst.1,
            worst_step: self.worst.0,
            histogram: self.histogram.clone(),
            overrun_count: self.overrun_count,
            overruns: self.overruns.clone(),
        }
    }
}
