//! The suspended span of a pipe as a transfer function (seed 004 ch. 5): the exact
//! frequency response of the damped Euler-Bernoulli span between its end values,
//! and rational approximations of it.
//!
//! Status: the analytic transfer matrix and the source's three order-N
//! approximations (Taylor, term-wise Pade, function Pade) are here and verified; the
//! band fit, the state-space span unit, Bode plots and the accuracy/cost study are
//! the rest of issue 5.

pub mod fit;
pub mod rational;
pub mod realization;
pub mod transfer;
pub mod unit;
