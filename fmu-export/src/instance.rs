//! One FMU instance: the unit, its variables and its FMI state machine.

use serde::{Deserialize, Serialize};
use slender_fmi::export::{CONFIG_FILE, ExportConfig, Layout, VARIABLES_FILE};
use slender_fmi::ffi::*;
use slender_fmi::model_description::Value;
use slender_kinds::exported::ExportedUnit;
use slender_units::{Driver, DriverSlot, Hold, Time};
use std::ffi::{CString, c_void};
use std::panic::AssertUnwindSafe;

mod derivative;
mod fields;
mod state;
use state::SavedInstance;

#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
enum Phase {
    Instantiated,
    Initialization,
    Stepping,
    Terminated,
    /// FMI 3.0's Configuration Mode (from and back to `Instantiated`): the
    /// structural parameters (array sizes) may be set.
    Configuration,
}

/// An exported unit behind the FMI 2.0 entry points.
pub(crate) struct Instance {
    name: String,
    callbacks: fmi2CallbackFunctions,
    /// An FMI 3.0 instance's logger (its messages go there, not to `callbacks`).
    pub log3: Option<crate::fmi3::Logger>,
    pub logging: bool,
    /// FMI 3.0's independent variable `time`.
    time_reference: u32,
    /// The configuration as exported (for `fmi2Reset`) and as currently set.
    exported: ExportConfig,
    config: ExportConfig,
    layout: Layout,
    unit: Option<Driver>,
    /// Parameters changed since the unit was built.
    rebuild: bool,
    /// Inputs or parameters changed in initialisation mode since the unit last
    /// found its initial state.
    reinitialize: bool,
    phase: Phase,
    start_time: Time,
    time: Time,
    inputs: Vec<f64>,
    /// First derivatives of the inputs for the next step, and whether set.
    derivatives: Vec<f64>,
    ramped: Vec<bool>,
    end: Vec<f64>,
    outputs: Vec<f64>,
    /// Inputs set since the outputs were last computed (direct feedthrough).
    inputs_changed: bool,
    parameters: Vec<Value>,
    /// The FMI 3.0 array sizes (`Layout::sizes`) as set before
    /// initialisation (None: not set), and each field's length in the unit
    /// as built.
    sizes: Vec<Option<u64>>,
    field_lengths: Vec<usize>,
    strings: Vec<CString>,
    /// The unit's step Jacobian, kept for the step it was taken after
    /// (`fmi2GetDirectionalDerivative` may ask one output at a time).
    jacobian: Vec<f64>,
    /// Counts steps and state changes; the Jacobian's is `jacobian_of`.
    generation: u64,
    jacobian_of: Option<u64>,
}

/// Sends a message to the environment's logger, whatever the instance state.
pub(crate) fn log_with(
    callbacks: &fmi2CallbackFunctions,
    instance: &str,
    status: fmi2Status,
    message: &str,
) {
    let Some(logger) = callbacks.logger else {
        return;
    };
    let category = match status {
        FMI2_OK => c"logAll",
        FMI2_WARNING => c"logStatusWarning",
        _ => c"logStatusError",
    };
    let instance = CString::new(instance.replace('\0', " ")).unwrap_or_default();
    let message = CString::new(message.replace('\0', " ")).unwrap_or_default();
    // SAFETY: the FMI 2.0 logger with a "%s" format and one string argument.
    unsafe {
        logger(
            callbacks.component_environment,
            instance.as_ptr(),
            status,
            category.as_ptr(),
            c"%s".as_ptr(),
            message.as_ptr(),
        )
    };
}

