//! Independent runs on a few threads (the studies' runs): each worker takes the
//! next task when it is free, in the order given (the likely costliest first, so
//! the longest run does not start last), and the outcomes come back in the
//! tasks' order, so results never depend on the number of jobs.

use std::sync::atomic::{AtomicUsize, Ordering};

/// Runs `run` on every task on `jobs` threads, starting them in `order` (task
/// indices), and returns the outcomes in the tasks' order.
pub fn run_all<T: Sync, O: Send>(
    tasks: &[T],
    order: &[usize],
    jobs: usize,
    run: impl Fn(&T) -> O + Sync,
) -> Vec<O> {
    let next = AtomicUsize::new(0);
    // Each worker keeps what it ran; a run that panics (a bug, not bad input)
    // panics the study as it would without threads.
    let mut done: Vec<(usize, O)> = std::thread::scope(|scope| {
        let workers: Vec<_> = (0..jobs.clamp(1, tasks.len().max(1)))
            .map(|_| {
                scope.spawn(|| {
                    let mut mine = Vec::new();
                    while let Some(&task) = order.get(next.fetch_add(1, Ordering::Relaxed)) {
                        mine.push((task, run(&tasks[task])));
                    }
                    mine
                })
            })
            .collect();
        workers
            .into_iter()
            .flat_map(|w| w.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
            .collect()
    });
    done.sort_by_key(|(task, _)| *task);
    done.into_iter().map(|(_, outcome)| outcome).collect()
}

#[cfg(test)]
mod tests {
    use super::run_all;

    #[test]
    fn outcomes_come_back_in_the_tasks_order_whatever_the_jobs() {
        let tasks: Vec<u64> = (0..17).collect();
        let order: Vec<usize> = (0..17).rev().collect();
        for jobs in [1, 2, 5] {
            let out = run_all(&tasks, &order, jobs, |t| t * t);
            assert_eq!(out, tasks.iter().map(|t| t * t).collect::<Vec<_>>());
        }
    }
}
