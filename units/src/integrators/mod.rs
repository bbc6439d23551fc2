//! Time integrators shared by the units; one integrator per file.
//!
//! - [`hht`]: HHT-alpha with Newton iterations for any [`hht::SecondOrderSystem`]
//!   (banded matrices, prescribed DOFs, a nonlinear force with its tangent);
//! - [`newmark`]: linear Newmark average acceleration on small dense systems.

pub mod hht;
pub mod newmark;