/// Runs an entry point's body on the instance behind `c`, catching panics;
/// errors are logged with the call and returned as fmi2Error.
pub(crate) fn guarded(
    c: fmi2Component,
    call: &str,
    body: impl FnOnce(&mut Instance) -> Result<fmi2Status, String>,
) -> fmi2Status {
    if c.is_null() {
        return FMI2_ERROR;
    }
    // SAFETY: `c` came from fmi2Instantiate (FMI forbids other values) and the
    // environment does not call one instance concurrently.
    let instance = unsafe { &mut *c.cast::<Instance>() };
    let result = std::panic::catch_unwind(AssertUnwindSafe(|| body(&mut *instance)));
    match result {
        Ok(Ok(status)) => status,
        Ok(Err(message)) => {
            instance.log(FMI2_ERROR, &format!("{call}: {message}"));
            FMI2_ERROR
        }
        Err(_) => {
            instance.log(
                FMI2_ERROR,
                &format!("{call}: internal error (panic caught)"),
            );
            FMI2_ERROR
        }
    }
}

/// Frees a state made by `fmi2GetFMUstate` or `fmi2DeSerializeFMUstate`.
pub(crate) fn free_state(state: fmi2FMUstate) {
    if !state.is_null() {
        // SAFETY: every non-null handle we return is a leaked Box<SavedInstance>.
        drop(unsafe { Box::from_raw(state.cast::<SavedInstance>()) });
    }
}

impl Instance {
    /// The instance of the FMU whose resources are in `resources`, checking
    /// its GUID (FMI 3.0: instantiation token).
    pub(crate) fn new(
        name: String,
        guid: &str,
        resources: &std::path::Path,
        callbacks: fmi2CallbackFunctions,
        logging: bool,
    ) -> Result<Instance, String> {
        let file = resources.join(CONFIG_FILE);
        let text = std::fs::read_to_string(&file).map_err(|e| {
            format!(
                "{}: cannot read the unit's configuration ({e})",
                file.display()
            )
        })?;
        let config = ExportConfig::from_toml(&text).map_err(|e| e.to_string())?;
        if config.guid != guid {
            return Err(format!(
                "GUID {guid} does not match this FMU's {} (model description and resources disagree)",
                config.guid
            ));
        }
        let layout = config.layout().map_err(|e| e.to_string())?;
        // FMUs exported before the list existed carry none.
        if let Ok(carried) = std::fs::read_to_string(resources.join(VARIABLES_FILE)) {
            layout.check_variables(&carried)?;
        }
        let n_in = layout.unit.inputs.len();
        let inputs = layout
            .unit
            .inputs
            .iter()
            .map(|p| config.inputs.get(&p.name).copied().unwrap_or(0.0))
            .collect();
        let parameters = layout.parameters.iter().map(|p| p.start.clone()).collect();
        let start_time = Time::from_secs(config.start_time).unwrap_or(Time::ZERO);
        let sizes = vec![None; layout.sizes.len()];
        let field_lengths = layout.fields.iter().map(|f| f.len).collect();
        Ok(Instance {
            name,
            callbacks,
            log3: None,
            logging,
            time_reference: layout.model.time_reference(),
            exported: config.clone(),
            config,
            outputs: vec![0.0; layout.unit.outputs.len()],
            layout,
            unit: None,
            rebuild: true,
            reinitialize: true,
            phase: Phase::Instantiated,
            start_time,
            time: start_time,
            inputs,
            derivatives: vec![0.0; n_in],
            ramped: vec![false; n_in],
            end: vec![0.0; n_in],
            inputs_changed: false,
            parameters,
            sizes,
            field_lengths,
            strings: Vec::new(),
            jacobian: Vec::new(),
            generation: 0,
            jacobian_of: None,
        })
    }

    pub(crate) fn log(&self, status: fmi2Status, message: &str) {
        if status != FMI2_OK || self.logging {
            let message = format!("unit `{}`: {message}", self.config.name);
            match &self.log3 {
                Some(logger) => logger.log(status, &message),
                None => log_with(&self.callbacks, &self.name, status, &message),
            }
        }
    }

    pub(crate) fn time_secs(&self) -> f64 {
        self.time.as_secs()
    }

    pub(crate) fn setup(&mut self, start_time: f64) -> Result<fmi2Status, String> {
        if self.phase != Phase::Instantiated {
            return Err("only allowed after fmi2Instantiate or fmi2Reset".into());
        }
        self.start_time = Time::from_secs(start_time)
            .ok_or_else(|| format!("startTime {start_time}: expected a finite time (s)"))?;
        self.time = self.start_time;
        Ok(FMI2_OK)
    }

