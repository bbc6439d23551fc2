//! Signal units: sources of prescribed loads and the artefacts a control system
//! puts on coupled signals.

pub mod artefact;
pub mod characteristic_load;
pub mod compensation;
