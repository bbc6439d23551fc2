//! The warm start of a repeated step: a master iterating on the units'
//! interface Jacobians restores a unit and steps it again over the same step
//! with inputs that changed little (`Unit::warm_repeat`). The unit's Newton
//! then starts from the last attempt's solution moved by the step's
//! derivatives, d q / d input (the columns its step Jacobian solved for),
//! and takes one or two iterations instead of a whole solve. The result is
//! the same to Newton's tolerance, not to the bit.

/// The last whole step's start, end inputs and end coordinates, the
/// derivatives of those coordinates per input, and the repeat's hint.
#[derive(Clone, Debug, Default)]
pub struct WarmStart {
    /// The next step repeats the last one (set by `Unit::warm_repeat`,
    /// cleared by `guess`).
    pub warm: bool,
    last_t0: f64,
    last_inputs: Vec<f64>,
    last_end: Vec<f64>,
    /// d q / d input, one column of `last_end.len()` per input.
    columns: Vec<f64>,
    columns_valid: bool,
    guess: Vec<f64>,
}

impl WarmStart {
    /// Records a whole step from `t0` (s) that ended at the coordinates `q`
    /// with end `inputs`; its derivatives are not known yet.
    pub fn record_step(&mut self, t0: f64, inputs: &[f64], q: &[f64]) {
        self.last_t0 = t0;
        self.last_inputs.clear();
        self.last_inputs.extend_from_slice(inputs);
        self.last_end.clear();
        self.last_end.extend_from_slice(q);
        self.columns_valid = false;
    }

    /// Room for `inputs` columns of `n` coordinates, to be filled by
    /// `set_column`; the columns count once `columns_done(true)`.
    pub fn begin_columns(&mut self, inputs: usize, n: usize) {
        self.columns.resize(inputs * n, 0.0);
        self.columns_valid = false;
    }

    /// Column `j`: d q / d input `j` of the last step.
    pub fn set_column(&mut self, j: usize, dq: &[f64]) {
        let n = dq.len();
        if let Some(column) = self.columns.get_mut(j * n..(j + 1) * n) {
            column.copy_from_slice(dq);
        }
    }

    /// Whether every column was filled.
    pub fn columns_done(&mut self, complete: bool) {
        self.columns_valid = complete;
    }

    /// Every column at once (`inputs x n`, column by column).
    pub fn set_columns(&mut self, columns: &[f64]) {
        self.columns.clear();
        self.columns.extend_from_slice(columns);
        self.columns_valid = true;
    }

    /// Adds the last step's end coordinates' change for a change of its end
    /// inputs, to first order (the columns times `change`, one per input), to
    /// `dq`; false, adding nothing, when the columns are not all known.
    pub fn add_change(&self, change: &[f64], dq: &mut [f64]) -> bool {
        let n = dq.len();
        if !self.columns_valid || self.columns.len() != n * change.len() || n != self.last_end.len()
        {
            return false;
        }
        for (du, column) in change.iter().zip(self.columns.chunks_exact(n)) {
            if *du != 0.0 {
                for (d, c) in dq.iter_mut().zip(column) {
                    *d += c * du;
                }
            }
        }
        true
    }

    /// The first iterate of a step from `t0` with end `inputs` that repeats
    /// the last one (after `Unit::warm_repeat`): its end coordinates moved
    /// by the columns where they are of that step; None when the step is
    /// another one. Clears the hint.
    pub fn guess(&mut self, t0: f64, inputs: &[f64]) -> Option<&[f64]> {
        let warm = std::mem::take(&mut self.warm);
        if !warm
            || t0 != self.last_t0
            || inputs.len() != self.last_inputs.len()
            || self.last_end.is_empty()
        {
            return None;
        }
        let n = self.last_end.len();
        self.guess.clone_from(&self.last_end);
        if self.columns_valid && self.columns.len() == n * inputs.len() {
            for (j, (u, u0)) in inputs.iter().zip(&self.last_inputs).enumerate() {
                let du = u - u0;
                if du != 0.0 {
                    for (g, c) in self.guess.iter_mut().zip(&self.columns[j * n..(j + 1) * n]) {
                        *g += c * du;
                    }
                }
            }
        }
        Some(&self.guess)
    }
}

#[cfg(test)]
mod tests {
    use super::WarmStart;

    #[test]
    fn the_guess_moves_the_last_end_by_the_columns_only_on_a_repeat() {
        let mut w = WarmStart::default();
        w.record_step(1.0, &[2.0, 3.0], &[10.0, 20.0]);
        w.begin_columns(2, 2);
        w.set_column(0, &[1.0, 0.0]);
        w.set_column(1, &[0.0, -2.0]);
        w.columns_done(true);
        assert_eq!(w.guess(1.0, &[2.5, 3.0]), None, "no hint, no guess");
        w.warm = true;
        assert_eq!(w.guess(1.0, &[2.5, 4.0]), Some(&[10.5, 18.0][..]));
        w.warm = true;
        assert_eq!(w.guess(1.1, &[2.5, 4.0]), None, "another step");
        let mut dq = [0.0; 2];
        assert!(w.add_change(&[0.5, 1.0], &mut dq));
        assert_eq!(dq, [0.5, -2.0]);
        w.columns_done(false);
        assert!(!w.add_change(&[0.5, 1.0], &mut dq), "columns not known");
        w.warm = true;
        assert_eq!(w.guess(1.0, &[9.0, 9.0]), Some(&[10.0, 20.0][..]));
    }
}
