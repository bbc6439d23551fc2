//! slender-master: couples units into a system and steps it.
//!
//! - [`system`]: units and connections, checked as they are added;
//! - [`coupler::Master`]: the synchronisation schemes (Jacobi, Gauss-Seidel, their
//!   iterative versions with rollback and acceleration, Newton);
//! - [`scene`]: TOML scene files to systems and settings;
//! - [`run`]: running a scene with recording, summary and plots (used by the CLI).

pub mod acceleration;
pub mod adapter;
pub mod counters;
pub mod coupler;
pub mod coupling_study;
pub mod error;
pub mod fmi;
pub mod indicators;
mod newton;
pub mod order;
pub mod scene;
pub mod settings;
pub mod span_study;
pub mod study;
pub mod system;

pub use coupler::Master;
pub use error::MasterError;
pub use settings::{Acceleration, MasterSettings, Scheme, Tolerances};
pub use system::{Link, System};
pub mod plot;
pub mod record;
pub mod run;
