//! `fmi2GetDirectionalDerivative`: the unit's step Jacobian (the derivative of
//! its outputs after the last `fmi2DoStep` with respect to the inputs that step
//! ended at), applied to the environment's seed. Offered where the unit gives
//! one (`providesDirectionalDerivative`); an interface-Jacobian master gets
//! from it what slender's own master gets from the unit.

use super::*;

impl Instance {
    /// `dv_unknown = J[unknown, known] dv_known` after a step; an error before
    /// the first step, after `fmi2SetFMUstate`, or for an output the unit does
    /// not derive (named).
    pub(crate) fn directional_derivative(
        &mut self,
        (unknown, known): (&[u32], &[u32]),
        dv_known: &[f64],
        dv_unknown: &mut [f64],
    ) -> Result<fmi2Status, String> {
        if self.phase != Phase::Stepping {
            return Err("directional derivatives are given after a step (fmi2DoStep) only".into());
        }
        let (n_in, n_out) = (self.n_in(), self.n_out());
        let column = |r: u32| {
            Some(r as usize)
                .filter(|&r| r < n_in)
                .ok_or_else(|| format!("value reference {r} is not an input (a known must be one)"))
        };
        let row = |r: u32| {
            (r as usize)
                .checked_sub(n_in)
                .filter(|&r| r < n_out)
                .ok_or_else(|| {
                    format!("value reference {r} is not an output (an unknown must be one)")
                })
        };
        if self.jacobian_of != Some(self.generation) {
            self.jacobian.resize(n_in * n_out, 0.0);
            let unit = self.unit.as_mut().ok_or("no unit")?;
            unit.step_jacobian(&mut self.jacobian)
                .map_err(|e| format!("the step Jacobian: {e}"))?;
            self.jacobian_of = Some(self.generation);
        }
        for (&u, d) in unknown.iter().zip(dv_unknown.iter_mut()) {
            let i = row(u)?;
            let mut sum = 0.0;
            for (&k, &dk) in known.iter().zip(dv_known) {
                sum += self.jacobian[i * n_in + column(k)?] * dk;
            }
            if !sum.is_finite() {
                return Err(format!(
                    "output `{}` has no derivative from this unit",
                    self.layout.unit.outputs[i].name
                ));
            }
            *d = sum;
        }
        Ok(FMI2_OK)
    }
}
