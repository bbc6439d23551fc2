//! slender-coupling: the coupling algorithm. Couples units into a system and steps
//! it; no I/O, no FMI, no command line.
//!
//! - [`system`]: units and connections, checked as they are added;
//! - [`adapter`]: the master's side of a unit (port values, counters);
//! - [`coupler::Master`]: the synchronisation schemes (Jacobi, Gauss-Seidel, their
//!   iterative versions with rollback and acceleration), initialisation, sweeps;
//! - [`acceleration`]: constant relaxation, Aitken, IQN-ILS; [`newton`]: interface
//!   Newton; [`order`]: sweep order and torn connections;
//! - [`settings`], [`counters`], [`error`]: settings, what a run did, typed errors.

pub mod acceleration;
pub mod adapter;
pub mod counters;
pub mod coupler;
pub mod error;
mod newton;
pub mod order;
pub mod settings;
pub mod system;

pub use coupler::Master;
pub use error::MasterError;
pub use settings::{Acceleration, MasterSettings, NewtonSettings, Scheme, Solver, Tolerances};
pub use system::{Link, System, SystemError};
