//! The C types of the FMI 2.0 co-simulation API, shared by the importer and the
//! exported FMU's entry points.

#![allow(non_camel_case_types)]

use std::ffi::{c_char, c_int, c_void};

/// An FMU instance.
pub type fmi2Component = *mut c_void;
/// The master's pointer handed back in callbacks.
pub type fmi2ComponentEnvironment = *mut c_void;
/// A saved FMU state.
pub type fmi2FMUstate = *mut c_void;
/// A variable's value reference.
pub type fmi2ValueReference = u32;
/// A real value.
pub type fmi2Real = f64;
/// An integer value.
pub type fmi2Integer = c_int;
/// A Boolean value (`FMI2_TRUE` or `FMI2_FALSE`).
pub type fmi2Boolean = c_int;
/// A NUL-terminated string.
pub type fmi2String = *const c_char;
/// A byte of a serialised state.
pub type fmi2Byte = c_char;
/// A call's status (`FMI2_OK` ... `FMI2_PENDING`).
pub type fmi2Status = c_int;
/// Model exchange or co-simulation.
pub type fmi2Type = c_int;
/// What `fmi2Get*Status` asks about.
pub type fmi2StatusKind = c_int;

/// The call succeeded.
pub const FMI2_OK: fmi2Status = 0;
/// The call succeeded with a caveat.
pub const FMI2_WARNING: fmi2Status = 1;
/// The call's result is not to be used; the master may retry.
pub const FMI2_DISCARD: fmi2Status = 2;
/// The call failed; the instance may be freed or reset.
pub const FMI2_ERROR: fmi2Status = 3;
/// The instance is unusable.
pub const FMI2_FATAL: fmi2Status = 4;
/// An asynchronous step is running.
pub const FMI2_PENDING: fmi2Status = 5;
/// `fmi2ModelExchange`.
pub const FMI2_MODEL_EXCHANGE: fmi2Type = 0;
/// `fmi2CoSimulation`.
pub const FMI2_CO_SIMULATION: fmi2Type = 1;
/// True.
pub const FMI2_TRUE: fmi2Boolean = 1;
/// False.
pub const FMI2_FALSE: fmi2Boolean = 0;

/// The logger callback (C-variadic: `printf`-style format then arguments).
pub type fmi2CallbackLogger = Option<
    unsafe extern "C" fn(
        fmi2ComponentEnvironment,
        fmi2String,
        fmi2Status,
        fmi2String,
        fmi2String,
        ...
    ),
>;

/// `fmi2CallbackFunctions`.
#[repr(C)]
#[derive(Copy, Clone)]
pub struct fmi2CallbackFunctions {
    /// Where the FMU sends messages.
    pub logger: fmi2CallbackLogger,
    /// `calloc`-like allocator.
    pub allocate_memory: Option<unsafe extern "C" fn(usize, usize) -> *mut c_void>,
    /// Its `free`.
    pub free_memory: Option<unsafe extern "C" fn(*mut c_void)>,
    /// Called when an asynchronous step ends (unused: slender steps synchronously).
    pub step_finished: Option<unsafe extern "C" fn(fmi2ComponentEnvironment, fmi2Status)>,
    /// Passed back to the logger.
    pub component_environment: fmi2ComponentEnvironment,
}

/// Name of an FMI status, for messages.
pub fn status_name(status: fmi2Status) -> &'static str {
    match status {
        FMI2_OK => "fmi2OK",
        FMI2_WARNING => "fmi2Warning",
        FMI2_DISCARD => "fmi2Discard",
        FMI2_ERROR => "fmi2Error",
        FMI2_FATAL => "fmi2Fatal",
        FMI2_PENDING => "fmi2Pending",
        _ => "an unknown status",
    }
}
