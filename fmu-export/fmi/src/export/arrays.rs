//! A unit's fields as FMI 3.0 array outputs: one Float64 output per field,
//! no direct dependence on inputs (a field is the state after the step),
//! each sized by a structural parameter that counts what it has a value for
//! (`n_nodes`, `n_elements`: UInt64, fixed, after the arrays), so that an
//! importer that changes the mesh through the parameters can size its
//! buffers. The FMI 2.0 description leaves both out.

use crate::measure::si_definition;
use crate::model_description::{
    ModelDescription, ScalarVariable, Unknown, Value, VariableCausality,
};
use slender_contract::{Field, FieldSupport};

/// A structural parameter sizing the arrays of one support.
#[derive(Clone, Debug, PartialEq)]
pub struct ArraySize {
    /// Its FMI name (`n_nodes`, `n_elements`).
    pub name: String,
    /// What it counts.
    pub per: FieldSupport,
    /// The count at export (its start).
    pub start: usize,
    /// Its value reference.
    pub value_reference: u32,
}

/// The FMI name of the structural parameter counting `per`.
pub fn size_name(per: FieldSupport) -> &'static str {
    match per {
        FieldSupport::Node => "n_nodes",
        FieldSupport::Element => "n_elements",
    }
}

/// Appends the fields to `model`'s variables (value references from
/// `first`), outputs and initial unknowns, with their units of measure, then
/// the structural parameters that size them; returns the latter.
pub(super) fn add(model: &mut ModelDescription, fields: &[Field], first: u32) -> Vec<ArraySize> {
    let sizes = sizes(fields, first + fields.len() as u32);
    for (k, field) in fields.iter().enumerate() {
        let unit = si_definition(&field.unit).map(|def| {
            if model.unit(&def.name).is_none() {
                model.units.push(def);
            }
            field.unit.clone()
        });
        let sized_by = sizes
            .iter()
            .find(|s| s.per == field.per && s.start == field.len);
        model.variables.push(ScalarVariable {
            unit,
            dimensions: vec![field.len],
            sized_by: sized_by.map(|s| s.value_reference),
            ..ScalarVariable::calculated_output(
                field.name.clone(),
                first + k as u32,
                field.description.clone(),
            )
        });
        let unknown = Unknown {
            index: model.variables.len(),
            dependencies: Some(Vec::new()),
        };
        model.outputs.push(unknown.clone());
        model.initial_unknowns.push(unknown);
    }
    for size in &sizes {
        model.variables.push(size_variable(size));
    }
    sizes
}

/// One structural parameter per support the fields have (nodes first), its
/// start the fields' length; value references from `first`.
fn sizes(fields: &[Field], first: u32) -> Vec<ArraySize> {
    [FieldSupport::Node, FieldSupport::Element]
        .into_iter()
        .filter_map(|per| fields.iter().find(|f| f.per == per))
        .enumerate()
        .map(|(k, field)| ArraySize {
            name: size_name(field.per).to_owned(),
            per: field.per,
            start: field.len,
            value_reference: first + k as u32,
        })
        .collect()
}

fn size_variable(size: &ArraySize) -> ScalarVariable {
    let what = size.per.counted();
    let start = i32::try_from(size.start).unwrap_or(i32::MAX);
    let description = format!(
        "number of {what} of the unit's mesh, the length of the arrays with one value per {}: \
             follows the parameters (read it after initialisation), or set it with parameters \
             that change the mesh and the FMU checks it; fixed at instantiation",
        &what[..what.len() - 1]
    );
    ScalarVariable::new(
        size.name.clone(),
        size.value_reference,
        description,
        VariableCausality::StructuralParameter,
        Value::Integer(Some(start)),
    )
    .fixed()
}
