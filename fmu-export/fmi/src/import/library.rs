//! The FMU's shared library: its FMI entry points bound once, the C logger shim
//! and the log kept for error messages, loading with every symbol bound now.

use super::{LoadError, file_uri};
use crate::ffi::*;
use crate::model_description::ModelDescription;
use std::ffi::{CStr, CString, c_char, c_int, c_void};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

unsafe extern "C" {
    pub(super) fn calloc(count: usize, size: usize) -> *mut c_void;
    pub(super) fn free(pointer: *mut c_void);
    /// The C shim in `logger.c`.
    pub(super) fn slender_fmi_logger(
        environment: fmi2ComponentEnvironment,
        instance: fmi2String,
        status: fmi2Status,
        category: fmi2String,
        format: fmi2String,
        ...
    );
}

/// Messages an FMU logged, kept for error reports (the last few).
#[derive(Default)]
pub(super) struct LogBook(Mutex<Vec<String>>);

pub(super) const LOG_KEPT: usize = 20;

/// Called by the C logger shim with the formatted message.
#[unsafe(no_mangle)]
pub(super) extern "C" fn slender_fmi_log_sink(
    environment: *mut c_void,
    instance: *const c_char,
    status: c_int,
    category: *const c_char,
    message: *const c_char,
) {
    // SAFETY: the environment is the LogBook the unit registered and outlives
    // the FMU instance (dropped after fmi2FreeInstance).
    unsafe { LogBook::push_to(environment, instance, status, category, message) }
}

impl LogBook {
    /// A logger callback's message into the LogBook its `environment` points
    /// to (nothing when null), FMI 2.0 and 3.0 alike; never unwinds into the
    /// FMU.
    ///
    /// # Safety
    /// A non-null `environment` is a `LogBook` that outlives the call.
    pub(super) unsafe fn push_to(
        environment: *mut c_void,
        instance: *const c_char,
        status: c_int,
        category: *const c_char,
        message: *const c_char,
    ) {
        let _ = std::panic::catch_unwind(|| {
            if environment.is_null() {
                return;
            }
            // SAFETY: by the caller.
            let book = unsafe { &*(environment as *const LogBook) };
            book.push(instance, status, category, message);
        });
    }

    /// Keeps one message (the last [`LOG_KEPT`]); the strings are
    /// NUL-terminated or null.
    pub(super) fn push(
        &self,
        instance: *const c_char,
        status: c_int,
        category: *const c_char,
        message: *const c_char,
    ) {
        let text = |p: *const c_char| {
            if p.is_null() {
                String::new()
            } else {
                // SAFETY: FMUs pass NUL-terminated strings (FMI logger contract).
                unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned()
            }
        };
        if let Ok(mut lines) = self.0.lock() {
            if lines.len() == LOG_KEPT {
                lines.remove(0);
            }
            let who = text(instance);
            let who = if who.is_empty() {
                who
            } else {
                format!("{who} ")
            };
            lines.push(format!(
                "[{who}{} {}] {}",
                status_name(status),
                text(category),
                text(message)
            ));
        }
    }
}

pub(super) type Instantiate = unsafe extern "C" fn(
    fmi2String,
    fmi2Type,
    fmi2String,
    fmi2String,
    *const fmi2CallbackFunctions,
    fmi2Boolean,
    fmi2Boolean,
) -> fmi2Component;
pub(super) type FreeInstance = unsafe extern "C" fn(fmi2Component);
pub(super) type SetupExperiment =
    unsafe extern "C" fn(fmi2Component, fmi2Boolean, f64, f64, fmi2Boolean, f64) -> fmi2Status;
pub(super) type Plain = unsafe extern "C" fn(fmi2Component) -> fmi2Status;
pub(super) type GetReal =
    unsafe extern "C" fn(fmi2Component, *const fmi2ValueReference, usize, *mut f64) -> fmi2Status;
pub(super) type GetInteger = unsafe extern "C" fn(
    fmi2Component,
    *const fmi2ValueReference,
    usize,
    *mut fmi2Integer,
) -> fmi2Status;
pub(super) type SetReal =
    unsafe extern "C" fn(fmi2Component, *const fmi2ValueReference, usize, *const f64) -> fmi2Status;
pub(super) type SetInteger = unsafe extern "C" fn(
    fmi2Component,
    *const fmi2ValueReference,
    usize,
    *const fmi2Integer,
) -> fmi2Status;
pub(super) type SetString = unsafe extern "C" fn(
    fmi2Component,
    *const fmi2ValueReference,
    usize,
    *const fmi2String,
) -> fmi2Status;
pub(super) type StateCall = unsafe extern "C" fn(fmi2Component, *mut fmi2FMUstate) -> fmi2Status;
pub(super) type SetState = unsafe extern "C" fn(fmi2Component, fmi2FMUstate) -> fmi2Status;
pub(super) type SetDerivatives = unsafe extern "C" fn(
    fmi2Component,
    *const fmi2ValueReference,
    usize,
    *const fmi2Integer,
    *const f64,
) -> fmi2Status;
pub(super) type DoStep = unsafe extern "C" fn(fmi2Component, f64, f64, fmi2Boolean) -> fmi2Status;
pub(super) type GetDirectionalDerivative = unsafe extern "C" fn(
    fmi2Component,
    *const fmi2ValueReference,
    usize,
    *const fmi2ValueReference,
    usize,
    *const f64,
    *mut f64,
) -> fmi2Status;

