//! slender-fmu: the FMI 2.0 co-simulation entry points of an exported slender unit.
//!
//! One shared library serves every exported unit: `fmi2Instantiate` reads the
//! unit's scene section from `resources/slender-unit.toml` (written by
//! `slender fmu export`), and the variables follow
//! [`slender_fmi::export::Layout`], the same code that wrote the model
//! description. Every entry point catches panics and reports errors through the
//! logger with the instance name and the reason, returning `fmi2Error`.
//!
//! Input timing: a value set before `fmi2DoStep` is held over the step (zero-order);
//! when `fmi2SetRealInputDerivatives` gave a first derivative for the step, the
//! input ramps from the unit's last value to `u + h du/dt`. Derivatives apply to
//! the next step only.

#![allow(non_snake_case, clippy::missing_safety_doc)]

mod fmi3;
mod instance;
mod states;
mod uri;

use instance::{Instance, guarded};
use slender_fmi::ffi::*;
use std::ffi::{CStr, c_char};

/// `fmi2GetTypesPlatform`.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char {
    c"default".as_ptr()
}

/// `fmi2GetVersion`.
#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetVersion() -> *const c_char {
    c"2.0".as_ptr()
}

/// `fmi2Instantiate`: reads the unit's configuration from the resources and
/// checks the GUID; null on failure (reported through the logger).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2Instantiate(
    instance_name: fmi2String,
    fmu_type: fmi2Type,
    guid: fmi2String,
    resource_location: fmi2String,
    functions: *const fmi2CallbackFunctions,
    _visible: fmi2Boolean,
    logging_on: fmi2Boolean,
) -> fmi2Component {
    let text = |p: fmi2String| {
        if p.is_null() {
            String::new()
        } else {
            // SAFETY: FMI passes NUL-terminated strings.
            unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned()
        }
    };
    if functions.is_null() {
        return std::ptr::null_mut();
    }
    // SAFETY: checked non-null; the struct is the FMI 2.0 callback table.
    let callbacks = unsafe { *functions };
    let name = text(instance_name);
    let result = std::panic::catch_unwind(|| {
        if fmu_type != FMI2_CO_SIMULATION {
            return Err(
                "this FMU offers co-simulation only (fmuType must be fmi2CoSimulation)".to_owned(),
            );
        }
        Instance::new(
            name.clone(),
            &text(guid),
            &uri::path_of_uri(&text(resource_location))?,
            callbacks,
            logging_on != FMI2_FALSE,
        )
    });
    match result {
        Ok(Ok(instance)) => Box::into_raw(Box::new(instance)).cast(),
        Ok(Err(message)) => {
            instance::log_with(
                &callbacks,
                &name,
                FMI2_ERROR,
                &format!("fmi2Instantiate: {message}"),
            );
            std::ptr::null_mut()
        }
        Err(_) => {
            instance::log_with(
                &callbacks,
                &name,
                FMI2_ERROR,
                "fmi2Instantiate: internal error (panic caught)",
            );
            std::ptr::null_mut()
        }
    }
}

/// `fmi2FreeInstance`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2FreeInstance(c: fmi2Component) {
    if !c.is_null() {
        let _ = std::panic::catch_unwind(|| {
            // SAFETY: `c` came from fmi2Instantiate and is freed once.
            drop(unsafe { Box::from_raw(c.cast::<Instance>()) });
        });
    }
}

/// `fmi2SetDebugLogging`: turns debug messages on or off (categories ignored).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetDebugLogging(
    c: fmi2Component,
    logging_on: fmi2Boolean,
    _n: usize,
    _categories: *const fmi2String,
) -> fmi2Status {
    guarded(c, "fmi2SetDebugLogging", |i| {
        i.logging = logging_on != FMI2_FALSE;
        Ok(FMI2_OK)
    })
}

/// `fmi2SetupExperiment`: the start time (tolerance and stop time are not used).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetupExperiment(
    c: fmi2Component,
    _tolerance_defined: fmi2Boolean,
    _tolerance: fmi2Real,
    start_time: fmi2Real,
    _stop_time_defined: fmi2Boolean,
    _stop_time: fmi2Real,
) -> fmi2Status {
    guarded(c, "fmi2SetupExperiment", |i| i.setup(start_time))
}

/// `fmi2EnterInitializationMode`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2EnterInitializationMode(c: fmi2Component) -> fmi2Status {
    guarded(
        c,
        "fmi2EnterInitializationMode",
        Instance::enter_initialization,
    )
}

