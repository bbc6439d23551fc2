//! slender-units: the unit contract and the native units of slender.
//!
//! A unit is one substructure (or signal block) with an FMI-like stepping contract,
//! see [`unit::Unit`]. The master (crate `slender-master`) couples units; this crate
//! holds the physics and the numerics they share.

pub mod algebraic_loop;
pub mod beam;
pub mod cable;
pub mod contact;
pub mod hold;
pub mod integrators;
pub mod numerics;
pub mod oscillator;
pub mod port;
pub mod signal;
pub mod span;
pub mod state;
pub mod time;
pub mod unit;

pub use hold::HeldInputs;
pub use port::{Causality, Hold, Port, PortKind};
pub use state::StateSlot;
pub use time::Time;
pub use unit::{Capabilities, ModalAnalysis, Mode, StepReport, Unit, UnitDescription, UnitError};