/// `fmi2GetBooleanStatus`: after an `fmi2DoStep` that returned `fmi2Discard`,
/// whether the slave asks to end the simulation (`fmi2Terminated`).
pub(super) type GetBooleanStatus =
    unsafe extern "C" fn(fmi2Component, i32, *mut fmi2Boolean) -> fmi2Status;

/// FMI 2.0's `fmi2StatusKind` `fmi2Terminated`.
pub(super) const FMI2_TERMINATED: i32 = 3;

/// slender's extension `slenderGivesStepDerivative`: whether the instance's
/// unit gives its step Jacobian (fmi2True) through `slenderGetStepDerivative`.
pub(super) type GivesStepDerivative = unsafe extern "C" fn(fmi2Component) -> fmi2Boolean;

/// The FMU's entry points, bound once.
pub(super) struct Api {
    pub(super) instantiate: Instantiate,
    pub(super) free_instance: FreeInstance,
    pub(super) setup_experiment: SetupExperiment,
    pub(super) enter_initialization_mode: Plain,
    pub(super) exit_initialization_mode: Plain,
    pub(super) terminate: Plain,
    pub(super) reset: Plain,
    pub(super) get_real: GetReal,
    pub(super) get_integer: GetInteger,
    pub(super) set_real: SetReal,
    pub(super) set_integer: SetInteger,
    pub(super) set_boolean: SetInteger,
    pub(super) set_string: SetString,
    pub(super) set_real_input_derivatives: SetDerivatives,
    pub(super) do_step: DoStep,
    /// `fmi2GetBooleanStatus` (co-simulation), where exported.
    pub(super) get_boolean_status: Option<GetBooleanStatus>,
    pub(super) get_fmu_state: Option<StateCall>,
    pub(super) set_fmu_state: Option<SetState>,
    pub(super) free_fmu_state: Option<StateCall>,
    /// slender's extension (the step Jacobian), where the binary exports it.
    pub(super) step_derivative: Option<StepDerivative>,
}

/// slender's step-derivative extension: whether an instance gives it, and
/// the derivative itself (FMI 2.0's `GetDirectionalDerivative` signature).
#[derive(Clone, Copy)]
pub(super) struct StepDerivative {
    pub(super) gives: GivesStepDerivative,
    pub(super) get: GetDirectionalDerivative,
}

pub(super) fn symbol<T: Copy>(library: &libloading::Library, name: &str) -> Result<T, String> {
    let c_name = format!("{name}\0");
    // SAFETY: the types above are the FMI 2.0 signatures of these names.
    unsafe { library.get::<T>(c_name.as_bytes()) }
        .map(|s| *s)
        .map_err(|_| {
            format!(
                "the binary does not export `{name}` (required by FMI {}.0 co-simulation)",
                if name.starts_with("fmi3") { 3 } else { 2 }
            )
        })
}

/// The entry point `name` when `wanted` (an optional capability the model
/// description declares), else `None`.
pub(super) fn optional<T: Copy>(
    library: &libloading::Library,
    wanted: bool,
    name: &str,
) -> Result<Option<T>, String> {
    wanted.then(|| symbol(library, name)).transpose()
}

impl Api {
    /// Binds the entry points; the state calls when `states` (as the model
    /// description declares them), the step derivative where exported.
    pub(super) fn bind(library: &libloading::Library, states: bool) -> Result<Api, String> {
        Ok(Api {
            instantiate: symbol(library, "fmi2Instantiate")?,
            free_instance: symbol(library, "fmi2FreeInstance")?,
            setup_experiment: symbol(library, "fmi2SetupExperiment")?,
            enter_initialization_mode: symbol(library, "fmi2EnterInitializationMode")?,
            exit_initialization_mode: symbol(library, "fmi2ExitInitializationMode")?,
            terminate: symbol(library, "fmi2Terminate")?,
            reset: symbol(library, "fmi2Reset")?,
            get_real: symbol(library, "fmi2GetReal")?,
            get_integer: symbol(library, "fmi2GetInteger")?,
            set_real: symbol(library, "fmi2SetReal")?,
            set_integer: symbol(library, "fmi2SetInteger")?,
            set_boolean: symbol(library, "fmi2SetBoolean")?,
            set_string: symbol(library, "fmi2SetString")?,
            set_real_input_derivatives: symbol(library, "fmi2SetRealInputDerivatives")?,
            do_step: symbol(library, "fmi2DoStep")?,
            get_boolean_status: symbol(library, "fmi2GetBooleanStatus").ok(),
            get_fmu_state: optional(library, states, "fmi2GetFMUstate")?,
            set_fmu_state: optional(library, states, "fmi2SetFMUstate")?,
            free_fmu_state: optional(library, states, "fmi2FreeFMUstate")?,
            step_derivative: step_derivative(library),
        })
    }
}

