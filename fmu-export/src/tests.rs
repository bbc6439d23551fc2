//! The FFI helpers shared by the FMI 2.0 and 3.0 entry points.

use super::texts;
use std::ffi::{CString, c_char};

#[test]
fn an_fmi_string_array_is_copied_and_a_null_entry_refused() {
    let (a, b) = (CString::new("riser").unwrap(), CString::new("").unwrap());
    let array: [*const c_char; 2] = [a.as_ptr(), b.as_ptr()];
    // SAFETY: both entries are NUL-terminated strings that outlive the call.
    let copied = unsafe { texts(&array) }.unwrap();
    assert_eq!(copied, ["riser", ""]);
    let with_null: [*const c_char; 2] = [a.as_ptr(), std::ptr::null()];
    // SAFETY: the non-null entry is a NUL-terminated string.
    let refused = unsafe { texts(&with_null) }.unwrap_err();
    assert_eq!(refused, "null string");
}
