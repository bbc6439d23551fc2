//! One interface over an FMU's FMI 2.0 or FMI 3.0 entry points: what the
//! importing unit calls, with each call's name in the FMU's version for
//! messages. Every method is a thin `unsafe` call on a live instance with
//! arrays of the lengths given.

use super::api3::Api3;
use super::library::{Api, FMI2_TERMINATED, StepDerivative};
use crate::ffi::*;
use std::ffi::{c_char, c_void};

/// The bound entry points of either version.
pub(super) enum Calls {
    Two(Api),
    Three(Api3),
}

/// The FMI status of "this version has no such call".
const ABSENT: fmi2Status = FMI2_ERROR;

impl Calls {
    /// The call's name in this FMU's version (`fmi2...` or `fmi3...`).
    pub(super) fn name(&self, two: &'static str, three: &'static str) -> &'static str {
        match self {
            Calls::Two(_) => two,
            Calls::Three(_) => three,
        }
    }

    pub(super) fn has_state(&self) -> bool {
        match self {
            Calls::Two(a) => a.get_fmu_state.is_some(),
            Calls::Three(a) => a.get_fmu_state.is_some(),
        }
    }

    /// slender's step-derivative extension, where the binary exports it.
    fn extension(&self) -> Option<StepDerivative> {
        match self {
            Calls::Two(a) => a.step_derivative,
            Calls::Three(a) => a.step_derivative,
        }
    }

    /// Whether instance `c` gives its step Jacobian (slender's extension,
    /// asked of the instance: a slender FMU of a unit without one says no).
    pub(super) unsafe fn gives_step_derivative(&self, c: *mut c_void) -> bool {
        // SAFETY: a call on a live instance.
        self.extension()
            .is_some_and(|d| unsafe { (d.gives)(c) } == FMI2_TRUE)
    }

    /// Real (Float64) values of `refs`, arrays flattened, into `values`.
    pub(super) unsafe fn get_reals(
        &self,
        c: *mut c_void,
        refs: &[u32],
        values: &mut [f64],
    ) -> fmi2Status {
        // SAFETY (all methods): the caller's contract, see the module docs.
        unsafe {
            match self {
                Calls::Two(a) => (a.get_real)(c, refs.as_ptr(), refs.len(), values.as_mut_ptr()),
                Calls::Three(a) => (a.get_float64)(
                    c,
                    refs.as_ptr(),
                    refs.len(),
                    values.as_mut_ptr(),
                    values.len(),
                ),
            }
        }
    }

    /// Integer (Int32) values of the scalar `refs` into `values`.
    pub(super) unsafe fn get_integers(
        &self,
        c: *mut c_void,
        refs: &[u32],
        values: &mut [i32],
    ) -> fmi2Status {
        unsafe {
            match self {
                Calls::Two(a) => (a.get_integer)(c, refs.as_ptr(), refs.len(), values.as_mut_ptr()),
                Calls::Three(a) => (a.get_int32)(
                    c,
                    refs.as_ptr(),
                    refs.len(),
                    values.as_mut_ptr(),
                    values.len(),
                ),
            }
        }
    }

    pub(super) unsafe fn set_reals(
        &self,
        c: *mut c_void,
        refs: &[u32],
        values: &[f64],
    ) -> fmi2Status {
        unsafe {
            match self {
                Calls::Two(a) => (a.set_real)(c, refs.as_ptr(), refs.len(), values.as_ptr()),
                Calls::Three(a) => {
                    (a.set_float64)(c, refs.as_ptr(), refs.len(), values.as_ptr(), values.len())
                }
            }
        }
    }

    /// First derivatives of the inputs `refs` (FMI 2.0's interpolation; FMI
    /// 3.0 co-simulation without event mode has none).
    pub(super) unsafe fn set_input_slopes(
        &self,
        c: *mut c_void,
        refs: &[u32],
        orders: &[fmi2Integer],
        slopes: &[f64],
    ) -> fmi2Status {
        match self {
            Calls::Two(a) => unsafe {
                (a.set_real_input_derivatives)(
                    c,
                    refs.as_ptr(),
                    refs.len(),
                    orders.as_ptr(),
                    slopes.as_ptr(),
                )
            },
            Calls::Three(_) => ABSENT,
        }
    }

    pub(super) unsafe fn set_integer(&self, c: *mut c_void, vr: u32, value: i32) -> fmi2Status {
        unsafe {
            match self {
                Calls::Two(a) => (a.set_integer)(c, &vr, 1, &value),
                Calls::Three(a) => (a.set_int32)(c, &vr, 1, &value, 1),
            }
        }
    }

    pub(super) unsafe fn set_boolean(&self, c: *mut c_void, vr: u32, value: bool) -> fmi2Status {
        unsafe {
            match self {
                Calls::Two(a) => (a.set_boolean)(c, &vr, 1, &fmi2Boolean::from(value)),
                Calls::Three(a) => (a.set_boolean)(c, &vr, 1, &value, 1),
            }
        }
    }

    pub(super) unsafe fn set_string(
        &self,
        c: *mut c_void,
        vr: u32,
        value: *const c_char,
    ) -> fmi2Status {
        unsafe {
            match self {
                Calls::Two(a) => (a.set_string)(c, &vr, 1, &value),
                Calls::Three(a) => (a.set_string)(c, &vr, 1, &value, 1),
            }
        }
    }

    /// FMI 2.0's `fmi2SetupExperiment` at `t0` (FMI 3.0 passes it on entering
    /// initialisation).
    pub(super) unsafe fn setup(&self, c: *mut c_void, t0: f64) -> fmi2Status {
        match self {
            Calls::Two(a) => unsafe {
                (a.setup_experiment)(c, FMI2_FALSE, 0.0, t0, FMI2_FALSE, 0.0)
            },
            Calls::Three(_) => FMI2_OK,
        }
    }

    pub(super) unsafe fn enter_initialization(&self, c: *mut c_void, t0: f64) -> fmi2Status {
        unsafe {
            match self {
                Calls::Two(a) => (a.enter_initialization_mode)(c),
                Calls::Three(a) => (a.enter_initialization_mode)(c, false, 0.0, t0, false, 0.0),
            }
        }
    }

    pub(super) unsafe fn exit_initialization(&self, c: *mut c_void) -> fmi2Status {
        unsafe {
            match self {
                Calls::Two(a) => (a.exit_initialization_mode)(c),
                Calls::Three(a) => (a.exit_initialization_mode)(c),
            }
        }
    }

    pub(super) unsafe fn reset(&self, c: *mut c_void) -> fmi2Status {
        unsafe {
            match self {
                Calls::Two(a) => (a.reset)(c),
                Calls::Three(a) => (a.reset)(c),
            }
        }
    }

    pub(super) unsafe fn terminate(&self, c: *mut c_void) -> fmi2Status {
        unsafe {
            match self {
                Calls::Two(a) => (a.terminate)(c),
                Calls::Three(a) => (a.terminate)(c),
            }
        }
    }

    pub(super) unsafe fn free_instance(&self, c: *mut c_void) {
        unsafe {
            match self {
                Calls::Two(a) => (a.free_instance)(c),
                Calls::Three(a) => (a.free_instance)(c),
            }
        }
    }

    /// One step; the status and whether the FMU asked to end the simulation
    /// (FMI 3.0's `terminateSimulation`; FMI 2.0's `fmi2Discard` with
    /// `fmi2GetBooleanStatus(fmi2Terminated)` true).
    pub(super) unsafe fn do_step(
        &self,
        c: *mut c_void,
        t: f64,
        h: f64,
        no_prior: bool,
    ) -> (fmi2Status, bool) {
        match self {
            Calls::Two(a) => {
                let no_prior = if no_prior { FMI2_TRUE } else { FMI2_FALSE };
                let status = unsafe { (a.do_step)(c, t, h, no_prior) };
                let mut terminated = FMI2_FALSE;
                let asks_to_end = status == FMI2_DISCARD
                    && a.get_boolean_status.is_some_and(|f| {
                        let asked = unsafe { f(c, FMI2_TERMINATED, &mut terminated) };
                        asked == FMI2_OK && terminated == FMI2_TRUE
                    });
                (if asks_to_end { FMI2_OK } else { status }, asks_to_end)
            }
            Calls::Three(a) => {
                let (mut event, mut terminate, mut early, mut last) = (false, false, false, t);
                let status = unsafe {
                    (a.do_step)(
                        c,
                        t,
                        h,
                        no_prior,
                        &mut event,
                        &mut terminate,
                        &mut early,
                        &mut last,
                    )
                };
                (status, terminate)
            }
        }
    }

    /// Saves the FMU's state into `handle` (a new one when null).
    pub(super) unsafe fn get_state(&self, c: *mut c_void, handle: &mut fmi2FMUstate) -> fmi2Status {
        unsafe {
            match self {
                Calls::Two(a) => a.get_fmu_state.map_or(ABSENT, |f| f(c, handle)),
                Calls::Three(a) => a.get_fmu_state.map_or(ABSENT, |f| f(c, handle)),
            }
        }
    }

    pub(super) unsafe fn set_state(&self, c: *mut c_void, handle: fmi2FMUstate) -> fmi2Status {
        unsafe {
            match self {
                Calls::Two(a) => a.set_fmu_state.map_or(ABSENT, |f| f(c, handle)),
                Calls::Three(a) => a.set_fmu_state.map_or(ABSENT, |f| f(c, handle)),
            }
        }
    }

    pub(super) unsafe fn free_state(
        &self,
        c: *mut c_void,
        handle: &mut fmi2FMUstate,
    ) -> fmi2Status {
        unsafe {
            match self {
                Calls::Two(a) => a.free_fmu_state.map_or(ABSENT, |f| f(c, handle)),
                Calls::Three(a) => a.free_fmu_state.map_or(ABSENT, |f| f(c, handle)),
            }
        }
    }

    /// The step derivative (slender's extension) of the outputs `unknowns`
    /// (flattened into `sensitivity`) along `seed` over the inputs `knowns`.
    pub(super) unsafe fn step_derivative(
        &self,
        c: *mut c_void,
        (unknowns, knowns): (&[u32], &[u32]),
        seed: &[f64],
        sensitivity: &mut [f64],
    ) -> fmi2Status {
        // SAFETY: a call on a live instance; the arrays have the lengths passed.
        self.extension().map_or(ABSENT, |d| unsafe {
            (d.get)(
                c,
                unknowns.as_ptr(),
                unknowns.len(),
                knowns.as_ptr(),
                knowns.len(),
                seed.as_ptr(),
                sensitivity.as_mut_ptr(),
            )
        })
    }
}
