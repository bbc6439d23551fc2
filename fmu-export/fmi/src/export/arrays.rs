//! A unit's fields as FMI 3.0 array outputs: one Float64 output per field,
//! its length as a fixed dimension, no direct dependence on inputs (a field
//! is the state after the step). The FMI 2.0 description leaves them out.

use crate::measure::si_definition;
use crate::model_description::{
    ModelDescription, ScalarVariable, Unknown, Value, VariableCausality,
};
use slender_contract::Field;

/// Appends the fields to `model`'s variables (value references from
/// `first`), outputs and initial unknowns, with their units of measure.
pub(super) fn add(model: &mut ModelDescription, fields: &[Field], first: u32) {
    for (k, field) in fields.iter().enumerate() {
        let unit = si_definition(&field.unit).map(|def| {
            if model.unit(&def.name).is_none() {
                model.units.push(def);
            }
            field.unit.clone()
        });
        model.variables.push(ScalarVariable {
            name: field.name.clone(),
            value_reference: first + k as u32,
            description: field.description.clone(),
            causality: VariableCausality::Output,
            variability: "continuous".into(),
            initial: Some("calculated".into()),
            value: Value::Real(None),
            unit,
            min: None,
            max: None,
            dimensions: vec![field.len],
            aliases: Vec::new(),
        });
        let unknown = Unknown {
            index: model.variables.len(),
            dependencies: Some(Vec::new()),
        };
        model.outputs.push(unknown.clone());
        model.initial_unknowns.push(unknown);
    }
}
