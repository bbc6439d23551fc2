//! Derivatives of the outputs with respect to the inputs, two of them.
//!
//! - `fmi2GetDirectionalDerivative` / `fmi3GetDirectionalDerivative`: what the
//!   standard defines, the partial derivatives of the outputs with respect to
//!   the inputs at the current instant, the state held. A slender unit's
//!   outputs depend on its state only unless it declares feedthrough, so they
//!   are zero; a unit with feedthrough does not offer them
//!   (`providesDirectionalDerivative` false, the call refused).
//! - `slenderGetStepDerivative` (a slender extension, FMI 2.0's signature
//!   for both versions): the unit's step Jacobian, the derivative of its
//!   outputs after the last `DoStep` with respect to the inputs that step
//!   ended at, applied to the seed. An interface-Jacobian master (slender's
//!   own) gets from it what it gets from the unit itself.

use super::*;

impl Instance {
    /// The standard's directional derivative at the current instant:
    /// `dv_unknown = 0` for a unit without feedthrough (its outputs do not
    /// move with an input until the next step), for scalar outputs
    /// `unknown` or, without them, every element asked (FMI 3.0 arrays);
    /// refused for a unit with feedthrough, whose instantaneous partials
    /// slender does not form.
    pub(crate) fn directional_derivative(
        &mut self,
        (unknown, known): (Option<&[u32]>, &[u32]),
        dv_unknown: &mut [f64],
    ) -> Result<fmi2Status, String> {
        if self.phase == Phase::Instantiated {
            return Err("directional derivatives are given from initialization mode on".into());
        }
        if self.layout.unit.has_feedthrough() {
            return Err("this unit has direct feedthrough, whose partial derivatives at an instant it does not give (providesDirectionalDerivative is false); its step Jacobian is slenderGetStepDerivative".into());
        }
        let (n_in, n_out) = (self.n_in(), self.n_out());
        if let Some(&k) = known.iter().find(|&&k| k as usize >= n_in) {
            return Err(format!(
                "value reference {k} is not an input (a known must be one)"
            ));
        }
        let not_output = |&&u: &&u32| (u as usize) < n_in || u as usize >= n_in + n_out;
        if let Some(&u) = unknown.and_then(|u| u.iter().find(not_output)) {
            return Err(format!(
                "value reference {u} is not an output (an unknown must be one)"
            ));
        }
        dv_unknown.fill(0.0);
        Ok(FMI2_OK)
    }

    /// Whether the unit gives its step Jacobian (`slenderGetStepDerivative`).
    pub(crate) fn gives_step_derivative(&self) -> bool {
        self.layout.unit.capabilities.step_jacobian
    }

    /// `dv_unknown = J[unknown, known] dv_known` after a step; an error before
    /// the first step, after `fmi2SetFMUstate`, or for an output the unit does
    /// not derive (named).
    pub(crate) fn step_derivative(
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