/// `fmi2ExitInitializationMode`: the unit finds its initial state.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2ExitInitializationMode(c: fmi2Component) -> fmi2Status {
    guarded(
        c,
        "fmi2ExitInitializationMode",
        Instance::exit_initialization,
    )
}

/// `fmi2Terminate`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2Terminate(c: fmi2Component) -> fmi2Status {
    guarded(c, "fmi2Terminate", Instance::terminate)
}

/// `fmi2Reset`: back to the instantiated state with the exported parameters.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2Reset(c: fmi2Component) -> fmi2Status {
    guarded(c, "fmi2Reset", Instance::reset)
}

/// Reads `n` value references.
pub(crate) unsafe fn refs<'a>(
    vr: *const fmi2ValueReference,
    n: usize,
) -> Result<&'a [u32], String> {
    if n == 0 {
        Ok(&[])
    } else if vr.is_null() {
        Err("null value-reference array".into())
    } else {
        // SAFETY: the caller passes `n` value references.
        Ok(unsafe { std::slice::from_raw_parts(vr, n) })
    }
}

pub(crate) unsafe fn values<'a, T>(p: *const T, n: usize) -> Result<&'a [T], String> {
    if n == 0 {
        Ok(&[])
    } else if p.is_null() {
        Err("null value array".into())
    } else {
        // SAFETY: the caller passes `n` values.
        Ok(unsafe { std::slice::from_raw_parts(p, n) })
    }
}

/// The NUL-terminated strings of an FMI string array (FMI 2.0 and 3.0
/// alike), copied; a null entry is refused.
///
/// # Safety
/// Each non-null entry points to a NUL-terminated string.
pub(crate) unsafe fn texts(value: &[*const c_char]) -> Result<Vec<String>, String> {
    let mut texts = Vec::with_capacity(value.len());
    for p in value {
        if p.is_null() {
            return Err("null string".into());
        }
        // SAFETY: FMI passes NUL-terminated strings.
        texts.push(unsafe { CStr::from_ptr(*p) }.to_string_lossy().into_owned());
    }
    Ok(texts)
}

pub(crate) unsafe fn values_mut<'a, T>(p: *mut T, n: usize) -> Result<&'a mut [T], String> {
    if n == 0 {
        Ok(&mut [])
    } else if p.is_null() {
        Err("null value array".into())
    } else {
        // SAFETY: the caller passes room for `n` values.
        Ok(unsafe { std::slice::from_raw_parts_mut(p, n) })
    }
}

/// `fmi2GetReal`: inputs, outputs and Real parameters.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetReal(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    value: *mut fmi2Real,
) -> fmi2Status {
    guarded(c, "fmi2GetReal", |i| {
        // SAFETY: FMI array arguments of length n.
        let (vr, value) = unsafe { (refs(vr, n)?, values_mut(value, n)?) };
        i.get_real(vr, value)
    })
}

/// `fmi2SetReal`: inputs (any time) and Real parameters (before initialisation ends).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetReal(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    value: *const fmi2Real,
) -> fmi2Status {
    guarded(c, "fmi2SetReal", |i| {
        // SAFETY: FMI array arguments of length n.
        let (vr, value) = unsafe { (refs(vr, n)?, values(value, n)?) };
        i.set_real(vr, value)
    })
}

/// `fmi2GetInteger`: Integer parameters.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetInteger(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    value: *mut fmi2Integer,
) -> fmi2Status {
    guarded(c, "fmi2GetInteger", |i| {
        // SAFETY: FMI array arguments of length n.
        let (vr, value) = unsafe { (refs(vr, n)?, values_mut(value, n)?) };
        i.get_integer(vr, value, false)
    })
}

/// `fmi2SetInteger`: Integer parameters.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetInteger(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    value: *const fmi2Integer,
) -> fmi2Status {
    guarded(c, "fmi2SetInteger", |i| {
        // SAFETY: FMI array arguments of length n.
        let (vr, value) = unsafe { (refs(vr, n)?, values(value, n)?) };
        i.set_integer(vr, value, false)
    })
}

/// `fmi2GetBoolean`: Boolean parameters (including `effects.<name>`).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetBoolean(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    value: *mut fmi2Boolean,
) -> fmi2Status {
    guarded(c, "fmi2GetBoolean", |i| {
        // SAFETY: FMI array arguments of length n.
        let (vr, value) = unsafe { (refs(vr, n)?, values_mut(value, n)?) };
        i.get_integer(vr, value, true)
    })
}

/// `fmi2SetBoolean`: Boolean parameters (including `effects.<name>`).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetBoolean(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    value: *const fmi2Boolean,
) -> fmi2Status {
    guarded(c, "fmi2SetBoolean", |i| {
        // SAFETY: FMI array arguments of length n.
        let (vr, value) = unsafe { (refs(vr, n)?, values(value, n)?) };
        i.set_integer(vr, value, true)
    })
}

