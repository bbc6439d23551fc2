//! The unit of an exported FMU built from its configuration (kind, parameters,
//! effects, hold): what the FMU library does at instantiation, and what the
//! exporter does to write the model description.

use crate::{BuildContext, BuildError, Given, find};
use slender_fmi::export::{ExportConfig, KindInfo, Layout};
use slender_units::{Driver, Unit};
use std::path::Path;

/// Building an exported unit from its [`ExportConfig`].
pub trait ExportedUnit {
    /// Builds the unit with the configured parameters and effects.
    fn build_unit(&self) -> Result<Box<dyn Unit>, BuildError>;

    /// The unit in a driver with the configured hold.
    fn driver(&self) -> Result<Driver, BuildError>;

    /// The FMU layout: builds the unit once to read its ports (with the holds in
    /// force) and to check its parameters.
    fn layout(&self) -> Result<Layout, BuildError>;
}

impl ExportedUnit for ExportConfig {
    fn build_unit(&self) -> Result<Box<dyn Unit>, BuildError> {
        let kind = find(&self.kind).ok_or_else(|| BuildError::UnknownKind(self.kind.clone()))?;
        let context = BuildContext {
            effects: &self.effects,
            base_dir: Path::new("."),
        };
        kind.build(Given::Table(self.parameters.clone()), &context)
    }

    fn driver(&self) -> Result<Driver, BuildError> {
        let mut unit = Driver::new(self.build_unit()?);
        if let Some(hold) = self.hold {
            for port in 0..unit.description().inputs.len() {
                unit.set_hold(port, hold)?;
            }
        }
        Ok(unit)
    }

    fn layout(&self) -> Result<Layout, BuildError> {
        let driver = self.driver()?;
        let mut unit = driver.description().clone();
        for (port, hold) in unit.inputs.iter_mut().zip(driver.holds()) {
            port.hold = *hold;
        }
        let kind = find(&self.kind).ok_or_else(|| BuildError::UnknownKind(self.kind.clone()))?;
        let info = KindInfo {
            summary: kind.summary,
            effects: kind.effects,
            parameters: crate::reference::parameters(kind.name),
        };
        Ok(Layout::new(self, unit, driver.fields(), &info))
    }
}
