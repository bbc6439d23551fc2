//! FMI 3.0 co-simulation entry points beside FMI 2.0's, on the same
//! [`Instance`]: an FMU exported with `slender fmu export --fmi 3` carries an
//! FMI 3.0 model description and this library, which exports both sets of
//! symbols. Event-free co-simulation (no event mode, no intermediate update, no
//! early return); Float64 inputs, outputs and parameters, Int32, Boolean and
//! String parameters; FMU state get/set/serialise; directional derivatives
//! where the unit gives its step Jacobian; inputs held over a step (FMI 3.0
//! co-simulation passes no input derivatives without event mode).

use crate::instance::{Instance, guarded};
use crate::states;
use crate::{refs, texts, values, values_mut};
use slender_fmi::ffi::*;
use std::ffi::{CStr, CString, c_char, c_int, c_void};

mod unsupported;

/// FMI 3.0's status values equal FMI 2.0's (OK 0 ... Fatal 4).
type Status = c_int;
type Instance3 = *mut c_void;
type LogMessage = unsafe extern "C" fn(*mut c_void, c_int, *const c_char, *const c_char);

/// An FMI 3.0 instance's logger: `logMessage(instanceEnvironment, status,
/// category, message)`.
pub(crate) struct Logger {
    environment: *mut c_void,
    callback: LogMessage,
}

impl Logger {
    /// Sends `message` in the category of `status` (see the model
    /// description's `LogCategories`).
    pub(crate) fn log(&self, status: Status, message: &str) {
        let category = match status {
            FMI2_OK => c"logAll",
            FMI2_WARNING => c"logStatusWarning",
            _ => c"logStatusError",
        };
        let message = CString::new(message.replace('\0', " ")).unwrap_or_default();
        // SAFETY: the FMI 3.0 logMessage callback with NUL-terminated strings.
        unsafe {
            (self.callback)(
                self.environment,
                status,
                category.as_ptr(),
                message.as_ptr(),
            )
        };
    }
}

/// `fmi3GetVersion`.
#[unsafe(no_mangle)]
pub(crate) extern "C" fn fmi3GetVersion() -> *const c_char {
    c"3.0".as_ptr()
}

/// `fmi3InstantiateCoSimulation`: reads the unit's configuration from the
/// resources and checks the instantiation token; null on failure (logged).
/// Event mode and intermediate updates are refused (the FMU declares neither).
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3InstantiateCoSimulation(
    instance_name: *const c_char,
    token: *const c_char,
    resource_path: *const c_char,
    _visible: bool,
    logging_on: bool,
    event_mode_used: bool,
    _early_return_allowed: bool,
    _required_intermediate: *const u32,
    _n_required_intermediate: usize,
    environment: *mut c_void,
    log_message: Option<LogMessage>,
    _intermediate_update: *mut c_void,
) -> Instance3 {
    let text = |p: *const c_char| {
        if p.is_null() {
            String::new()
        } else {
            // SAFETY: FMI passes NUL-terminated strings.
            unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned()
        }
    };
    let logger = log_message.map(|callback| Logger {
        environment,
        callback,
    });
    let name = text(instance_name);
    let callbacks = fmi2CallbackFunctions {
        logger: None,
        allocate_memory: None,
        free_memory: None,
        step_finished: None,
        component_environment: std::ptr::null_mut(),
    };
    let result = std::panic::catch_unwind(|| {
        if event_mode_used {
            return Err("this FMU has no event mode (hasEventMode = false)".to_owned());
        }
        let resources = std::path::PathBuf::from(text(resource_path));
        Instance::new(
            name.clone(),
            &text(token),
            &resources,
            callbacks,
            logging_on,
        )
    });
    match result {
        Ok(Ok(mut instance)) => {
            instance.log3 = logger;
            Box::into_raw(Box::new(instance)).cast()
        }
        Ok(Err(message)) => {
            if let Some(l) = &logger {
                l.log(
                    FMI2_ERROR,
                    &format!("fmi3InstantiateCoSimulation: {message}"),
                );
            }
            std::ptr::null_mut()
        }
        Err(_) => {
            if let Some(l) = &logger {
                l.log(
                    FMI2_ERROR,
                    "fmi3InstantiateCoSimulation: internal error (panic caught)",
                );
            }
            std::ptr::null_mut()
        }
    }
}

