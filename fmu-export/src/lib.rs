//! slender-fmu: FMI 2.0 co-simulation export of slender units.
//!
//! Placeholder crate of the workspace layout: the C ABI and the FMU packaging are
//! the subject of issue 6 and are not written yet.