    fn unit(&mut self) -> Result<&mut Driver, String> {
        if self.rebuild || self.unit.is_none() {
            let unit = self
                .config
                .driver()
                .map_err(|e| format!("building the unit: {e}"))?;
            self.check_sizes(&unit.fields())?;
            self.unit = Some(unit);
            self.rebuild = false;
            self.reinitialize = true;
        }
        self.unit.as_mut().ok_or_else(|| "no unit".to_owned())
    }

    /// Finds the initial state with the current inputs, if anything changed.
    fn settle(&mut self) -> Result<(), String> {
        self.unit()?;
        if !self.reinitialize {
            return Ok(());
        }
        let unit = self.unit.as_mut().ok_or("no unit")?;
        unit.set_inputs(&self.inputs).map_err(|e| e.to_string())?;
        unit.initialize(self.start_time)
            .map_err(|e| format!("initial state: {e}"))?;
        unit.outputs(&mut self.outputs).map_err(|e| e.to_string())?;
        self.reinitialize = false;
        self.inputs_changed = false;
        Ok(())
    }

    pub(crate) fn enter_initialization(&mut self) -> Result<fmi2Status, String> {
        if self.phase != Phase::Instantiated {
            return Err("only allowed after fmi2Instantiate or fmi2Reset".into());
        }
        self.unit()?;
        self.phase = Phase::Initialization;
        Ok(FMI2_OK)
    }

    pub(crate) fn exit_initialization(&mut self) -> Result<fmi2Status, String> {
        if self.phase != Phase::Initialization {
            return Err("only allowed in initialisation mode".into());
        }
        self.settle()?;
        self.time = self.start_time;
        self.phase = Phase::Stepping;
        Ok(FMI2_OK)
    }

    pub(crate) fn terminate(&mut self) -> Result<fmi2Status, String> {
        self.phase = Phase::Terminated;
        Ok(FMI2_OK)
    }

    pub(crate) fn reset(&mut self) -> Result<fmi2Status, String> {
        self.generation += 1;
        self.config = self.exported.clone();
        self.parameters = self
            .layout
            .parameters
            .iter()
            .map(|p| p.start.clone())
            .collect();
        self.inputs = self
            .layout
            .unit
            .inputs
            .iter()
            .map(|p| self.config.inputs.get(&p.name).copied().unwrap_or(0.0))
            .collect();
        self.sizes.fill(None);
        self.unit = None;
        self.rebuild = true;
        self.phase = Phase::Instantiated;
        self.time = Time::from_secs(self.config.start_time).unwrap_or(Time::ZERO);
        self.start_time = self.time;
        Ok(FMI2_OK)
    }

    fn n_in(&self) -> usize {
        self.layout.unit.inputs.len()
    }

    fn n_out(&self) -> usize {
        self.layout.unit.outputs.len()
    }

    /// Index of a parameter variable, or an error naming the reference.
    fn parameter(&self, vr: u32) -> Result<usize, String> {
        let first = (self.n_in() + self.n_out()) as u32;
        vr.checked_sub(first)
            .map(|i| i as usize)
            .filter(|i| *i < self.parameters.len())
            .ok_or_else(|| format!("value reference {vr} does not exist"))
    }

    fn set_parameter(&mut self, vr: u32, value: Value) -> Result<(), String> {
        let p = self.parameter(vr)?;
        if !matches!(self.phase, Phase::Instantiated | Phase::Initialization) {
            return Err(format!(
                "parameter `{}` is fixed: set it before fmi2ExitInitializationMode",
                self.layout.parameters[p].name
            ));
        }
        if std::mem::discriminant(&value) != std::mem::discriminant(&self.parameters[p]) {
            return Err(format!(
                "parameter `{}` is a {}, not a {}",
                self.layout.parameters[p].name,
                self.parameters[p].type_name(),
                value.type_name()
            ));
        }
        let target = self.layout.parameters[p].target.clone();
        self.config
            .set_parameter(&target, value.clone())
            .map_err(|e| e.to_string())?;
        self.parameters[p] = value;
        self.rebuild = true;
        Ok(())
    }

