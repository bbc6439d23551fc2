//! Figures that read right (SVG through plotters): every axis titled with its
//! unit, ticks at decades or 1-2-5 steps with labels that do not run into each
//! other, legends and keys beside the data, point labels as numbers placed
//! clear of each other.
//!
//! - [`ticks`], [`axes`], [`labels`]: the parts every figure uses;
//! - [`study`] (with `bars` and `heat`): `study.svg`, drawn as each group's
//!   settings allow (lines, grouped bars, heat maps);
//! - [`tradeoff`]: error against cost with the Pareto front (`error_cost.svg`
//!   of a study, `fidelity.svg`);
//! - [`units`]: a setting's unit for its axis;
//! - [`curves`]: curves against one abscissa (a moored body's statics);
//! - [`cases`]: a load-case matrix's extremes and fatigue shares over the
//!   Hs-Tp scatter (`cases.svg`).

pub mod axes;
mod bars;
pub mod cases;
pub mod curves;
mod heat;
pub mod labels;
pub mod study;
pub(crate) mod thin;
pub mod ticks;
pub mod tradeoff;
pub mod units;
