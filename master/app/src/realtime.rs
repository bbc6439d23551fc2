//! Paced real-time runs (`slender run --realtime`): each synchronisation step
//! must be computed before the wall clock reaches its end, as when a scene
//! drives a rig. The run waits for the clock when it is ahead (sleeping, then
//! spinning for the last 0.2 ms) and never waits to catch up when it is behind:
//! the schedule stays absolute, like a rig's. It reports the computing time per
//! step (histogram in tenths of the step, median, 99th and 99.9th percentiles,
//! worst) and every overrun, so a user knows whether the scene can drive a rig.

use serde::Serialize;
use std::time::{Duration, Instant};

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
    pub step_s: f64,
    pub steps: usize,
    pub median_s: f64,
    pub p99_s: f64,
    pub p999_s: f64,
    pub worst_s: f64,
    /// Step whose computing time was the worst.
    pub worst_step: usize,
    /// Steps per tenth of the synchronisation step: bin k counts computing
    /// times in [k, k + 1) tenths; the last bin everything from one step on.
    pub histogram: Vec<usize>,
    pub overruns: Vec<Overrun>,
}

/// Keeps the schedule and records each step.
pub struct Pacer {
    start: Instant,
    step: Duration,
    compute: Vec<f64>,
    overruns: Vec<Overrun>,
    began: Instant,
}

/// How long before a deadline the pacer stops sleeping and spins.
const SPIN: Duration = Duration::from_micros(200);

impl Pacer {
    /// A schedule of `steps` steps of `step_s` seconds from now.
    pub fn new(step_s: f64, steps: usize) -> Pacer {
        let now = Instant::now();
        Pacer {
            start: now,
            step: Duration::from_secs_f64(step_s),
            compute: Vec::with_capacity(steps),
            overruns: Vec::new(),
            began: now,
        }
    }

    /// Marks the start of a step's computation.
    pub fn begin(&mut self) {
        self.began = Instant::now();
    }

    /// Marks the end of step `index` (simulated time `time_s` at its end), then
    /// waits for its deadline if it is early.
    pub fn end(&mut self, index: usize, time_s: f64) {
        let done = Instant::now();
        let compute = done.duration_since(self.began).as_secs_f64();
        self.compute.push(compute);
        let deadline = self.start
            + self
                .step
                .saturating_mul(u32::try_from(index + 1).unwrap_or(u32::MAX));
        if done > deadline {
            self.overruns.push(Overrun {
                step: index,
                time_s,
                compute_s: compute,
                late_s: done.duration_since(deadline).as_secs_f64(),
            });
            return;
        }
        let left = deadline - done;
        if left > SPIN {
            std::thread::sleep(left - SPIN);
        }
        while Instant::now() < deadline {
            std::hint::spin_loop();
        }
    }

    /// The figures so far.
    pub fn report(&self) -> RealtimeReport {
        let mut sorted = self.compute.clone();
        sorted.sort_by(f64::total_cmp);
        let quantile = |p: f64| {
            sorted
                .get(((p * sorted.len() as f64).ceil() as usize).saturating_sub(1))
                .copied()
                .unwrap_or(0.0)
        };
        let step = self.step.as_secs_f64();
        let mut histogram = vec![0usize; 11];
        for &c in &self.compute {
            histogram[((c / step * 10.0) as usize).min(10)] += 1;
        }
        let (worst_step, worst) =
            self.compute
                .iter()
                .copied()
                .enumerate()
                .fold(
                    (0, 0.0),
                    |(k, w), (i, c)| if c > w { (i, c) } else { (k, w) },
                );
        RealtimeReport {
            step_s: step,
            steps: self.compute.len(),
            median_s: quantile(0.5),
            p99_s: quantile(0.99),
            p999_s: quantile(0.999),
            worst_s: worst,
            worst_step,
            histogram,
            overruns: self.overruns.clone(),
        }
    }
}
