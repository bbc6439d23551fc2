//! A Jacobi sweep on threads: every connection is torn, so within a sweep no
//! unit reads another's fresh outputs and the units step side by side on the
//! master's thread pool (`[master] threads`). Each unit steps exactly as it
//! would alone, so the results are bit-identical to stepping them one after
//! another, for any thread count.

use super::{Master, link_value};
use crate::error::MasterError;
use rayon::prelude::*;
use std::time::Instant;

impl Master {
    /// The thread pool of a Jacobi scheme with more than one thread (none
    /// where the units step one after another: `sequential`).
    pub(super) fn thread_pool(
        threads: u32,
        sequential: bool,
    ) -> Result<Option<rayon::ThreadPool>, MasterError> {
        if threads <= 1 || sequential {
            return Ok(None);
        }
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads as usize)
            .thread_name(|i| format!("slender-sweep-{i}"))
            .build()
            .map(Some)
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
        pool.install(|| {
            units.par_iter_mut().enumerate().for_each(|(u, unit)| {
                if repeat && !iterated[u] {
                    return;
                }
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