/// `fmi2GetString`: String parameters (pointers valid until the next call).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetString(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    value: *mut fmi2String,
) -> fmi2Status {
    guarded(c, "fmi2GetString", |i| {
        // SAFETY: FMI array arguments of length n.
        let (vr, value) = unsafe { (refs(vr, n)?, values_mut(value, n)?) };
        i.get_string(vr, value)
    })
}

/// `fmi2SetString`: String parameters.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetString(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    value: *const fmi2String,
) -> fmi2Status {
    guarded(c, "fmi2SetString", |i| {
        // SAFETY: FMI array arguments of length n.
        let (vr, value) = unsafe { (refs(vr, n)?, values(value, n)?) };
        // SAFETY: FMI passes NUL-terminated strings.
        let texts = unsafe { texts(value)? };
        i.set_string(vr, &texts)
    })
}

/// `fmi2GetFMUstate`: a copy of the unit's state (new, or written into `*state`).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetFMUstate(c: fmi2Component, state: *mut fmi2FMUstate) -> fmi2Status {
    unsafe { states::get(c, "fmi2GetFMUstate", state) }
}

/// `fmi2SetFMUstate`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetFMUstate(c: fmi2Component, state: fmi2FMUstate) -> fmi2Status {
    guarded(c, "fmi2SetFMUstate", |i| i.set_state(state))
}

/// `fmi2FreeFMUstate`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2FreeFMUstate(
    c: fmi2Component,
    state: *mut fmi2FMUstate,
) -> fmi2Status {
    unsafe { states::free(c, "fmi2FreeFMUstate", state) }
}

/// `fmi2SerializedFMUstateSize`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SerializedFMUstateSize(
    c: fmi2Component,
    state: fmi2FMUstate,
    size: *mut usize,
) -> fmi2Status {
    unsafe { states::size(c, "fmi2SerializedFMUstateSize", state, size) }
}

/// `fmi2SerializeFMUstate`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SerializeFMUstate(
    c: fmi2Component,
    state: fmi2FMUstate,
    bytes: *mut fmi2Byte,
    size: usize,
) -> fmi2Status {
    unsafe { states::serialize(c, "fmi2SerializeFMUstate", state, (bytes.cast(), size)) }
}

/// `fmi2DeSerializeFMUstate`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2DeSerializeFMUstate(
    c: fmi2Component,
    bytes: *const fmi2Byte,
    size: usize,
    state: *mut fmi2FMUstate,
) -> fmi2Status {
    unsafe { states::deserialize(c, "fmi2DeSerializeFMUstate", (bytes.cast(), size), state) }
}

/// `fmi2GetDirectionalDerivative`: the outputs' partial derivatives with
/// respect to the inputs at the current instant, as the standard defines
/// them (zero for a unit without feedthrough; `instance/derivative.rs`).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetDirectionalDerivative(
    c: fmi2Component,
    unknown: *const fmi2ValueReference,
    n_unknown: usize,
    known: *const fmi2ValueReference,
    n_known: usize,
    _dv_known: *const fmi2Real,
    dv_unknown: *mut fmi2Real,
) -> fmi2Status {
    guarded(c, "fmi2GetDirectionalDerivative", |i| {
        // SAFETY: FMI array arguments of the lengths given.
        let (unknown, known, dv_unknown) = unsafe {
            (
                refs(unknown, n_unknown)?,
                refs(known, n_known)?,
                values_mut(dv_unknown, n_unknown)?,
            )
        };
        i.directional_derivative((Some(unknown), known), dv_unknown)
    })
}

/// `slenderGivesStepDerivative` (a slender extension): fmi2True when the
/// instance's unit gives its step Jacobian through `slenderGetStepDerivative`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn slenderGivesStepDerivative(c: fmi2Component) -> fmi2Boolean {
    let mut gives = false;
    let status = guarded(c, "slenderGivesStepDerivative", |i| {
        gives = i.gives_step_derivative();
        Ok(FMI2_OK)
    });
    fmi2Boolean::from(status == FMI2_OK && gives)
}

