//! The FMI 3.0 co-simulation entry points an importer calls, bound once, and
//! the FMI 3.0 logger (not variadic: the FMU formats its message).

use super::LoadError;
use super::library::{LogBook, log_tail, optional, symbol};
use crate::model_description::ModelDescription;
use std::ffi::{CString, c_char, c_int, c_void};
use std::path::Path;

pub(super) type Instance = *mut c_void;
pub(super) type Status = c_int;
type LogMessage = unsafe extern "C" fn(*mut c_void, Status, *const c_char, *const c_char);
type Instantiate = unsafe extern "C" fn(
    *const c_char,
    *const c_char,
    *const c_char,
    bool,
    bool,
    bool,
    bool,
    *const u32,
    usize,
    *mut c_void,
    Option<LogMessage>,
    *mut c_void,
) -> Instance;
type FreeInstance = unsafe extern "C" fn(Instance);
type EnterInitialization = unsafe extern "C" fn(Instance, bool, f64, f64, bool, f64) -> Status;
pub(super) type Plain = unsafe extern "C" fn(Instance) -> Status;
type Get<T> = unsafe extern "C" fn(Instance, *const u32, usize, *mut T, usize) -> Status;
type Set<T> = unsafe extern "C" fn(Instance, *const u32, usize, *const T, usize) -> Status;
type DoStep = unsafe extern "C" fn(
    Instance,
    f64,
    f64,
    bool,
    *mut bool,
    *mut bool,
    *mut bool,
    *mut f64,
) -> Status;
pub(super) type StateCall = unsafe extern "C" fn(Instance, *mut *mut c_void) -> Status;
pub(super) type SetState = unsafe extern "C" fn(Instance, *mut c_void) -> Status;

/// An FMI 3.0 FMU's entry points.
pub(super) struct Api3 {
    instantiate: Instantiate,
    pub(super) free_instance: FreeInstance,
    pub(super) enter_initialization_mode: EnterInitialization,
    pub(super) exit_initialization_mode: Plain,
    pub(super) terminate: Plain,
    pub(super) reset: Plain,
    pub(super) get_float64: Get<f64>,
    pub(super) get_int32: Get<i32>,
    pub(super) set_float64: Set<f64>,
    pub(super) set_int32: Set<i32>,
    pub(super) set_boolean: Set<bool>,
    pub(super) set_string: Set<*const c_char>,
    pub(super) do_step: DoStep,
    pub(super) get_fmu_state: Option<StateCall>,
    pub(super) set_fmu_state: Option<SetState>,
    pub(super) free_fmu_state: Option<StateCall>,
    /// slender's extension `slenderGetStepDerivative` (FMI 2.0's signature).
    pub(super) step_derivative: Option<super::library::StepDerivative>,
}

impl Api3 {
    /// Binds the entry points; the state calls when `states` (as the model
    /// description declares them), the step derivative where exported.
    pub(super) fn bind(library: &libloading::Library, states: bool) -> Result<Api3, String> {
        Ok(Api3 {
            instantiate: symbol(library, "fmi3InstantiateCoSimulation")?,
            free_instance: symbol(library, "fmi3FreeInstance")?,
            enter_initialization_mode: symbol(library, "fmi3EnterInitializationMode")?,
            exit_initialization_mode: symbol(library, "fmi3ExitInitializationMode")?,
            terminate: symbol(library, "fmi3Terminate")?,
            reset: symbol(library, "fmi3Reset")?,
            get_float64: symbol(library, "fmi3GetFloat64")?,
            get_int32: symbol(library, "fmi3GetInt32")?,
            set_float64: symbol(library, "fmi3SetFloat64")?,
            set_int32: symbol(library, "fmi3SetInt32")?,
            set_boolean: symbol(library, "fmi3SetBoolean")?,
            set_string: symbol(library, "fmi3SetString")?,
            do_step: symbol(library, "fmi3DoStep")?,
            get_fmu_state: optional(library, states, "fmi3GetFMUState")?,
            set_fmu_state: optional(library, states, "fmi3SetFMUState")?,
            free_fmu_state: optional(library, states, "fmi3FreeFMUState")?,
            step_derivative: super::library::step_derivative(library),
        })
    }

    /// `fmi3InstantiateCoSimulation` (no event mode, no early return, no
    /// intermediate update) with a logger into `log`, which must outlive the
    /// instance; the resources folder as FMI 3.0 passes it (a path ending in
    /// a separator).
    pub(super) fn instantiate(
        &self,
        model: &ModelDescription,
        folder: &Path,
        logging: bool,
        label: &str,
    ) -> Result<(Instance, Box<LogBook>), LoadError> {
        let log = Box::new(LogBook::default());
        let c = |s: &str| {
            CString::new(s).map_err(|_| LoadError::Nul {
                fmu: label.to_owned(),
                text: s.to_owned(),
            })
        };
        let resources = format!("{}/", folder.join("resources").display());
        let (name, token, resources) = (c(&model.model_name)?, c(&model.guid)?, c(&resources)?);
        // SAFETY: FMI 3.0 fmi3InstantiateCoSimulation with valid C strings and
        // a logger whose environment (the log) outlives the instance.
        let instance = unsafe {
            (self.instantiate)(
                name.as_ptr(),
                token.as_ptr(),
                resources.as_ptr(),
                false,
                logging,
                false,
                false,
                std::ptr::null(),
                0,
                &*log as *const LogBook as *mut c_void,
                Some(log_message),
                std::ptr::null_mut(),
            )
        };
        if instance.is_null() {
            return Err(LoadError::Instantiate {
                fmu: label.to_owned(),
                call: "fmi3InstantiateCoSimulation",
                log: log_tail(&log),
            });
        }
        Ok((instance, log))
    }
}

/// FMI 3.0's `logMessage`: the message into the unit's log.
unsafe extern "C" fn log_message(
    environment: *mut c_void,
    status: Status,
    category: *const c_char,
    message: *const c_char,
) {
    // SAFETY: the environment is the unit's LogBook, which outlives the
    // instance (dropped after fmi3FreeInstance).
    unsafe { LogBook::push_to(environment, std::ptr::null(), status, category, message) }
}
