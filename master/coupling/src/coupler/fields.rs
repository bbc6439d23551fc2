//! The units' fields (quantities along a unit: positions, tension,
//! curvature) read through the master, for envelopes along a line.

use super::Master;
use slender_contract::{Field, UnitError};

impl Master {
    /// The fields unit `unit` can report (none for most units).
    pub fn fields(&self, unit: usize) -> Vec<Field> {
        self.units.get(unit).map_or(Vec::new(), |u| u.fields())
    }

    /// The current values of field `index` of unit `unit` into `out` (its
    /// length); after `initialize`.
    pub fn field_values(
        &self,
        unit: usize,
        index: usize,
        out: &mut [f64],
    ) -> Result<(), UnitError> {
        match self.units.get(unit) {
            Some(u) => u.field_values(index, out),
            None => Err(UnitError::Unsupported(format!("unit {unit}: no such unit"))),
        }
    }
}
