//! Linear algebra the units share.

pub mod banded;
pub mod modal;
