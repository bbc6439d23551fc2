//! Importing an FMI 2.0 co-simulation FMU as a unit.
//!
//! The FMU is unzipped into a temporary folder, its model description parsed and
//! its `binaries/linux64/<modelIdentifier>.so` loaded with every symbol bound at
//! load time. Real inputs and outputs become ports; their kind follows from the
//! unit of measure (N: force, m/s: velocity, ...), direct feedthrough from
//! `ModelStructure/Outputs`. Rollback is offered only when the FMU declares
//! `canGetAndSetFMUstate`.
//!
//! Input timing. The contract gives a unit the input values at the END of a step;
//! FMI reads the values set before `fmi2DoStep` as those at its start. Under a
//! zero-order hold the two agree (the value is held over the step), so the end
//! value is sent. Under a ramp hold, when the FMU declares `canInterpolateInputs`,
//! the start value and the ramp's slope (`fmi2SetRealInputDerivatives`, order 1)
//! are sent; an FMU that cannot interpolate gets the end value held (its ports say
//! zero-order).
//!
//! The master's `initialize` may run several times while it settles a loop: the
//! FMU stays in initialisation mode, takes the new inputs and reports its
//! outputs, and leaves that mode at the first step. A later `initialize` resets
//! the FMU (`fmi2Reset`) and starts again.

use crate::ffi::*;
use crate::measure::si_definition;
use crate::model_description::{ModelDescription, Value, VariableCausality};
use serde::{Deserialize, Serialize};
use slender_contract::names::did_you_mean;
use slender_contract::{
    Capabilities, Hold, HoldSupport, Inputs, Port, PortKind, StateSlot, StepReport, Time, Unit,
    UnitDescription, UnitError,
};
use std::collections::BTreeMap;
use std::ffi::CString;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};

/// Parameters of the `fmu` unit kind.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FmuParams {
    /// The `.fmu` file (relative to the scene file's folder).
    pub file: PathBuf,
    /// Start values of parameters (or inputs) by variable name.
    #[serde(default)]
    pub start: BTreeMap<String, toml::Value>,
    /// Shared libraries to load globally before the FMU, e.g. libpython for FMUs
    /// built by pythonfmu.
    #[serde(default)]
    pub preload: Vec<PathBuf>,
    /// Ask the FMU for debug logging.
    #[serde(default)]
    pub logging: bool,
}

mod archive;
mod describe;
mod error;
mod library;
use archive::{binary_for_this_platform, unpack};

use describe::{describe, real_refs, start_values};
pub use error::LoadError;
use library::{Api, LogBook, instantiate, log_tail, open_binary};

#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
enum Phase {
    Instantiated,
    Initialization,
    Stepping,
}

/// What `save_state` keeps besides the FMU's own state (which stays in the FMU).
#[derive(Clone, Debug, Serialize, Deserialize)]
struct SavedFmu {
    /// Which `FmuUnit` saved it (an FMU state belongs to one instance).
    owner: u64,
    /// The FMU state handle (`fmi2FMUstate`, a pointer, as an integer); it is
    /// updated in place by later saves into the same slot and freed with the unit.
    handle: usize,
    phase: Phase,
    outputs: Vec<f64>,
}

static NEXT_ID: AtomicU64 = AtomicU64::new(1);

/// A parameter start value to apply before initialisation.
pub(super) enum StartValue {
    Real(u32, f64),
    Integer(u32, i32),
    Boolean(u32, bool),
    String(u32, CString),
}

/// An FMI 2.0 co-simulation FMU behind the unit contract.
pub struct FmuUnit {
    /// The FMU's file name, for messages.
    label: String,
    id: u64,
    description: UnitDescription,
    model: ModelDescription,
    api: Api,
    component: fmi2Component,
    phase: Phase,
    starts: Vec<StartValue>,
    input_refs: Vec<u32>,
    output_refs: Vec<u32>,
    /// The input values sent before a step: start values of ramped inputs, end
    /// values of held ones (scratch).
    values: Vec<f64>,
    /// The ramps' slopes sent with them (scratch).
    slopes: Vec<f64>,
    orders: Vec<fmi2Integer>,
    outputs: Vec<f64>,
    /// A seed of the directional derivative and its answer (scratch).
    seed: Vec<f64>,
    column: Vec<f64>,
    /// Every FMU state handle handed out, freed with the instance.
    states: Mutex<Vec<usize>>,
    log: Box<LogBook>,
    /// Kept alive for the instance, which holds a pointer to them.
    _callbacks: Box<fmi2CallbackFunctions>,
    // Dropped last: the library and the unzipped files.
    library: Option<libloading::Library>,
    _folder: tempfile::TempDir,
}

