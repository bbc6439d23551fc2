//! The unit's fields as FMI 3.0 array outputs: which value reference is an
//! array, and its values.

use super::Instance;

impl Instance {
    /// The field whose array variable has value reference `vr`.
    pub(super) fn field_of(&self, vr: u32) -> Option<usize> {
        let k = vr.checked_sub(self.layout.first_field_reference)? as usize;
        (k < self.layout.fields.len()).then_some(k)
    }

    /// Writes field `k`'s values at the start of `out`; how many.
    pub(super) fn read_field(&self, k: usize, out: &mut [f64]) -> Result<usize, String> {
        let field = &self.layout.fields[k];
        let room = out.len();
        let slot = out.get_mut(..field.len).ok_or_else(|| {
            format!(
                "`{}` is an array of {} values; room for {room} was passed",
                field.name, field.len
            )
        })?;
        let unit = self
            .unit
            .as_ref()
            .ok_or_else(|| format!("`{}` is known after initialisation", field.name))?;
        unit.field_values(k, slot).map_err(|e| e.to_string())?;
        Ok(field.len)
    }
}
