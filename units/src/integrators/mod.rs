//! Time integrators shared by the units; one integrator per file.
//!
//! - [`hht`]: HHT-alpha with Newton iterations for any [`hht::SecondOrderSystem`]
//!   (banded matrices, prescribed DOFs, a nonlinear force with its tangent);
//! - [`newmark_iterated`]: Newmark average acceleration in total form on banded
//!   systems with a velocity-dependent force iterated on the fixed factorisation
//!   (the cable);
//! - [`central_difference`]: explicit central differences (velocity Verlet) with
//!   the critical step reported;
//! - [`newmark`]: linear Newmark average acceleration on small dense systems;
//! - [`hht_sensitivity`]: a converged HHT-alpha step's sensitivity to its
//!   coupled end values (the step Jacobians of the units it steps);
//! - [`warm_start`]: a repeated step's first iterate from the last attempt
//!   moved by those derivatives.

pub mod central_difference;
pub mod hht;
pub mod hht_sensitivity;
#[cfg(test)]
mod hht_tests;
pub mod newmark;
pub mod newmark_iterated;
pub mod warm_start;