// SAFETY: an FMI 2.0 instance may be called from any thread as long as calls are
// not concurrent; the unit is moved between threads but never shared (`&mut self`
// for every FMU call, `outputs` reads only the cache).
unsafe impl Send for FmuUnit {}

impl FmuUnit {
    /// Loads and instantiates the FMU (`params.file` relative to `base_dir`).
    pub fn load(params: &FmuParams, base_dir: &Path) -> Result<FmuUnit, LoadError> {
        let path = if params.file.is_absolute() {
            params.file.clone()
        } else {
            base_dir.join(&params.file)
        };
        let label = path.display().to_string();
        let (folder, model, cs) = unpack(&path, &label)?;
        let binary = binary_for_this_platform(folder.path(), &cs.model_identifier, &label)?;
        let library = open_binary(&binary, &params.preload, &label)?;
        let api = Api::bind(
            &library,
            cs.can_get_and_set_fmu_state,
            cs.provides_directional_derivative,
        )
        .map_err(|message| LoadError::Library {
            fmu: label.clone(),
            message,
        })?;
        let description = describe(&model, &label)?;
        let starts = start_values(&model, &params.start, &label)?;
        let input_refs: Vec<u32> = real_refs(&model, VariableCausality::Input);
        let output_refs: Vec<u32> = real_refs(&model, VariableCausality::Output);
        let n_in = input_refs.len();
        let (component, log, callbacks) =
            instantiate(&api, &model, folder.path(), params.logging, &label)?;
        let mut unit = FmuUnit {
            label,
            id: NEXT_ID.fetch_add(1, Ordering::Relaxed),
            description,
            model,
            api,
            component,
            phase: Phase::Instantiated,
            starts,
            input_refs,
            values: vec![0.0; n_in],
            slopes: vec![0.0; n_in],
            orders: vec![1; n_in],
            outputs: vec![0.0; output_refs.len()],
            seed: vec![0.0; n_in],
            column: vec![0.0; output_refs.len()],
            output_refs,
            states: Mutex::new(Vec::new()),
            log,
            _callbacks: callbacks,
            library: Some(library),
            _folder: folder,
        };
        let hold = if cs.can_interpolate_inputs {
            Hold::Ramp
        } else {
            Hold::ZeroOrder
        };
        for p in unit.description.inputs.iter_mut() {
            p.hold = hold;
        }
        Ok(unit)
    }

    /// `fmi2GetDirectionalDerivative` of the outputs `rows` for the seed, into
    /// the same rows of `column`; the status.
    fn derivative(
        &mut self,
        get: library::GetDirectionalDerivative,
        rows: std::ops::Range<usize>,
    ) -> fmi2Status {
        let n_in = self.input_refs.len();
        let (refs, column) = (&self.output_refs[rows.clone()], &mut self.column[rows]);
        // SAFETY: FMI 2.0 call on a live instance; the arrays have the lengths
        // passed.
        unsafe {
            get(
                self.component,
                refs.as_ptr(),
                refs.len(),
                self.input_refs.as_ptr(),
                n_in,
                self.seed.as_ptr(),
                column.as_mut_ptr(),
            )
        }
    }

    /// The parsed model description.
    pub fn model_description(&self) -> &ModelDescription {
        &self.model
    }

    fn check(&self, call: &str, status: fmi2Status) -> Result<(), UnitError> {
        self.check_with(status, || call.to_owned())
    }

    /// Like `check`, naming the call only when it failed (no formatting per step).
    fn check_with(
        &self,
        status: fmi2Status,
        call: impl FnOnce() -> String,
    ) -> Result<(), UnitError> {
        match status {
            FMI2_OK | FMI2_WARNING => Ok(()),
            _ => Err(UnitError::Numerical(format!(
                "FMU {}: {} returned {}{}",
                self.label,
                call(),
                status_name(status),
                log_tail(&self.log)
            ))),
        }
    }

    /// Sends the inputs for a step of `h` seconds (0: initialisation): under a ramp
    /// the start value and the slope, under a zero-order hold the end value.
    fn send_inputs(&mut self, inputs: Inputs<'_>, h: f64) -> Result<(), UnitError> {
        let n = self.input_refs.len();
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
        // SAFETY: arrays of n value references and values.
        let status = unsafe {
            (self.api.set_real)(
                self.component,
                self.input_refs.as_ptr(),
                n,
                self.values.as_ptr(),
            )
        };
        self.check("fmi2SetReal (inputs)", status)?;
        if ramped {
            // SAFETY: arrays of n references, orders and values.
            let status = unsafe {
                (self.api.set_real_input_derivatives)(
                    self.component,
                    self.input_refs.as_ptr(),
                    n,
                    self.orders.as_ptr(),
                    self.slopes.as_ptr(),
                )
            };
            self.check("fmi2SetRealInputDerivatives", status)?;
        }
        Ok(())
    }

