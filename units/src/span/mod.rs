//! The suspended span of a pipe as a transfer function (seed 004 ch. 5): the exact
//! frequency response of the damped Euler-Bernoulli span between its end values,
//! and rational approximations of it.
//!
//! - [`transfer`]: the exact 4x4 transfer matrix between any four end quantities;
//! - [`rational`]: the source's Taylor, term-wise and function Pade approximations;
//! - [`fit`], [`realization`], [`unit`]: the SISO span unit (kind `span`, U2 -> U5);
//! - [`coupling`]: the 4x4 span between two sections (kind `span_coupling`).

pub mod coupling;
pub mod fit;
mod matrix_fit;
pub mod rational;
pub mod realization;
pub mod transfer;
pub mod unit;
