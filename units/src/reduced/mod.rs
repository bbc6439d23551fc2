//! Reduced-order models of a nonlinear section (seed 002, issue 15): bases about
//! the stress-free state and the reduced restoring forces.
//!
//! - [`polynomial`]: a seed 002 section's restoring force as the cubic
//!   polynomial g(V) = K0 V + K1(V) V + K2(V, V) V over its free DOFs, with the
//!   mass matrix;
//! - [`basis`]: linear normal modes (mass or stiffness normalised), modal
//!   derivatives in seed 002's three forms (static, modified with the geometric
//!   restriction, and the novel ones from the Taylor expansion of the equations
//!   of motion), the Taylor basis's columns and the detection of linearly
//!   dependent derivatives;
//! - [`lrbf`]: the reduced restoring force by global reduced tensors (seed
//!   002's RBF on a linear basis), and its tangent;
//! - [`ecsw`]: hyper-reduction, the reduced force summed over sampled,
//!   weighted elements (energy-conserving sampling and weighting);
//! - [`system`]: a reduced section as a second-order system the shared
//!   integrators step;
//! - [`taylor`]: the Taylor basis with N unknowns (the derivatives follow the
//!   modal coordinates), stepped by central differences up to 2 / omega_N;
//! - [`unit`]: kind `reduced`, a reduced section as a unit for scenes, and
//!   `jacobian`, its step Jacobian (tangent-linear step, linear bases).

pub mod basis;
mod build;
pub mod ecsw;
mod jacobian;
pub mod lrbf;
pub mod polynomial;
pub mod system;
pub mod taylor;
pub mod unit;
