//! Importing an FMI 2.0 or FMI 3.0 co-simulation FMU as a unit.
//!
//! The FMU is unzipped into a temporary folder, its model description parsed and
//! its `binaries/linux64/<modelIdentifier>.so` (FMI 3.0:
//! `binaries/x86_64-linux/`) loaded with every symbol bound at load time. Real
//! (Float64) inputs and outputs become ports, an FMI 3.0 array one port per
//! element (`name[1]`, `name[2]`, ... row-major); their kind follows from the
//! unit of measure (N: force, m/s: velocity, ...), direct feedthrough from the
//! model structure's outputs. Rollback is offered only when the FMU declares
//! that it can get and set its state.
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

use describe::{describe, integer_output_refs, real_refs, start_values};
pub use error::LoadError;
mod api3;
mod calls;
mod exchange;
use api3::Api3;
use calls::Calls;
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

/// An FMI 2.0 or 3.0 co-simulation FMU behind the unit contract.
pub struct FmuUnit {
    /// The FMU's file name, for messages.
    label: String,
    id: u64,
    description: UnitDescription,
    model: ModelDescription,
    calls: Calls,
    component: fmi2Component,
    phase: Phase,
    starts: Vec<StartValue>,
    /// The value references of the Real inputs and outputs (an array's one
    /// reference stands for all its elements, which follow in the values).
    input_refs: Vec<u32>,
    output_refs: Vec<u32>,
    /// How many values each output reference holds (1 for a scalar).
    output_sizes: Vec<usize>,
    /// The scalar Integer outputs' references and their values (scratch):
    /// their ports follow the Real outputs'.
    integer_refs: Vec<u32>,
    integers: Vec<i32>,
    /// The input values sent before a step: start values of ramped inputs, end
    /// values of held ones (scratch).
    values: Vec<f64>,
    /// The ramps' slopes sent with them (scratch).
    slopes: Vec<f64>,
    orders: Vec<fmi2Integer>,
    outputs: Vec<f64>,
    /// A seed of the step derivative and its answer (scratch).
    seed: Vec<f64>,
    column: Vec<f64>,
    /// Every FMU state handle handed out, freed with the instance.
    states: Mutex<Vec<usize>>,
    log: Box<LogBook>,
    /// Kept alive for an FMI 2.0 instance, which holds a pointer to them.
    _callbacks: Option<Box<fmi2CallbackFunctions>>,
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
        let three = model.fmi_version.starts_with('3');
        let binary = binary_for_this_platform(folder.path(), &cs.model_identifier, three, &label)?;
        let library = open_binary(&binary, &params.preload, &label)?;
        let states = cs.can_get_and_set_fmu_state;
        let library_error = |message| LoadError::Library {
            fmu: label.clone(),
            message,
        };
        let calls = if three {
            Calls::Three(Api3::bind(&library, states).map_err(library_error)?)
        } else {
            Calls::Two(Api::bind(&library, states).map_err(library_error)?)
        };
        let mut description = describe(&model, &label)?;
        let starts = start_values(&model, &params.start, &label)?;
        given_input_starts(&mut description, &params.start);
        let (input_refs, _) = real_refs(&model, VariableCausality::Input);
        let (output_refs, output_sizes) = real_refs(&model, VariableCausality::Output);
        let integer_refs = integer_output_refs(&model);
        let (n_in, n_out) = (description.inputs.len(), description.outputs.len());
        let (component, log, callbacks) = match &calls {
            Calls::Two(api) => {
                let (c, log, callbacks) =
                    instantiate(api, &model, folder.path(), params.logging, &label)?;
                (c, log, Some(callbacks))
            }
            Calls::Three(api) => {
                let (c, log) = api.instantiate(&model, folder.path(), params.logging, &label)?;
                (c, log, None)
            }
        };
        // The step Jacobian where the FMU gives it (slender's extension), not
        // the standard's derivative at an instant.
        // SAFETY: a call on the live instance just made.
        description.capabilities.step_jacobian = unsafe { calls.gives_step_derivative(component) };
        let mut unit = FmuUnit {
            label,
            id: NEXT_ID.fetch_add(1, Ordering::Relaxed),
            description,
            model,
            calls,
            component,
            phase: Phase::Instantiated,
            starts,
            input_refs,
            values: vec![0.0; n_in],
            slopes: vec![0.0; n_in],
            orders: vec![1; n_in],
            outputs: vec![0.0; n_out],
            seed: vec![0.0; n_in],
            column: vec![0.0; n_out],
            output_refs,
            output_sizes,
            integers: vec![0; integer_refs.len()],
            integer_refs,
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

    /// The step derivative (slender's extension) of the output references `refs` (their
    /// values from `first` in `column`) for the seed; the status.
    fn derivative(&mut self, refs: std::ops::Range<usize>, first: usize) -> fmi2Status {
        let size: usize = self.output_sizes[refs.clone()].iter().sum();
        let (refs, column) = (
            &self.output_refs[refs],
            &mut self.column[first..first + size],
        );
        // SAFETY: a call on a live instance; the arrays have the lengths passed.
        unsafe {
            self.calls
                .step_derivative(self.component, (refs, &self.input_refs), &self.seed, column)
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
}

impl Unit for FmuUnit {
    fn description(&self) -> &UnitDescription {
        &self.description
    }

    fn initialize(&mut self, t0: Time, inputs: Inputs<'_>) -> Result<(), UnitError> {
        let calls = &self.calls;
        if self.phase == Phase::Stepping {
            // SAFETY: a call on a live instance.
            let status = unsafe { calls.reset(self.component) };
            self.check(calls.name("fmi2Reset", "fmi3Reset"), status)?;
            self.phase = Phase::Instantiated;
        }
        if self.phase == Phase::Instantiated {
            // SAFETY: as above.
            let status = unsafe { calls.setup(self.component, t0.as_secs()) };
            self.check("fmi2SetupExperiment", status)?;
            self.apply_start_values()?;
            // SAFETY: as above.
            let status = unsafe {
                self.calls
                    .enter_initialization(self.component, t0.as_secs())
            };
            let call = self
                .calls
                .name("fmi2EnterInitializationMode", "fmi3EnterInitializationMode");
            self.check(call, status)?;
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
                // SAFETY: a call on a live instance.
                let status = unsafe { self.calls.exit_initialization(self.component) };
                let call = self
                    .calls
                    .name("fmi2ExitInitializationMode", "fmi3ExitInitializationMode");
                self.check(call, status)?;
                self.phase = Phase::Stepping;
            }
            Phase::Stepping => {}
        }
        let h_secs = h.as_secs();
        self.send_inputs(inputs, h_secs)?;
        let no_prior = !self.description.capabilities.rollback;
        // SAFETY: a call on a live instance.
        let (status, terminate) = unsafe {
            self.calls
                .do_step(self.component, t.as_secs(), h_secs, no_prior)
        };
        let call = || {
            format!(
                "{}(t = {} s, h = {h_secs} s)",
                self.calls.name("fmi2DoStep", "fmi3DoStep"),
                t.as_secs()
            )
        };
        self.check_with(status, call)?;
        if terminate {
            return Err(UnitError::EndRequested(format!(
                "FMU {} in {}{}",
                self.label,
                call(),
                log_tail(&self.log)
            )));
        }
        self.read_outputs()?;
        Ok(StepReport::default())
    }

    fn outputs(&self, _inputs: Inputs<'_>, out: &mut [f64]) {
        out.copy_from_slice(&self.outputs);
    }

    /// One step derivative (slender's extension) per input (seed: that
    /// input), every output unknown; where the FMU refuses that, one output (or array) at
    /// a time, NaN for those it refuses (a master then differences the FMU).
    fn step_jacobian(
        &mut self,
        _inputs: Inputs<'_>,
        jacobian: &mut [f64],
    ) -> Result<(), UnitError> {
        if !self.description.capabilities.step_jacobian {
            return Err(UnitError::Unsupported(format!(
                "FMU {}: no step Jacobian (only an FMU made by slender gives one, through its extension slenderGetStepDerivative; the standard's directional derivative is the derivative at an instant)",
                self.label
            )));
        }
        let (n_in, n_refs) = (self.values.len(), self.output_refs.len());
        for j in 0..n_in {
            self.seed.fill(0.0);
            self.seed[j] = 1.0;
            if self.derivative(0..n_refs, 0) != FMI2_OK {
                let mut first = 0;
                for r in 0..n_refs {
                    let size = self.output_sizes[r];
                    if self.derivative(r..r + 1, first) != FMI2_OK {
                        self.column[first..first + size].fill(f64::NAN);
                    }
                    first += size;
                }
            }
            for (i, d) in self.column.iter().enumerate() {
                jacobian[i * n_in + j] = *d;
            }
        }
        Ok(())
    }

    fn save_state(&self, slot: &mut StateSlot) -> Result<(), UnitError> {
        if !self.calls.has_state() {
            return Err(self.no_state());
        }
        let call = self.calls.name("fmi2GetFMUstate", "fmi3GetFMUState");
        // A slot this unit filled before is updated in place: the FMU overwrites
        // its state, the vectors are copied without allocating.
        if let Some(saved) = slot.get_mut::<SavedFmu>()
            && saved.owner == self.id
        {
            let mut handle = saved.handle as fmi2FMUstate;
            // SAFETY: FMI 2.0: a handle of this instance is overwritten in place.
            let status = unsafe { self.calls.get_state(self.component, &mut handle) };
            self.check(call, status)?;
            saved.handle = handle as usize;
            saved.phase = self.phase;
            saved.outputs.copy_from_slice(&self.outputs);
            return Ok(());
        }
        let mut handle: fmi2FMUstate = std::ptr::null_mut();
        // SAFETY: FMI 2.0: a null handle asks for a new state.
        let status = unsafe { self.calls.get_state(self.component, &mut handle) };
        self.check(call, status)?;
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
        if !self.calls.has_state() {
            return Err(self.no_state());
        }
        // SAFETY: the handle came from this instance's get-state call.
        let status = unsafe {
            self.calls
                .set_state(self.component, saved.handle as fmi2FMUstate)
        };
        self.check(
            self.calls.name("fmi2SetFMUstate", "fmi3SetFMUState"),
            status,
        )?;
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
        if let Ok(states) = self.states.get_mut() {
            for s in states.iter() {
                let mut handle = *s as fmi2FMUstate;
                // SAFETY: handles from this instance's get-state call.
                unsafe { self.calls.free_state(self.component, &mut handle) };
            }
        }
        // SAFETY: ending a live instance; terminate only after initialisation.
        unsafe {
            if self.phase != Phase::Instantiated {
                self.calls.terminate(self.component);
            }
            self.calls.free_instance(self.component);
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

/// A start value the scene gives an input is its value where nothing drives
/// it (the master sent 0 over it before).
fn given_input_starts(description: &mut UnitDescription, given: &BTreeMap<String, toml::Value>) {
    for port in description.inputs.iter_mut() {
        let names = std::iter::once(&port.name).chain(&port.aliases);
        let value = names.filter_map(|n| given.get(n)).next();
        if let Some(x) = value.and_then(|v| v.as_float().or(v.as_integer().map(|i| i as f64))) {
            port.start = Some(x);
        }
    }
}