/// `fmi3InstantiateModelExchange`: not offered (co-simulation only).
#[unsafe(no_mangle)]
pub(crate) extern "C" fn fmi3InstantiateModelExchange() -> Instance3 {
    std::ptr::null_mut()
}

/// `fmi3FreeInstance`.
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3FreeInstance(c: Instance3) {
    if !c.is_null() {
        let _ = std::panic::catch_unwind(|| {
            // SAFETY: `c` came from fmi3InstantiateCoSimulation, freed once.
            drop(unsafe { Box::from_raw(c.cast::<Instance>()) });
        });
    }
}

/// `fmi3SetDebugLogging` (categories ignored).
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3SetDebugLogging(
    c: Instance3,
    logging_on: bool,
    _n: usize,
    _categories: *const *const c_char,
) -> Status {
    guarded(c, "fmi3SetDebugLogging", |i| {
        i.logging = logging_on;
        Ok(FMI2_OK)
    })
}

/// `fmi3EnterInitializationMode`: the start time (tolerance and stop time
/// are not used), then initialisation mode.
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3EnterInitializationMode(
    c: Instance3,
    _tolerance_defined: bool,
    _tolerance: f64,
    start_time: f64,
    _stop_time_defined: bool,
    _stop_time: f64,
) -> Status {
    guarded(c, "fmi3EnterInitializationMode", |i| {
        i.setup(start_time)?;
        i.enter_initialization()
    })
}

/// `fmi3ExitInitializationMode`: the unit finds its initial state; step mode.
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3ExitInitializationMode(c: Instance3) -> Status {
    guarded(
        c,
        "fmi3ExitInitializationMode",
        Instance::exit_initialization,
    )
}

/// `fmi3EnterStepMode`: already there after initialisation (no event mode).
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3EnterStepMode(c: Instance3) -> Status {
    guarded(c, "fmi3EnterStepMode", |_| Ok(FMI2_OK))
}

/// `fmi3Terminate`.
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3Terminate(c: Instance3) -> Status {
    guarded(c, "fmi3Terminate", Instance::terminate)
}

/// `fmi3Reset`: back to the instantiated state with the exported parameters.
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3Reset(c: Instance3) -> Status {
    guarded(c, "fmi3Reset", Instance::reset)
}

/// `fmi3GetFloat64`: inputs, outputs, Float64 parameters and `time`.
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3GetFloat64(
    c: Instance3,
    vr: *const u32,
    n_vr: usize,
    value: *mut f64,
    n_values: usize,
) -> Status {
    guarded(c, "fmi3GetFloat64", |i| {
        // SAFETY: FMI array arguments of the lengths given (scalars: equal).
        let (vr, value) = unsafe { (refs(vr, n_vr)?, values_mut(value, n_values)?) };
        i.get_real(vr, value)
    })
}

/// `fmi3SetFloat64`: inputs (any time) and Float64 parameters (before
/// initialisation ends).
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3SetFloat64(
    c: Instance3,
    vr: *const u32,
    n_vr: usize,
    value: *const f64,
    n_values: usize,
) -> Status {
    guarded(c, "fmi3SetFloat64", |i| {
        // SAFETY: FMI array arguments of the lengths given.
        let (vr, value) = unsafe { (refs(vr, n_vr)?, values(value, n_values)?) };
        i.set_real(vr, value)
    })
}

/// `fmi3GetInt32`: Int32 parameters.
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3GetInt32(
    c: Instance3,
    vr: *const u32,
    n_vr: usize,
    value: *mut i32,
    n_values: usize,
) -> Status {
    guarded(c, "fmi3GetInt32", |i| {
        // SAFETY: FMI array arguments of the lengths given.
        let (vr, value) = unsafe { (refs(vr, n_vr)?, values_mut(value, n_values)?) };
        i.get_integer(vr, value, false)
    })
}

