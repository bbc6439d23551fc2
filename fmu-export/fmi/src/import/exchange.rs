//! The values an imported FMU exchanges with the master: the inputs sent
//! before a step (start value and slope under a ramp, end value under a zero-order
//! hold), the outputs read after it (Real, then scalar Integer ones as reals),
//! and the scene's start values.

use super::*;

impl FmuUnit {
    /// Sends the inputs for a step of `h` seconds (0: initialisation): under a ramp
    /// the start value and the slope, under a zero-order hold the end value.
    pub(super) fn send_inputs(&mut self, inputs: Inputs<'_>, h: f64) -> Result<(), UnitError> {
        let n = self.values.len();
        if n == 0 {
            return Ok(());
        }
        let ramped = h > 0.0 && (0..n).any(|i| inputs.hold(i) == Hold::Ramp);
        for i in 0..n {
            let ramp = ramped && inputs.hold(i) == Hold::Ramp;
            self.slopes[i] = if ramp { inputs.rate(i, h) } else { 0.0 };
            self.values[i] = if ramp {
                inputs.start()[i]
            } else {
                inputs.end()[i]
            };
        }
        // SAFETY: the input references and their n values.
        let status = unsafe {
            self.calls
                .set_reals(self.component, &self.input_refs, &self.values)
        };
        self.check_with(status, || {
            format!(
                "{} (inputs)",
                self.calls.name("fmi2SetReal", "fmi3SetFloat64")
            )
        })?;
        if ramped {
            // SAFETY: n references, orders and values (ramps exist only where
            // the FMU interpolates inputs: FMI 2.0).
            let status = unsafe {
                self.calls.set_input_slopes(
                    self.component,
                    &self.input_refs,
                    &self.orders,
                    &self.slopes,
                )
            };
            self.check("fmi2SetRealInputDerivatives", status)?;
        }
        Ok(())
    }

    pub(super) fn read_outputs(&mut self) -> Result<(), UnitError> {
        if self.outputs.is_empty() {
            return Ok(());
        }
        let reals = self.outputs.len() - self.integers.len();
        // SAFETY: the output references and their values.
        let status = unsafe {
            (self.calls).get_reals(
                self.component,
                &self.output_refs,
                &mut self.outputs[..reals],
            )
        };
        let calls = &self.calls;
        self.check_with(status, || {
            format!("{} (outputs)", calls.name("fmi2GetReal", "fmi3GetFloat64"))
        })?;
        if self.integers.is_empty() {
            return Ok(());
        }
        // SAFETY: the scalar Integer outputs' references and as many values.
        let status = unsafe {
            (self.calls).get_integers(self.component, &self.integer_refs, &mut self.integers)
        };
        let calls = &self.calls;
        self.check_with(status, || {
            format!("{} (outputs)", calls.name("fmi2GetInteger", "fmi3GetInt32"))
        })?;
        for (out, &value) in self.outputs[reals..].iter_mut().zip(&self.integers) {
            *out = f64::from(value);
        }
        Ok(())
    }

    pub(super) fn apply_start_values(&mut self) -> Result<(), UnitError> {
        let calls = &self.calls;
        for s in &self.starts {
            // SAFETY: single values matching each setter's type.
            let (call, status) = unsafe {
                match s {
                    StartValue::Real(vr, v) => (
                        calls.name("fmi2SetReal", "fmi3SetFloat64"),
                        calls.set_reals(self.component, &[*vr], &[*v]),
                    ),
                    StartValue::Integer(vr, v) => (
                        calls.name("fmi2SetInteger", "fmi3SetInt32"),
                        calls.set_integer(self.component, *vr, *v),
                    ),
                    StartValue::Boolean(vr, v) => (
                        calls.name("fmi2SetBoolean", "fmi3SetBoolean"),
                        calls.set_boolean(self.component, *vr, *v),
                    ),
                    StartValue::String(vr, v) => (
                        calls.name("fmi2SetString", "fmi3SetString"),
                        calls.set_string(self.component, *vr, v.as_ptr()),
                    ),
                }
            };
            self.check(&format!("{call} (start value)"), status)?;
        }
        Ok(())
    }
}
