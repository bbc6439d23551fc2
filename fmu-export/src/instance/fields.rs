//! The unit's fields as FMI 3.0 array outputs: which value reference is an
//! array, its values, and the structural parameters that size them
//! (`n_nodes`, `n_elements`). A size follows the unit as built from the
//! parameters (read it after initialisation); one set before initialisation
//! is checked against the unit, so an importer that sized its buffers by it
//! learns at once when the parameters give another mesh.

use super::{Instance, Phase};
use slender_fmi::ffi::{FMI2_OK, fmi2Status};
use slender_units::contract::Field;

impl Instance {
    /// The field whose array variable has value reference `vr`.
    pub(super) fn field_of(&self, vr: u32) -> Option<usize> {
        let k = vr.checked_sub(self.layout.first_field_reference)? as usize;
        (k < self.layout.fields.len()).then_some(k)
    }

    /// Writes field `k`'s values at the start of `out`; how many.
    pub(super) fn read_field(&self, k: usize, out: &mut [f64]) -> Result<usize, String> {
        let field = &self.layout.fields[k];
        let len = self.field_lengths[k];
        let room = out.len();
        let slot = out.get_mut(..len).ok_or_else(|| {
            let size = self.layout.sizes.iter().find(|s| s.per == field.per);
            let hint = size.map_or(String::new(), |s| {
                format!(" (its size is the structural parameter `{}`)", s.name)
            });
            format!(
                "`{}` is an array of {len} values{hint}; room for {room} was passed",
                field.name
            )
        })?;
        let unit = self
            .unit
            .as_ref()
            .ok_or_else(|| format!("`{}` is known after initialisation", field.name))?;
        unit.field_values(k, slot).map_err(|e| e.to_string())?;
        Ok(len)
    }

    /// Keeps the lengths of the fields of a unit just built, after checking
    /// them against the sizes set before initialisation.
    pub(super) fn check_sizes(&mut self, fields: &[Field]) -> Result<(), String> {
        for (size, set) in self.layout.sizes.iter().zip(&self.sizes) {
            let built = fields.iter().find(|f| f.per == size.per).map(|f| f.len);
            if let (Some(set), Some(built)) = (*set, built)
                && set != built as u64
            {
                return Err(format!(
                    "`{}` = {set}, but the parameters give {built} {}: set `{}` = {built} \
                     with them, or leave it unset and read it after initialisation",
                    size.name,
                    size.per.counted(),
                    size.name
                ));
            }
        }
        self.field_lengths = fields.iter().map(|f| f.len).collect();
        Ok(())
    }

    /// The index in `Layout::sizes` of value reference `vr`.
    fn size_of(&self, vr: u32) -> Result<usize, String> {
        (self.layout.sizes.iter())
            .position(|s| s.value_reference == vr)
            .ok_or_else(|| format!("value reference {vr} is not a UInt64 (an array size)"))
    }

    /// `fmi3GetUInt64`: the array sizes, as the unit has them once built (as
    /// set, or exported, before).
    pub(crate) fn get_sizes(&mut self, vr: &[u32], out: &mut [u64]) -> Result<fmi2Status, String> {
        for (r, value) in vr.iter().zip(out.iter_mut()) {
            let k = self.size_of(*r)?;
            let size = &self.layout.sizes[k];
            let built = (self.layout.fields.iter().zip(&self.field_lengths))
                .find(|(f, _)| f.per == size.per)
                .map(|(_, len)| *len as u64);
            *value = match (&self.unit, self.sizes[k]) {
                (Some(_), _) => built.unwrap_or(size.start as u64),
                (None, Some(set)) => set,
                (None, None) => size.start as u64,
            };
        }
        Ok(FMI2_OK)
    }

    /// `fmi3SetUInt64`: the array sizes, in Configuration Mode as FMI 3.0
    /// has it (or, as FMPy does, in the Instantiated state), before
    /// initialisation only (they are fixed structural parameters); checked
    /// when the unit is built.
    pub(crate) fn set_sizes(&mut self, vr: &[u32], values: &[u64]) -> Result<fmi2Status, String> {
        for (r, value) in vr.iter().zip(values) {
            let k = self.size_of(*r)?;
            let name = &self.layout.sizes[k].name;
            if !matches!(self.phase, Phase::Configuration | Phase::Instantiated) {
                return Err(format!(
                    "`{name}` is a fixed structural parameter: set it in Configuration Mode, before fmi3EnterInitializationMode"
                ));
            }
            if *value == 0 {
                return Err(format!("`{name}` = 0: expected at least 1"));
            }
            self.sizes[k] = Some(*value);
        }
        Ok(FMI2_OK)
    }

    /// `fmi3EnterConfigurationMode`: from the Instantiated state, where the
    /// FMU has array sizes to set.
    pub(crate) fn enter_configuration(&mut self) -> Result<fmi2Status, String> {
        if self.layout.sizes.is_empty() {
            return Err("this FMU has no structural parameter to configure".into());
        }
        if self.phase != Phase::Instantiated {
            return Err("only allowed after fmi3InstantiateCoSimulation or fmi3Reset".into());
        }
        self.phase = Phase::Configuration;
        Ok(FMI2_OK)
    }

    /// `fmi3ExitConfigurationMode`: back to the Instantiated state.
    pub(crate) fn exit_configuration(&mut self) -> Result<fmi2Status, String> {
        if self.phase != Phase::Configuration {
            return Err("only allowed in Configuration Mode".into());
        }
        self.phase = Phase::Instantiated;
        Ok(FMI2_OK)
    }
}
