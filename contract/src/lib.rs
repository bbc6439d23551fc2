//! The unit contract: what every substructure model offers the master, and the
//! one place that drives a unit through it ([`Driver`]).
//!
//! - [`unit`]: the [`Unit`] trait (call order in its docs), descriptions, errors;
//! - [`port`], [`time`], [`measure`]: ports and their kinds, integer-nanosecond
//!   time, units of measure;
//! - [`hold`]: held inputs (ramp / zero-order) and the [`Inputs`] view a unit reads;
//! - [`state`]: [`StateSlot`] for rollback and FMU state, [`state_struct!`](crate::state_struct)
//!   for allocation-free `clone_from`;
//! - [`driver`]: [`Driver`], which owns a unit's held inputs and checks them.
pub mod driver;
pub mod hold;
pub mod measure;
pub mod names;
pub mod port;
pub mod state;
pub mod time;
pub mod unit;

pub use driver::{Driver, DriverSlot};
pub use hold::{HeldInputs, Inputs};
pub use port::{Causality, Hold, Port, PortKind};
pub use state::{NestedSlot, StateSlot, StateVector};
pub use time::Time;
pub use unit::{
    Capabilities, Field, FieldSupport, HoldSupport, ModalAnalysis, Mode, StepReport, Unit,
    UnitDescription, UnitError, require_finite, require_finite_state, require_in_range,
    require_non_negative, require_positive, require_step_jacobian_ready,
};
