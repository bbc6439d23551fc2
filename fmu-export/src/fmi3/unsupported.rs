//! The FMI 3.0 functions this FMU does not offer (model exchange, scheduled
//! execution, event mode, clocks, reconfiguration, other number types):
//! every FMU exports the whole interface, so these are present and answer
//! `fmi3Error` with a message naming the function. Only the first argument
//! (the instance) is read; the C calling convention leaves the rest unused.

use super::Instance3;
use crate::instance::guarded;

macro_rules! unsupported {
    ($($name:ident),* $(,)?) => {
        $(
            #[doc = concat!("`", stringify!($name), "`: not offered (fmi3Error).")]
            #[unsafe(no_mangle)]
            // Reached by name through the library's symbol table, not as a path.
            #[allow(unreachable_pub)]
            pub unsafe extern "C" fn $name(c: Instance3) -> std::ffi::c_int {
                guarded(c, stringify!($name), |_| {
                    Err("not offered: this FMU is event-free co-simulation with Float64 ports, Int32, Boolean and String parameters and UInt64 array sizes".into())
                })
            }
        )*
    };
}

unsupported!(
    fmi3ActivateModelPartition,
    fmi3CompletedIntegratorStep,
    fmi3EnterContinuousTimeMode,
    fmi3EnterEventMode,
    fmi3EvaluateDiscreteStates,
    fmi3GetAdjointDerivative,
    fmi3GetBinary,
    fmi3GetClock,
    fmi3GetContinuousStateDerivatives,
    fmi3GetContinuousStates,
    fmi3GetEventIndicators,
    fmi3GetFloat32,
    fmi3GetInt16,
    fmi3GetInt64,
    fmi3GetInt8,
    fmi3GetIntervalDecimal,
    fmi3GetIntervalFraction,
    fmi3GetNominalsOfContinuousStates,
    fmi3GetNumberOfContinuousStates,
    fmi3GetNumberOfEventIndicators,
    fmi3GetNumberOfVariableDependencies,
    fmi3GetOutputDerivatives,
    fmi3GetShiftDecimal,
    fmi3GetShiftFraction,
    fmi3GetUInt16,
    fmi3GetUInt32,
    fmi3GetUInt8,
    fmi3GetVariableDependencies,
    fmi3SetBinary,
    fmi3SetClock,
    fmi3SetContinuousStates,
    fmi3SetFloat32,
    fmi3SetInt16,
    fmi3SetInt64,
    fmi3SetInt8,
    fmi3SetIntervalDecimal,
    fmi3SetIntervalFraction,
    fmi3SetShiftDecimal,
    fmi3SetShiftFraction,
    fmi3SetTime,
    fmi3SetUInt16,
    fmi3SetUInt32,
    fmi3SetUInt8,
    fmi3UpdateDiscreteStates,
);

/// `fmi3InstantiateScheduledExecution`: not offered (null).
#[unsafe(no_mangle)]
pub(super) extern "C" fn fmi3InstantiateScheduledExecution() -> Instance3 {
    std::ptr::null_mut()
}
