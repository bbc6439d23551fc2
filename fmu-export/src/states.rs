//! The FMU-state calls both FMI versions share (their C signatures agree):
//! checked pointers, the unit's state through [`Instance`], errors logged with
//! the calling function's name.

use crate::instance::{self, guarded};
use crate::{values, values_mut};
use slender_fmi::ffi::*;

/// `fmi2GetFMUstate` / `fmi3GetFMUState`: a copy of the unit's state.
pub(crate) unsafe fn get(c: fmi2Component, call: &str, state: *mut fmi2FMUstate) -> fmi2Status {
    guarded(c, call, |i| {
        if state.is_null() {
            return Err("null state pointer".into());
        }
        // SAFETY: checked non-null; FMI passes a pointer to a state handle.
        i.get_state(unsafe { &mut *state })
    })
}

/// `fmi2FreeFMUstate` / `fmi3FreeFMUState`.
pub(crate) unsafe fn free(c: fmi2Component, call: &str, state: *mut fmi2FMUstate) -> fmi2Status {
    guarded(c, call, |_| {
        if !state.is_null() {
            // SAFETY: FMI passes a pointer to a handle we made.
            let handle = unsafe { &mut *state };
            instance::free_state(*handle);
            *handle = std::ptr::null_mut();
        }
        Ok(FMI2_OK)
    })
}

/// `fmi2SerializedFMUstateSize` / `fmi3SerializedFMUStateSize`.
pub(crate) unsafe fn size(
    c: fmi2Component,
    call: &str,
    state: fmi2FMUstate,
    size: *mut usize,
) -> fmi2Status {
    guarded(c, call, |i| {
        let bytes = i.serialize(state)?;
        // SAFETY: FMI passes room for one size.
        let out = unsafe { values_mut(size, 1)? };
        out[0] = bytes.len();
        Ok(FMI2_OK)
    })
}

/// `fmi2SerializeFMUstate` / `fmi3SerializeFMUState`: into a buffer of
/// exactly the state's size.
pub(crate) unsafe fn serialize(
    c: fmi2Component,
    call: &str,
    state: fmi2FMUstate,
    (bytes, size): (*mut u8, usize),
) -> fmi2Status {
    guarded(c, call, |i| {
        let data = i.serialize(state)?;
        if data.len() != size {
            return Err(format!(
                "the buffer holds {size} bytes, the state needs {}",
                data.len()
            ));
        }
        // SAFETY: FMI passes room for `size` bytes.
        let out = unsafe { values_mut(bytes, size)? };
        out.copy_from_slice(&data);
        Ok(FMI2_OK)
    })
}

/// `fmi2DeSerializeFMUstate` / `fmi3DeserializeFMUState`.
pub(crate) unsafe fn deserialize(
    c: fmi2Component,
    call: &str,
    (bytes, size): (*const u8, usize),
    state: *mut fmi2FMUstate,
) -> fmi2Status {
    guarded(c, call, |i| {
        // SAFETY: FMI passes `size` bytes and a handle to fill.
        let data = unsafe { values(bytes, size)? };
        if state.is_null() {
            return Err("null state pointer".into());
        }
        // SAFETY: checked non-null.
        i.deserialize(data, unsafe { &mut *state })
    })
}
