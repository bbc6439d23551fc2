//! slender-units: the native units of slender, and the unit contract
//! (crate `slender-contract`) re-exported as [`contract`].
//!
//! A unit is one substructure (or signal block) with an FMI-like stepping contract,
//! see [`contract::Unit`]; [`contract::Driver`] drives one through it. The master
//! (crate `slender-coupling`) couples units; this crate holds the contract, the
//! physics and the numerics they share:
//! - [`contract`]: unit, ports, holds, state, time, the driver;
//! - [`integrators`], [`numerics`]: time integration and linear algebra shared by units;
//! - physics: [`cable`], [`beam`], [`nonlinear`], [`contact`], [`span`], [`signal`],
//!   [`chord`] (a small-deflection section in its chord frame);
//! - [`body`]: a rigid body in six degrees of freedom with fairleads (a floater);
//! - [`benchmark`]: the coupling benchmark units (oscillator, algebraic loops).

/// The unit contract, in its own crate (`slender-contract`) so that the master
/// and the FMI layer depend on it without the physics.
pub use slender_contract as contract;
pub use slender_contract::state_struct;

pub mod beam;
pub mod benchmark;
pub mod body;
pub mod cable;
pub mod chord;
pub mod contact;
pub mod integrators;
pub mod line3d;
pub mod nonlinear;
pub mod numerics;
pub mod reduced;
pub mod sea;
pub mod signal;
pub mod span;
pub mod static_section;

pub use contract::{
    Capabilities, Causality, Driver, DriverSlot, HeldInputs, Hold, HoldSupport, Inputs,
    ModalAnalysis, Mode, Port, PortKind, StateSlot, StepReport, Time, Unit, UnitDescription,
    UnitError,
};
