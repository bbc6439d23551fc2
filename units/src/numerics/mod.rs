//! Linear algebra the units share.

pub mod banded;
pub mod bounded;
pub mod lanczos;
pub mod modal;
pub mod subspace;
pub mod table;