    pub(crate) fn get_real(&mut self, vr: &[u32], out: &mut [f64]) -> Result<fmi2Status, String> {
        if self.phase == Phase::Initialization {
            self.settle()?;
        } else if self.phase == Phase::Stepping && self.inputs_changed {
            self.refresh_feedthrough()?;
        }
        let (n_in, n_out) = (self.n_in(), self.n_out());
        let mut at = 0;
        for r in vr {
            if let Some(field) = self.field_of(*r) {
                at += self.read_field(field, out.get_mut(at..).unwrap_or_default())?;
                continue;
            }
            let r_us = *r as usize;
            let v = out.get_mut(at).ok_or("more value references than values")?;
            at += 1;
            *v = if r_us < n_in {
                self.inputs[r_us]
            } else if r_us < n_in + n_out {
                self.outputs[r_us - n_in]
            } else if *r == self.time_reference {
                self.time.as_secs()
            } else {
                match self.parameters[self.parameter(*r)?] {
                    Value::Real(Some(x)) => x,
                    _ => return Err(format!("value reference {r} is not a Real")),
                }
            };
        }
        if at != out.len() {
            return Err(format!(
                "{} values passed for variables that hold {at}",
                out.len()
            ));
        }
        Ok(FMI2_OK)
    }

    pub(crate) fn set_real(&mut self, vr: &[u32], values: &[f64]) -> Result<fmi2Status, String> {
        let n_in = self.n_in();
        for (r, v) in vr.iter().zip(values) {
            let r_us = *r as usize;
            if r_us < n_in {
                if !v.is_finite() {
                    return Err(format!(
                        "input `{}` = {v}: expected a finite value",
                        self.layout.unit.inputs[r_us].name
                    ));
                }
                self.inputs[r_us] = *v;
                self.reinitialize |= self.phase == Phase::Initialization;
                self.inputs_changed = true;
            } else if r_us < n_in + self.n_out() {
                return Err(format!(
                    "`{}` is an output and cannot be set",
                    self.layout.unit.outputs[r_us - n_in].name
                ));
            } else if let Some(k) = self.field_of(*r) {
                let name = &self.layout.fields[k].name;
                return Err(format!("`{name}` is an output and cannot be set"));
            } else {
                self.set_parameter(*r, Value::Real(Some(*v)))?;
            }
        }
        Ok(FMI2_OK)
    }

    /// Integers, or Booleans when `boolean` (FMI passes both as C ints).
    pub(crate) fn get_integer(
        &mut self,
        vr: &[u32],
        out: &mut [i32],
        boolean: bool,
    ) -> Result<fmi2Status, String> {
        for (r, v) in vr.iter().zip(out.iter_mut()) {
            *v = match (&self.parameters[self.parameter(*r)?], boolean) {
                (Value::Integer(Some(x)), false) => *x,
                (Value::Boolean(Some(b)), true) => i32::from(*b),
                _ => {
                    return Err(format!(
                        "value reference {r} is not an {}",
                        if boolean { "Boolean" } else { "Integer" }
                    ));
                }
            };
        }
        Ok(FMI2_OK)
    }

    pub(crate) fn set_integer(
        &mut self,
        vr: &[u32],
        values: &[i32],
        boolean: bool,
    ) -> Result<fmi2Status, String> {
        for (r, v) in vr.iter().zip(values) {
            let value = if boolean {
                Value::Boolean(Some(*v != FMI2_FALSE))
            } else {
                Value::Integer(Some(*v))
            };
            self.set_parameter(*r, value)?;
        }
        Ok(FMI2_OK)
    }

    pub(crate) fn get_string(
        &mut self,
        vr: &[u32],
        out: &mut [fmi2String],
    ) -> Result<fmi2Status, String> {
        self.strings.clear();
        for r in vr {
            match &self.parameters[self.parameter(*r)?] {
                Value::String(Some(s)) => self
                    .strings
                    .push(CString::new(s.as_str()).map_err(|_| "string with NUL".to_owned())?),
                _ => return Err(format!("value reference {r} is not a String")),
            }
        }
        for (o, s) in out.iter_mut().zip(&self.strings) {
            *o = s.as_ptr();
        }
        Ok(FMI2_OK)
    }