/// `slenderGetStepDerivative` (a slender extension, FMI 2.0's
/// `GetDirectionalDerivative` signature, for FMI 2.0 and 3.0 instances
/// alike): the unit's step Jacobian times the seed, the derivative of the
/// outputs after the last step with respect to the inputs it ended at.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn slenderGetStepDerivative(
    c: fmi2Component,
    unknown: *const fmi2ValueReference,
    n_unknown: usize,
    known: *const fmi2ValueReference,
    n_known: usize,
    dv_known: *const fmi2Real,
    dv_unknown: *mut fmi2Real,
) -> fmi2Status {
    guarded(c, "slenderGetStepDerivative", |i| {
        // SAFETY: FMI array arguments of the lengths given.
        let (unknown, known, dv_known, dv_unknown) = unsafe {
            (
                refs(unknown, n_unknown)?,
                refs(known, n_known)?,
                values(dv_known, n_known)?,
                values_mut(dv_unknown, n_unknown)?,
            )
        };
        i.step_derivative((unknown, known), dv_known, dv_unknown)
    })
}

/// `fmi2SetRealInputDerivatives`: first derivatives of inputs for the next step.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetRealInputDerivatives(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    order: *const fmi2Integer,
    value: *const fmi2Real,
) -> fmi2Status {
    guarded(c, "fmi2SetRealInputDerivatives", |i| {
        // SAFETY: FMI array arguments of length n.
        let (vr, order, value) = unsafe { (refs(vr, n)?, values(order, n)?, values(value, n)?) };
        i.set_input_derivatives(vr, order, value)
    })
}

/// `fmi2GetRealOutputDerivatives`: not provided (`maxOutputDerivativeOrder` = 0).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetRealOutputDerivatives(
    c: fmi2Component,
    _vr: *const fmi2ValueReference,
    _n: usize,
    _order: *const fmi2Integer,
    _value: *mut fmi2Real,
) -> fmi2Status {
    guarded(c, "fmi2GetRealOutputDerivatives", |_| {
        Err("output derivatives are not provided (maxOutputDerivativeOrder = 0)".into())
    })
}

/// `fmi2DoStep`: advances the unit from `t` to `t + h`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2DoStep(
    c: fmi2Component,
    t: fmi2Real,
    h: fmi2Real,
    _no_set_fmu_state_prior: fmi2Boolean,
) -> fmi2Status {
    guarded(c, "fmi2DoStep", |i| i.do_step(t, h))
}

/// `fmi2CancelStep`: steps never run asynchronously, so there is nothing to cancel.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2CancelStep(c: fmi2Component) -> fmi2Status {
    guarded(c, "fmi2CancelStep", |_| {
        Err("steps are synchronous; there is nothing to cancel".into())
    })
}

/// `fmi2GetStatus`: `fmi2DoStepStatus` is always fmi2OK (steps are synchronous).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetStatus(
    c: fmi2Component,
    kind: fmi2StatusKind,
    value: *mut fmi2Status,
) -> fmi2Status {
    guarded(c, "fmi2GetStatus", |_| {
        if kind != 0 || value.is_null() {
            return Ok(FMI2_DISCARD);
        }
        // SAFETY: checked non-null.
        unsafe { *value = FMI2_OK };
        Ok(FMI2_OK)
    })
}

/// `fmi2GetRealStatus`: `fmi2LastSuccessfulTime` (s).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetRealStatus(
    c: fmi2Component,
    kind: fmi2StatusKind,
    value: *mut fmi2Real,
) -> fmi2Status {
    guarded(c, "fmi2GetRealStatus", |i| {
        if kind != 2 || value.is_null() {
            return Ok(FMI2_DISCARD);
        }
        // SAFETY: checked non-null.
        unsafe { *value = i.time_secs() };
        Ok(FMI2_OK)
    })
}

/// `fmi2GetIntegerStatus`: no integer status exists.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetIntegerStatus(
    c: fmi2Component,
    _kind: fmi2StatusKind,
    _value: *mut fmi2Integer,
) -> fmi2Status {
    guarded(c, "fmi2GetIntegerStatus", |_| Ok(FMI2_DISCARD))
}

/// `fmi2GetBooleanStatus`: `fmi2Terminated` is always false.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetBooleanStatus(
    c: fmi2Component,
    kind: fmi2StatusKind,
    value: *mut fmi2Boolean,
) -> fmi2Status {
    guarded(c, "fmi2GetBooleanStatus", |_| {
        if kind != 3 || value.is_null() {
            return Ok(FMI2_DISCARD);
        }
        // SAFETY: checked non-null.
        unsafe { *value = FMI2_FALSE };
        Ok(FMI2_OK)
    })
}

/// `fmi2GetStringStatus`: no string status exists.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetStringStatus(
    c: fmi2Component,
    _kind: fmi2StatusKind,
    _value: *mut fmi2String,
) -> fmi2Status {
    guarded(c, "fmi2GetStringStatus", |_| Ok(FMI2_DISCARD))
}

#[cfg(test)]
mod tests;