    fn read_outputs(&mut self) -> Result<(), UnitError> {
        let n = self.output_refs.len();
        if n == 0 {
            return Ok(());
        }
        // SAFETY: arrays of n references and n values.
        let status = unsafe {
            (self.api.get_real)(
                self.component,
                self.output_refs.as_ptr(),
                n,
                self.outputs.as_mut_ptr(),
            )
        };
        self.check("fmi2GetReal (outputs)", status)
    }

    fn apply_start_values(&mut self) -> Result<(), UnitError> {
        for s in &self.starts {
            // SAFETY: single-element arrays matching each setter's type.
            let (call, status) = unsafe {
                match s {
                    StartValue::Real(vr, v) => {
                        ("fmi2SetReal", (self.api.set_real)(self.component, vr, 1, v))
                    }
                    StartValue::Integer(vr, v) => (
                        "fmi2SetInteger",
                        (self.api.set_integer)(self.component, vr, 1, v),
                    ),
                    StartValue::Boolean(vr, v) => {
                        let b = if *v { FMI2_TRUE } else { FMI2_FALSE };
                        (
                            "fmi2SetBoolean",
                            (self.api.set_boolean)(self.component, vr, 1, &b),
                        )
                    }
                    StartValue::String(vr, v) => {
                        let p = v.as_ptr();
                        (
                            "fmi2SetString",
                            (self.api.set_string)(self.component, vr, 1, &p),
                        )
                    }
                }
            };
            self.check(&format!("{call} (start value)"), status)?;
        }
        Ok(())
    }
}

impl Unit for FmuUnit {
    fn description(&self) -> &UnitDescription {
        &self.description
    }

    fn initialize(&mut self, t0: Time, inputs: Inputs<'_>) -> Result<(), UnitError> {
        if self.phase == Phase::Stepping {
            // SAFETY: FMI 2.0 call on a live instance.
            let status = unsafe { (self.api.reset)(self.component) };
            self.check("fmi2Reset", status)?;
            self.phase = Phase::Instantiated;
        }
        if self.phase == Phase::Instantiated {
            // SAFETY: FMI 2.0 call on a live instance.
            let status = unsafe {
                (self.api.setup_experiment)(
                    self.component,
                    FMI2_FALSE,
                    0.0,
                    t0.as_secs(),
                    FMI2_FALSE,
                    0.0,
                )
            };
            self.check("fmi2SetupExperiment", status)?;
            self.apply_start_values()?;
            // SAFETY: as above.
            let status = unsafe { (self.api.enter_initialization_mode)(self.component) };
            self.check("fmi2EnterInitializationMode", status)?;
            self.phase = Phase::Initialization;
        }
        self.send_inputs(inputs, 0.0)?;
        self.read_outputs()
    }

    fn do_step(&mut self, t: Time, h: Time, inputs: Inputs<'_>) -> Result<StepReport, UnitError> {
        match self.phase {
            Phase::Instantiated => {
                return Err(UnitError::State(format!(
                    "FMU {}: stepped before initialisation",
                    self.label
                )));
            }
            Phase::Initialization => {
                // SAFETY: FMI 2.0 call on a live instance.
                let status = unsafe { (self.api.exit_initialization_mode)(self.component) };
                self.check("fmi2ExitInitializationMode", status)?;
                self.phase = Phase::Stepping;
            }
            Phase::Stepping => {}
        }
        let h_secs = h.as_secs();
        self.send_inputs(inputs, h_secs)?;
        let no_prior = if self.description.capabilities.rollback {
            FMI2_FALSE
        } else {
            FMI2_TRUE
        };
        // SAFETY: FMI 2.0 call on a live instance.
        let status = unsafe { (self.api.do_step)(self.component, t.as_secs(), h_secs, no_prior) };
        self.check_with(status, || {
            format!("fmi2DoStep(t = {} s, h = {h_secs} s)", t.as_secs())
        })?;
        self.read_outputs()?;
        Ok(StepReport::default())
    }

    fn outputs(&self, _inputs: Inputs<'_>, out: &mut [f64]) {
        out.copy_from_slice(&self.outputs);
    }

