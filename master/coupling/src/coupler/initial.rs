//! Initialisation of a coupled system: consistent start values of loops, found
//! like a zero-length step; Jacobi schemes start from an upstream-first pass.

use super::{Master, link_value};
use crate::error::MasterError;
use crate::order::tears;
use slender_contract::Time;

impl Master {
    /// Initialises every unit at `t0`, in order, each fed by the units initialised
    /// before it. Where connections form a loop, initialisation is a zero-length
    /// step solved like the others: the torn inputs start at their start values
    /// (scene `inputs`) and are iterated with the run's acceleration (plain fixed
    /// point for non-iterative schemes) until consistent. `initialize` restarts a
    /// unit from its parameters, so no rollback is needed here.
    pub fn initialize(&mut self, t0: Time) -> Result<(), MasterError> {
        self.time = t0;
        self.initializing = true;
        let outcome = self.initial_iterations(t0);
        self.initializing = false;
        let (iterations, residual, converged) = outcome?;
        self.counters.initialization_iterations = iterations;
        self.counters.initialization_residual = residual;
        if !converged {
            self.counters.non_converged_steps += 1;
        }
        self.accepted.copy_from_slice(&self.value);
        self.accepted_before.copy_from_slice(&self.value);
        self.accepted_earlier.copy_from_slice(&self.value);
        if let Some(adaptive) = self.adaptive.as_mut() {
            adaptive.start(t0, &self.value);
        }
        self.record_static_loads();
        self.initialized = true;
        Ok(())
    }

    fn initial_iterations(&mut self, t0: Time) -> Result<(u32, f64, bool), MasterError> {
        self.first_sweep_done = false;
        let primed = self.prime_sequentially(t0)?;
        for (k, &c) in self.torn.iter().enumerate() {
            let conn = &self.connections[c];
            self.x[k] = if primed[conn.from.unit] {
                link_value(conn, &self.units[conn.from.unit].outputs)
            } else {
                self.units[conn.to.unit].start_inputs[conn.to.port]
            };
        }
        // Relative tolerances start from the torn inputs' first values.
        for (k, &c) in self.torn.iter().enumerate() {
            self.value[c] = self.x[k];
        }
        self.tolerances.follow(
            &self.value,
            &self.connections,
            &mut self.tolerance,
            &mut self.units,
        );
        if self.torn.is_empty() {
            self.sweep(1)?;
            return Ok((1, 0.0, true));
        }
        // Untorn values have no earlier value yet: the first pass never converges.
        self.previous.fill(f64::NAN);
        if self.newton.is_some() {
            self.step_newton()
        } else {
            self.step_fixed_point()
        }
    }

    /// Under Jacobi every connection is torn, so every unit would start from the
    /// scene's start inputs (0 N for a cable under a constant top load: a slack
    /// line), although upstream units could tell it better. Jacobi schemes
    /// therefore begin with one upstream-first pass, as Gauss-Seidel initialises:
    /// each unit in order from its upstream's fresh values, with only the inputs
    /// that close a loop at their start values; the Jacobi iterate starts from the
    /// values this pass produced. Returns which units were initialised so (none for
    /// sequential schemes, whose sweep already does this).
    fn prime_sequentially(&mut self, t0: Time) -> Result<Vec<bool>, MasterError> {
        let n = self.units.len();
        let mut primed = vec![false; n];
        if self.settings.scheme.is_sequential() {
            return Ok(primed);
        }
        let closes_loop = tears(&self.order, &self.connections, true);
        for i in 0..self.order.len() {
            let u = self.order[i];
            for (p, source) in self.input_connection[u].iter().enumerate() {
                if let Some(c) = *source {
                    let conn = &self.connections[c];
                    self.units[u].inputs[p] = if closes_loop[c] {
                        self.units[u].start_inputs[p]
                    } else {
                        link_value(conn, &self.units[conn.from.unit].outputs)
                    };
                }
            }
            self.units[u].initialize(t0, 0)?;
            primed[u] = true;
        }
        Ok(primed)
    }
}
