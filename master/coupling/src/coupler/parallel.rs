//! A Jacobi sweep on threads: every connection is torn, so within a sweep no
//! unit reads another's fresh outputs and the units step side by side on the
//! master's thread pool (`[master] threads`). Each unit steps exactly as it
//! would alone, so the results are bit-identical to stepping them one after
//! another, for any thread count. How the units are shared out among the
//! threads: [`share_out`].

use super::{Master, link_value};
use crate::adapter::UnitAdapter;
use crate::error::MasterError;
use std::sync::Mutex;
use std::time::Instant;

impl Master {
    /// The thread pool of a Jacobi scheme with more than one thread (none
    /// where the units step one after another: `sequential`).
    pub(super) fn thread_pool(
        threads: u32,
        sequential: bool,
    ) -> Result<Option<std::sync::Arc<rayon::ThreadPool>>, MasterError> {
        if threads <= 1 || sequential {
            return Ok(None);
        }
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads as usize)
            .thread_name(|i| format!("slender-sweep-{i}"))
            .build()
            .map(|pool| Some(std::sync::Arc::new(pool)))
            .map_err(|e| MasterError::Invalid(format!("threads {threads}: {e}")))
    }

    /// [`Master::sweep`] with the units stepped on the pool; the first failure
    /// in the sweep order is the sweep's.
    pub(super) fn sweep_parallel(&mut self, iteration: u32) -> Result<(), MasterError> {
        let (t, h) = (self.time, self.h);
        let repeat = self.first_sweep_done;
        self.first_sweep_done = true;
        for (u, unit) in self.units.iter_mut().enumerate() {
            if repeat && !self.iterated[u] {
                continue;
            }
            for (p, source) in self.input_connection[u].iter().enumerate() {
                if let Some(c) = *source {
                    unit.inputs[p] = match self.tear_index[c] {
                        Some(k) => self.x[k],
                        None => self.value[c],
                    };
                }
            }
        }
        let Master {
            units,
            iterated,
            pool,
            ..
        } = self;
        let pool = pool
            .as_ref()
            .ok_or_else(|| MasterError::Invalid("parallel sweep without a pool".into()))?;
        let stepping = |u: usize| !repeat || iterated[u];
        pool.install(|| {
            share_out(units, &stepping, &|unit: &mut UnitAdapter| {
                let started = Instant::now();
                unit.failure = unit.step(t, h, iteration).err();
                unit.step_time += started.elapsed();
            });
        });
        for i in 0..self.order.len() {
            let u = self.order[i];
            if let Some(failure) = self.units[u].failure.take() {
                return Err(failure);
            }
        }
        for i in 0..self.order.len() {
            let u = self.order[i];
            if repeat && !self.iterated[u] {
                continue;
            }
            for &c in &self.outgoing[u] {
                self.value[c] = link_value(&self.connections[c], &self.units[u].outputs);
            }
        }
        for (k, &c) in self.torn.iter().enumerate() {
            self.gx[k] = self.value[c];
        }
        Ok(())
    }
}

/// Runs `work` on every unit that `takes_part`, each unit alone, on every
/// thread of the pool the caller runs on. The threads take the
/// units in their order from one shared queue, each taking the next as it
/// finishes one; a unit is never a job of the pool's, so a thread waiting
/// inside a unit for help (a 3D line's wave sums) takes only such small work,
/// never a whole unit, and the threads that run out of units help with the
/// last ones' shared work. The caller takes part and carries on with the
/// step when all are done.
pub(crate) fn share_out<U: Send>(
    units: &mut [U],
    takes_part: &(impl Fn(usize) -> bool + Sync),
    work: &(impl Fn(&mut U) + Sync),
) {
    let queue = Mutex::new(
        (units.iter_mut().enumerate())
            .filter(|(u, _)| takes_part(*u))
            .map(|(_, unit)| unit),
    );
    let take_units = || {
        loop {
            // The guard is dropped at the end of the statement: the unit
            // steps outside the lock.
            let next = queue.lock().unwrap_or_else(|e| e.into_inner()).next();
            match next {
                Some(unit) => work(unit),
                None => break,
            }
        }
    };
    on_threads(rayon::current_num_threads(), &take_units);
}

/// Runs `work` on `threads` threads of the current pool (the caller's one
/// of them), returning when all are done.
fn on_threads(threads: usize, work: &(impl Fn() + Sync)) {
    if threads <= 1 {
        return work();
    }
    rayon::join(work, || on_threads(threads - 1, work));
}

#[cfg(test)]
mod tests {
    use super::share_out;
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// Every unit that takes part is worked once and only those, on any
    /// number of threads, more or fewer than the units; and the work is
    /// spread over the threads when each unit waits for the others.
    #[test]
    fn each_unit_that_takes_part_is_worked_once_on_any_thread_count() {
        for threads in 1..=4 {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            for n in [0, 1, 3, 10] {
                let mut units = vec![0u32; n];
                pool.install(|| {
                    share_out(&mut units, &|u| u % 3 != 1, &|unit| *unit += 1);
                });
                let expected: Vec<u32> = (0..n).map(|u| u32::from(u % 3 != 1)).collect();
                assert_eq!(units, expected, "{threads} threads, {n} units");
            }
            // Each unit waits until `threads` units are running at once: on
            // one thread that would hang, so only from two.
            if threads >= 2 {
                let running = AtomicUsize::new(0);
                let mut units = vec![0u32; threads];
                pool.install(|| {
                    share_out(&mut units, &|_| true, &|unit| {
                        running.fetch_add(1, Ordering::SeqCst);
                        let started = std::time::Instant::now();
                        while running.load(Ordering::SeqCst) < threads
                            && started.elapsed().as_secs() < 10
                        {
                            std::thread::yield_now();
                        }
                        *unit = running.load(Ordering::SeqCst) as u32;
                    });
                });
                assert!(units.iter().all(|&u| u as usize == threads), "{units:?}");
            }
        }
    }
}
