//! slender-uq: the numerics of uncertainty studies (seed 000 sec. 4).
//!
//! - [`design`]: Latin hypercube designs on the unit cube, seeded and optimised
//!   for space filling (maximin), and their nested doubling (208 -> 416 -> 832
//!   keeps the earlier runs), and seeded Owen-scrambled Sobol' sequences;
//! - [`basis`]: marginal distributions and their orthonormal polynomials
//!   (Legendre for uniform, Hermite for normal inputs);
//! - [`pce`]: sparse polynomial chaos: hyperbolic truncation, hybrid least-angle
//!   regression with the leave-one-out error choosing the basis and the degree,
//!   and the mean, variance and first-order and total Sobol' indices from the
//!   coefficients;
//! - [`distribution`]: an expansion's output distribution (quantiles, density)
//!   from the surrogate on a large Sobol' sample;
//! - [`filtering`]: which inputs drive an outcome that splits the runs (Monte
//!   Carlo filtering by Kolmogorov-Smirnov distances) and the outcome's
//!   probability with its Wilson interval.
pub mod basis;
pub mod bootstrap;
pub mod design;
pub mod distribution;
pub mod filtering;
pub mod marginal;
pub mod pce;

/// Why a study's numerics cannot go on.
#[derive(Debug, thiserror::Error, PartialEq)]
#[non_exhaustive]
pub enum UqError {
    /// A parameter or data set that cannot be used: which and why.
    #[error("{what}: {why}")]
    Input {
        /// The parameter or data set.
        what: String,
        /// Why it cannot be used.
        why: String,
    },
    /// A least-squares fit that has no unique solution.
    #[error("the regression is singular: {0}")]
    Singular(String),
}

impl UqError {
    pub(crate) fn input(what: impl Into<String>, why: impl Into<String>) -> UqError {
        UqError::Input {
            what: what.into(),
            why: why.into(),
        }
    }
}