/// `fmi3SetInt32`: Int32 parameters.
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3SetInt32(
    c: Instance3,
    vr: *const u32,
    n_vr: usize,
    value: *const i32,
    n_values: usize,
) -> Status {
    guarded(c, "fmi3SetInt32", |i| {
        // SAFETY: FMI array arguments of the lengths given.
        let (vr, value) = unsafe { (refs(vr, n_vr)?, values(value, n_values)?) };
        i.set_integer(vr, value, false)
    })
}

/// `fmi3EnterConfigurationMode`: where the array sizes are set.
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3EnterConfigurationMode(c: Instance3) -> Status {
    guarded(
        c,
        "fmi3EnterConfigurationMode",
        Instance::enter_configuration,
    )
}

/// `fmi3ExitConfigurationMode`: back to the Instantiated state.
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3ExitConfigurationMode(c: Instance3) -> Status {
    guarded(c, "fmi3ExitConfigurationMode", Instance::exit_configuration)
}

/// `fmi3GetUInt64`: the array sizes (structural parameters `n_nodes`,
/// `n_elements`).
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3GetUInt64(
    c: Instance3,
    vr: *const u32,
    n_vr: usize,
    value: *mut u64,
    n_values: usize,
) -> Status {
    guarded(c, "fmi3GetUInt64", |i| {
        // SAFETY: FMI array arguments of the lengths given.
        let (vr, value) = unsafe { (refs(vr, n_vr)?, values_mut(value, n_values)?) };
        i.get_sizes(vr, value)
    })
}

/// `fmi3SetUInt64`: the array sizes, before initialisation.
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3SetUInt64(
    c: Instance3,
    vr: *const u32,
    n_vr: usize,
    value: *const u64,
    n_values: usize,
) -> Status {
    guarded(c, "fmi3SetUInt64", |i| {
        // SAFETY: FMI array arguments of the lengths given.
        let (vr, value) = unsafe { (refs(vr, n_vr)?, values(value, n_values)?) };
        i.set_sizes(vr, value)
    })
}

/// `fmi3GetBoolean`: Boolean parameters (`effects.<name>`; C `bool`s).
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3GetBoolean(
    c: Instance3,
    vr: *const u32,
    n_vr: usize,
    value: *mut bool,
    n_values: usize,
) -> Status {
    guarded(c, "fmi3GetBoolean", |i| {
        // SAFETY: FMI array arguments of the lengths given.
        let (vr, value) = unsafe { (refs(vr, n_vr)?, values_mut(value, n_values)?) };
        let mut ints = vec![0; vr.len()];
        let status = i.get_integer(vr, &mut ints, true)?;
        for (b, v) in value.iter_mut().zip(ints) {
            *b = v != 0;
        }
        Ok(status)
    })
}

/// `fmi3SetBoolean`: Boolean parameters.
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3SetBoolean(
    c: Instance3,
    vr: *const u32,
    n_vr: usize,
    value: *const bool,
    n_values: usize,
) -> Status {
    guarded(c, "fmi3SetBoolean", |i| {
        // SAFETY: FMI array arguments of the lengths given.
        let (vr, value) = unsafe { (refs(vr, n_vr)?, values(value, n_values)?) };
        let ints: Vec<c_int> = value.iter().map(|b| c_int::from(*b)).collect();
        i.set_integer(vr, &ints, true)
    })
}

/// `fmi3GetString`: String parameters (pointers valid until the next call).
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3GetString(
    c: Instance3,
    vr: *const u32,
    n_vr: usize,
    value: *mut *const c_char,
    n_values: usize,
) -> Status {
    guarded(c, "fmi3GetString", |i| {
        // SAFETY: FMI array arguments of the lengths given.
        let (vr, value) = unsafe { (refs(vr, n_vr)?, values_mut(value, n_values)?) };
        i.get_string(vr, value)
    })
}