/// slender's extension `slenderGetStepDerivative` where the binary exports
/// it (an FMU made by slender): the step Jacobian. The standard's
/// `GetDirectionalDerivative` is the derivative at an instant, which is not
/// what an interface-Jacobian master needs over a step, so it is not used.
pub(super) fn step_derivative(library: &libloading::Library) -> Option<StepDerivative> {
    Some(StepDerivative {
        gives: symbol(library, "slenderGivesStepDerivative").ok()?,
        get: symbol(library, "slenderGetStepDerivative").ok()?,
    })
}

/// Opens a shared library with every symbol bound now, so a missing one fails
/// here rather than mid-run.
pub(super) fn open_now(path: &Path) -> Result<libloading::Library, String> {
    use libloading::os::unix::{Library, RTLD_LOCAL, RTLD_NOW};
    // SAFETY: loading runs the library's initialisers; FMU binaries are trusted
    // code chosen by the scene's author.
    unsafe { Library::open(Some(path), RTLD_NOW | RTLD_LOCAL) }
        .map(Into::into)
        .map_err(|e| e.to_string())
}

/// Loads a library with its symbols visible to later libraries, and keeps it
/// for the life of the process (libpython must not be unloaded under an
/// interpreter that may still run).
pub(super) fn preload_globally(path: &Path) -> Result<(), String> {
    use libloading::os::unix::{Library, RTLD_GLOBAL, RTLD_NOW};
    // SAFETY: as in `open_now`.
    let library = unsafe { Library::open(Some(path), RTLD_NOW | RTLD_GLOBAL) }
        .map_err(|e| format!("{}: {e}", path.display()))?;
    std::mem::forget(library);
    Ok(())
}

pub(super) fn log_tail(log: &LogBook) -> String {
    match log.0.lock() {
        Ok(lines) if !lines.is_empty() => format!("; the FMU logged: {}", lines.join(" | ")),
        _ => String::new(),
    }
}

/// `fmi2Instantiate` with slender's logger (keeping the FMU's log lines for error
/// messages) and the FMU's resources folder; the log and callbacks must outlive
/// the instance.
pub(super) fn instantiate(
    api: &Api,
    model: &ModelDescription,
    folder: &Path,
    logging: bool,
    label: &str,
) -> Result<(fmi2Component, Box<LogBook>, Box<fmi2CallbackFunctions>), LoadError> {
    let log = Box::new(LogBook::default());
    // SAFETY: the shim has the C-variadic logger signature; only its type
    // differs in how Rust spells it.
    let logger: fmi2CallbackLogger = Some(slender_fmi_logger);
    let callbacks = Box::new(fmi2CallbackFunctions {
        logger,
        allocate_memory: Some(calloc),
        free_memory: Some(free),
        step_finished: None,
        component_environment: &*log as *const LogBook as *mut c_void,
    });
    let resources = folder.join("resources");
    let uri = file_uri(&resources);
    let c = |s: &str| {
        CString::new(s).map_err(|_| LoadError::Nul {
            fmu: label.to_owned(),
            text: s.to_owned(),
        })
    };
    let (name, guid, uri) = (c(&model.model_name)?, c(&model.guid)?, c(&uri)?);
    // SAFETY: FMI 2.0 fmi2Instantiate with valid C strings and callbacks that
    // outlive the instance.
    let component = unsafe {
        (api.instantiate)(
            name.as_ptr(),
            FMI2_CO_SIMULATION,
            guid.as_ptr(),
            uri.as_ptr(),
            &*callbacks,
            FMI2_FALSE,
            if logging { FMI2_TRUE } else { FMI2_FALSE },
        )
    };
    if component.is_null() {
        return Err(LoadError::Instantiate {
            fmu: label.to_owned(),
            call: "fmi2Instantiate",
            log: log_tail(&log),
        });
    }
    Ok((component, log, callbacks))
}

/// Loads the FMU's binary with every symbol bound now, after the libraries to
/// preload (libpython for pythonfmu FMUs, with a hint when it is missing).
pub(super) fn open_binary(
    binary: &Path,
    preload: &[PathBuf],
    label: &str,
) -> Result<libloading::Library, LoadError> {
    let library_error = |message: String| LoadError::Library {
        fmu: label.to_owned(),
        message,
    };
    for lib in preload {
        preload_globally(lib).map_err(|e| library_error(format!("preload: {e}")))?;
    }
    open_now(binary).map_err(|e| {
            library_error(if e.contains("undefined symbol") && e.contains("Py") {
                format!(
                    "the FMU was built with Python (e.g. pythonfmu) and needs libpython loaded first ({e}). Add `preload = [\"<LIBDIR>/libpython3.X.so\"]` to the unit's parameters, LIBDIR from `python3 -c \"import sysconfig; print(sysconfig.get_config_var('LIBDIR'))\"`, or run with LD_PRELOAD set to that library"
                )
            } else {
                format!("cannot load {} ({e})", binary.display())
            })
        })
}
