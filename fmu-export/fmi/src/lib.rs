//! FMI 2.0 co-simulation: FMUs as units (import) and units as FMUs (export).
//!
//! - [`model_description`]: reading and writing `modelDescription.xml`;
//! - [`import::FmuUnit`]: an FMU behind the unit contract (scene kind `fmu`);
//! - [`export`]: what an exported FMU carries, its variable layout and the
//!   packaging; building units from scenes is `slender_scene::export`, the entry
//!   points themselves live in the `slender-fmu` crate;
//! - [`ssp`]: SSP 1.0 system structures (`SystemStructure.ssd`) and archives;
//! - [`ffi`]: the C types both sides share; [`measure`]: units of measure.

pub mod export;
pub mod ffi;
pub mod import;
pub mod measure;
pub mod model_description;
pub mod ssp;
mod whole_file;