/// `fmi3SetString`: String parameters.
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3SetString(
    c: Instance3,
    vr: *const u32,
    n_vr: usize,
    value: *const *const c_char,
    n_values: usize,
) -> Status {
    guarded(c, "fmi3SetString", |i| {
        // SAFETY: FMI array arguments of the lengths given.
        let (vr, value) = unsafe { (refs(vr, n_vr)?, values(value, n_values)?) };
        // SAFETY: FMI passes NUL-terminated strings.
        let texts = unsafe { texts(value)? };
        i.set_string(vr, &texts)
    })
}

/// `fmi3DoStep`: one step, never ended early, no event, not terminating.
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3DoStep(
    c: Instance3,
    t: f64,
    h: f64,
    _no_set_state_prior: bool,
    event_handling_needed: *mut bool,
    terminate_simulation: *mut bool,
    early_return: *mut bool,
    last_successful_time: *mut f64,
) -> Status {
    guarded(c, "fmi3DoStep", |i| {
        let status = i.do_step(t, h)?;
        // SAFETY: FMI passes pointers to the flags (checked non-null).
        unsafe {
            for flag in [event_handling_needed, terminate_simulation, early_return] {
                if !flag.is_null() {
                    *flag = false;
                }
            }
            if !last_successful_time.is_null() {
                *last_successful_time = i.time_secs();
            }
        }
        Ok(status)
    })
}

/// `fmi3GetFMUState`: a copy of the unit's state.
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3GetFMUState(c: Instance3, state: *mut fmi2FMUstate) -> Status {
    unsafe { states::get(c, "fmi3GetFMUState", state) }
}

/// `fmi3SetFMUState`.
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3SetFMUState(c: Instance3, state: fmi2FMUstate) -> Status {
    guarded(c, "fmi3SetFMUState", |i| i.set_state(state))
}

/// `fmi3FreeFMUState`.
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3FreeFMUState(c: Instance3, state: *mut fmi2FMUstate) -> Status {
    unsafe { states::free(c, "fmi3FreeFMUState", state) }
}

/// `fmi3SerializedFMUStateSize`.
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3SerializedFMUStateSize(
    c: Instance3,
    state: fmi2FMUstate,
    size: *mut usize,
) -> Status {
    unsafe { states::size(c, "fmi3SerializedFMUStateSize", state, size) }
}

/// `fmi3SerializeFMUState`.
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3SerializeFMUState(
    c: Instance3,
    state: fmi2FMUstate,
    bytes: *mut u8,
    size: usize,
) -> Status {
    unsafe { states::serialize(c, "fmi3SerializeFMUState", state, (bytes, size)) }
}

/// `fmi3DeserializeFMUState`.
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3DeserializeFMUState(
    c: Instance3,
    bytes: *const u8,
    size: usize,
    state: *mut fmi2FMUstate,
) -> Status {
    unsafe { states::deserialize(c, "fmi3DeserializeFMUState", (bytes, size), state) }
}

/// `fmi3GetDirectionalDerivative`: the outputs' partial derivatives at the
/// current instant, as the standard defines them (zero for a unit without
/// feedthrough); the step Jacobian is `slenderGetStepDerivative`.
#[unsafe(no_mangle)]
pub(crate) unsafe extern "C" fn fmi3GetDirectionalDerivative(
    c: Instance3,
    unknowns: *const u32,
    n_unknowns: usize,
    knowns: *const u32,
    n_knowns: usize,
    seed: *const f64,
    n_seed: usize,
    sensitivity: *mut f64,
    n_sensitivity: usize,
) -> Status {
    guarded(c, "fmi3GetDirectionalDerivative", |i| {
        // SAFETY: FMI array arguments of the lengths given.
        let (unknowns, knowns, _, sensitivity) = unsafe {
            (
                refs(unknowns, n_unknowns)?,
                refs(knowns, n_knowns)?,
                values(seed, n_seed)?,
                values_mut(sensitivity, n_sensitivity)?,
            )
        };
        // Scalar unknowns are checked as outputs; an array's elements are
        // zero alike.
        let scalar = (sensitivity.len() == unknowns.len()).then_some(unknowns);
        i.directional_derivative((scalar, knowns), sensitivity)
    })
}