    /// One `fmi2GetDirectionalDerivative` per input (seed: that input), every
    /// output unknown; where the FMU refuses that, one output at a time, NaN
    /// for the outputs it refuses (a master then differences the FMU).
    fn step_jacobian(
        &mut self,
        _inputs: Inputs<'_>,
        jacobian: &mut [f64],
    ) -> Result<(), UnitError> {
        let get = self.api.get_directional_derivative.ok_or_else(|| {
            UnitError::Unsupported(format!(
                "FMU {}: no directional derivatives (providesDirectionalDerivative is false)",
                self.label
            ))
        })?;
        let (n_in, n_out) = (self.input_refs.len(), self.output_refs.len());
        for j in 0..n_in {
            self.seed.fill(0.0);
            self.seed[j] = 1.0;
            let all = self.derivative(get, 0..n_out);
            if all != FMI2_OK {
                for i in 0..n_out {
                    if self.derivative(get, i..i + 1) != FMI2_OK {
                        self.column[i] = f64::NAN;
                    }
                }
            }
            for (i, d) in self.column.iter().enumerate() {
                jacobian[i * n_in + j] = *d;
            }
        }
        Ok(())
    }

    fn save_state(&self, slot: &mut StateSlot) -> Result<(), UnitError> {
        let get = self.api.get_fmu_state.ok_or_else(|| self.no_state())?;
        // A slot this unit filled before is updated in place: the FMU overwrites
        // its state, the vectors are copied without allocating.
        if let Some(saved) = slot.get_mut::<SavedFmu>()
            && saved.owner == self.id
        {
            let mut handle = saved.handle as fmi2FMUstate;
            // SAFETY: FMI 2.0: a handle of this instance is overwritten in place.
            let status = unsafe { get(self.component, &mut handle) };
            self.check("fmi2GetFMUstate", status)?;
            saved.handle = handle as usize;
            saved.phase = self.phase;
            saved.outputs.copy_from_slice(&self.outputs);
            return Ok(());
        }
        let mut handle: fmi2FMUstate = std::ptr::null_mut();
        // SAFETY: FMI 2.0: a null handle asks for a new state.
        let status = unsafe { get(self.component, &mut handle) };
        self.check("fmi2GetFMUstate", status)?;
        if let Ok(mut states) = self.states.lock() {
            states.push(handle as usize);
        }
        slot.store(&SavedFmu {
            owner: self.id,
            handle: handle as usize,
            phase: self.phase,
            outputs: self.outputs.clone(),
        });
        Ok(())
    }

    fn restore_state(&mut self, slot: &StateSlot) -> Result<(), UnitError> {
        let saved = slot.load::<SavedFmu>()?;
        if saved.owner != self.id {
            return Err(UnitError::State(format!(
                "FMU {}: the slot holds another instance's state",
                self.label
            )));
        }
        let set = self.api.set_fmu_state.ok_or_else(|| self.no_state())?;
        // SAFETY: the handle came from this instance's fmi2GetFMUstate.
        let status = unsafe { set(self.component, saved.handle as fmi2FMUstate) };
        self.check("fmi2SetFMUstate", status)?;
        self.phase = saved.phase;
        self.outputs.copy_from_slice(&saved.outputs);
        Ok(())
    }
}

impl FmuUnit {
    fn no_state(&self) -> UnitError {
        UnitError::Unsupported(format!(
            "FMU {} does not declare canGetAndSetFMUstate, so it cannot roll back",
            self.label
        ))
    }
}

impl Drop for FmuUnit {
    fn drop(&mut self) {
        if let (Some(free_state), Ok(states)) = (self.api.free_fmu_state, self.states.get_mut()) {
            for s in states.iter() {
                let mut handle = *s as fmi2FMUstate;
                // SAFETY: handles from this instance's fmi2GetFMUstate.
                unsafe { free_state(self.component, &mut handle) };
            }
        }
        // SAFETY: ending a live instance; terminate only after initialisation.
        unsafe {
            if self.phase != Phase::Instantiated {
                (self.api.terminate)(self.component);
            }
            (self.api.free_instance)(self.component);
        }
        self.library.take();
    }
}

/// A `file://` URI for a local folder, percent-encoding what URIs reserve.
pub fn file_uri(path: &Path) -> String {
    let mut uri = String::from("file://");
    for b in path.to_string_lossy().bytes() {
        if b.is_ascii_alphanumeric() || b"/-_.~".contains(&b) {
            uri.push(b as char);
        } else {
            uri.push_str(&format!("%{b:02X}"));
        }
    }
    uri
}