    pub(crate) fn set_string(
        &mut self,
        vr: &[u32],
        values: &[String],
    ) -> Result<fmi2Status, String> {
        for (r, v) in vr.iter().zip(values) {
            self.set_parameter(*r, Value::String(Some(v.clone())))?;
        }
        Ok(FMI2_OK)
    }

    pub(crate) fn set_input_derivatives(
        &mut self,
        vr: &[u32],
        order: &[i32],
        values: &[f64],
    ) -> Result<fmi2Status, String> {
        for ((r, o), v) in vr.iter().zip(order).zip(values) {
            let i = *r as usize;
            if i >= self.n_in() {
                return Err(format!("value reference {r} is not an input"));
            }
            if *o != 1 {
                return Err(format!(
                    "derivative order {o}: only first derivatives are used"
                ));
            }
            if !v.is_finite() {
                return Err(format!(
                    "derivative of input {r} = {v}: expected a finite value"
                ));
            }
            self.derivatives[i] = *v;
            self.ramped[i] = true;
        }
        Ok(FMI2_OK)
    }

    pub(crate) fn do_step(&mut self, t: f64, h: f64) -> Result<fmi2Status, String> {
        self.generation += 1;
        if self.phase != Phase::Stepping {
            return Err("only allowed after fmi2ExitInitializationMode".into());
        }
        let t_at = Time::from_secs(t)
            .ok_or_else(|| format!("currentCommunicationPoint {t}: not a finite time"))?;
        let step = Time::from_secs(h)
            .filter(|s| *s > Time::ZERO)
            .ok_or_else(|| format!("communicationStepSize {h}: expected at least 1 ns"))?;
        // Hosts that accumulate t += h in floating point drift from the FMU's
        // integer time by round-off (1.6e-6 s after 1e7 steps of 1 ms); a real
        // repeat or skip is off by a whole step. Within half a step the point is
        // the FMU's own time, which stays exact (the FMU resynchronises).
        let slack = (step.as_nanos() / 2).max(1000);
        if (t_at.as_nanos() - self.time.as_nanos()).abs() > slack {
            return Err(format!(
                "currentCommunicationPoint {t} s differs from the FMU's time {} s by more than half a step (restore a state first to repeat a step)",
                self.time.as_secs()
            ));
        }
        let unit = self.unit.as_mut().ok_or("no unit")?;
        for i in 0..self.end.len() {
            let hold = if self.ramped[i] {
                Hold::Ramp
            } else {
                Hold::ZeroOrder
            };
            if unit.holds()[i] != hold {
                // Units with a fixed hold keep theirs.
                let _ = unit.set_hold(i, hold);
            }
            self.end[i] = if self.ramped[i] {
                self.inputs[i] + h * self.derivatives[i]
            } else {
                self.inputs[i]
            };
            self.ramped[i] = false;
        }
        unit.set_inputs(&self.end).map_err(|e| e.to_string())?;
        let result = unit.do_step(self.time, step);
        if let Err(e) = result {
            return Err(format!(
                "step from t = {} s by {h} s: {e}",
                self.time.as_secs()
            ));
        }
        unit.outputs(&mut self.outputs).map_err(|e| e.to_string())?;
        self.inputs_changed = false;
        self.time += step;
        Ok(FMI2_OK)
    }

    /// Outputs with direct feedthrough follow inputs set at the communication
    /// point: the unit's outputs are evaluated again with them as its current
    /// inputs (the state does not change; the next step starts from the last
    /// accepted inputs as before).
    fn refresh_feedthrough(&mut self) -> Result<(), String> {
        let unit = self.unit.as_mut().ok_or("no unit")?;
        if unit.description().has_feedthrough() {
            unit.set_inputs(&self.inputs).map_err(|e| e.to_string())?;
            unit.outputs(&mut self.outputs).map_err(|e| e.to_string())?;
        }
        self.inputs_changed = false;
        Ok(())
    }
}
