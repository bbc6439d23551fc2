//! Progress of a study's runs: which of how many has finished and about how
//! long the rest will take (`study`, `fidelity` and `uq` were silent for
//! minutes, or said only k of N).

use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

/// Finished runs out of a total, counted from any thread.
pub struct Progress {
    total: usize,
    finished: AtomicUsize,
    /// Runs made (not read back from an earlier study): the estimate's rate.
    made: AtomicUsize,
    start: Instant,
}

impl Progress {
    /// The progress of `total` runs, starting now.
    pub fn new(total: usize) -> Progress {
        Progress {
            total,
            finished: AtomicUsize::new(0),
            made: AtomicUsize::new(0),
            start: Instant::now(),
        }
    }

    /// Counts one more run finished (`made`: run now, not read back) and says
    /// so: `[k/N]`, with the time left while runs remain.
    pub fn tick(&self, made: bool) -> String {
        let k = self.finished.fetch_add(1, Ordering::Relaxed) + 1;
        let made = self.made.fetch_add(usize::from(made), Ordering::Relaxed) + usize::from(made);
        let elapsed = self.start.elapsed().as_secs_f64();
        match left(elapsed, made, self.total.saturating_sub(k)) {
            Some(t) => format!("[{k}/{}, about {} left]", self.total, words(t)),
            None => format!("[{k}/{}]", self.total),
        }
    }
}

/// Seconds left for `remaining` runs at the mean wall time of the `made` ones
/// so far (runs at once share it, so parallel runs count as they should); the
/// costliest start first, so the estimate errs long. None when nothing
/// remains or nothing has been timed.
fn left(elapsed: f64, made: usize, remaining: usize) -> Option<f64> {
    (remaining > 0 && made > 0).then(|| elapsed / made as f64 * remaining as f64)
}

/// A duration in words, to the precision worth reading: `12 s`, `4 min 10 s`,
/// `2 h 5 min`.
fn words(seconds: f64) -> String {
    let s = seconds.max(0.0).round() as u64;
    match s {
        0 => "less than 1 s".to_owned(),
        1..60 => format!("{s} s"),
        60..3600 => format!("{} min {} s", s / 60, s % 60),
        _ => format!("{} h {} min", s / 3600, (s % 3600) / 60),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_time_left_is_the_mean_run_time_over_the_runs_remaining() {
        // 4 runs made in 40 s, 6 remain: 60 s.
        assert_eq!(left(40.0, 4, 6), Some(60.0));
        assert_eq!(left(40.0, 4, 0), None);
        assert_eq!(left(0.1, 0, 6), None);
        assert_eq!(words(59.4), "59 s");
        assert_eq!(words(0.3), "less than 1 s");
        assert_eq!(words(250.0), "4 min 10 s");
        assert_eq!(words(7500.0), "2 h 5 min");
        let p = Progress::new(3);
        assert!(p.tick(false).starts_with("[1/3]"));
        assert!(p.tick(true).starts_with("[2/3, about "));
        assert_eq!(p.tick(true), "[3/3]");
    }
}
