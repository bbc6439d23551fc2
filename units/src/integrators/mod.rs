//! Time integrators shared by the units; one integrator per file.
//!
//! - [`hht`]: HHT-alpha with Newton iterations for any [`hht::SecondOrderSystem`]
//!   (banded matrices, prescribed DOFs, a nonlinear force with its tangent);
//! - [`newmark_iterated`]: Newmark average acceleration in total form on banded
//!   systems with a velocity-dependent force iterated on the fixed factorisation
//!   (the cable);
//! - [`central_difference`]: explicit central differences (velocity Verlet) with
//!   the critical step reported;
//! - [`newmark`]: linear Newmark average acceleration on small dense systems.

pub mod central_difference;
pub mod hht;
pub mod newmark;
pub mod newmark_iterated;
