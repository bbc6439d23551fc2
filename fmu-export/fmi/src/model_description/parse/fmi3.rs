//! What differs in an FMI 3.0 model description: typed variable elements
//! with their attributes on the element itself, array dimensions (fixed or
//! given by a structural parameter), `<Start>` children of strings, the
//! co-simulation flags' FMI 3.0 spellings, and a model structure that refers
//! to variables by value reference (turned into FMI 2.0's 1-based indices).

use super::*;

/// The FMI 3.0 type elements slender reads as variables; other types
/// (Float32, the other integer widths, Enumeration, Binary, Clock) are left
/// out of the variables.
const READ: [&str; 4] = ["Float64", "Int32", "Boolean", "String"];

/// The most values an array may hold (each becomes a port when it is an input
/// or an output).
const MAX_VALUES: usize = 1 << 20;

/// The integer types whose start value can size an array.
const INTEGERS: [&str; 8] = [
    "Int8", "UInt8", "Int16", "UInt16", "Int32", "UInt32", "Int64", "UInt64",
];

/// What is read before it can be resolved: dimensions given by a structural
/// parameter, and the model structure's unknowns by value reference.
#[derive(Default)]
pub(super) struct Pending {
    /// Start values of integer variables, by value reference.
    integers: HashMap<u32, i64>,
    /// (variable index, dimension index, value reference, line).
    dimensions: Vec<(usize, usize, u32, usize)>,
    unknowns: Vec<Unknown3>,
    /// The description's last line, for errors found after reading it.
    pub(super) last_line: usize,
}

/// A model structure entry as FMI 3.0 writes it: whether an Output (else an
/// InitialUnknown), its value reference, its dependencies' references, line.
type Unknown3 = (bool, u32, Option<Vec<u32>>, usize);

impl Pending {
    /// Sizes the arrays and turns value references into indices; unknowns
    /// and dependencies on variables left out are dropped.
    pub(super) fn resolve(self, md: &mut ModelDescription) -> Result<(), DescriptionError> {
        for (variable, dimension, vr, line) in self.dimensions {
            let size = self.integers.get(&vr).copied().ok_or_else(|| DescriptionError {
                line,
                message: format!(
                    "<Dimension>: valueReference {vr} is not an integer variable with a start value"
                ),
            })?;
            let size = usize::try_from(size).map_err(|_| DescriptionError {
                line,
                message: format!("<Dimension>: size {size} of valueReference {vr}"),
            })?;
            // (A variable left unfinished by a truncated file has no entry.)
            if let Some(v) = md.variables.get_mut(variable)
                && let Some(d) = v.dimensions.get_mut(dimension)
            {
                *d = size;
                if v.dimensions.len() == 1 {
                    v.sized_by = Some(vr);
                }
            }
        }
        for v in &md.variables {
            let values = v
                .dimensions
                .iter()
                .try_fold(1usize, |n, &d| n.checked_mul(d));
            if values.is_none_or(|n| n > MAX_VALUES) {
                return Err(DescriptionError {
                    line: self.last_line,
                    message: format!(
                        "`{}`: an array of {:?} values, more than the {MAX_VALUES} slender takes",
                        v.name, v.dimensions
                    ),
                });
            }
        }
        let index: HashMap<u32, usize> = md
            .variables
            .iter()
            .enumerate()
            .map(|(i, v)| (v.value_reference, i + 1))
            .collect();
        for (output, vr, dependencies, _) in self.unknowns {
            let Some(&i) = index.get(&vr) else { continue };
            let unknown = Unknown {
                index: i,
                dependencies: dependencies
                    .map(|list| list.iter().filter_map(|d| index.get(d).copied()).collect()),
            };
            if output {
                md.outputs.push(unknown);
            } else {
                md.initial_unknowns.push(unknown);
            }
        }
        Ok(())
    }
}

impl Parser<'_> {
    /// An element of an FMI 3.0 description where it differs from FMI 2.0:
    /// whether it stays open, or `None` to read it as FMI 2.0 does.
    pub(super) fn element3(
        &mut self,
        parent: &str,
        attrs: Attributes,
        is_empty: bool,
        state: &mut ParseState,
    ) -> Result<Option<bool>, DescriptionError> {
        let name = attrs.element.as_str();
        let pending = state
            .fmi3
            .as_mut()
            .ok_or_else(|| attrs.error("not FMI 3.0".into()))?;
        match (parent, name) {
            ("fmiModelDescription", "CoSimulation") => {
                if let Some(m) = state.md.as_mut() {
                    m.co_simulation = Some(Self::co_simulation3(&attrs)?);
                }
            }
            ("ModelVariables", _) => self.variable3(attrs, is_empty, state)?,
            (_, "Dimension") => {
                let line = attrs.line;
                let variables = state.md.as_ref().map_or(0, |m| m.variables.len());
                if let Some((_, Some(v))) = state.variable.as_mut() {
                    match attrs.parsed::<usize>("start", "an array size")? {
                        Some(n) => v.dimensions.push(n),
                        None => {
                            let vr = attrs
                                .parsed("valueReference", "a value reference")?
                                .ok_or_else(|| {
                                    attrs.error("needs `start` or `valueReference`".into())
                                })?;
                            pending
                                .dimensions
                                .push((variables, v.dimensions.len(), vr, line));
                            v.dimensions.push(0);
                        }
                    }
                }
            }
            (_, "Alias") => {
                if let Some((_, Some(v))) = state.variable.as_mut() {
                    v.aliases.push(attrs.required("name")?.to_owned());
                }
            }
            ("String", "Start") => {
                if let Some((_, Some(v))) = state.variable.as_mut() {
                    v.value = Value::String(attrs.optional("value").map(str::to_owned));
                }
            }
            ("ModelStructure", _) => {
                let output = name == "Output";
                if output || name == "InitialUnknown" {
                    pending.unknowns.push(Self::unknown3(&attrs, output)?);
                }
            }
            _ => return Ok(None),
        }
        Ok(Some(!is_empty))
    }

    /// A variable element of `ModelVariables`: an integer's start kept for
    /// the arrays it sizes, a read type parsed and held open for its
    /// `Dimension`, `Alias` and `Start` children.
    fn variable3(
        &mut self,
        attrs: Attributes,
        is_empty: bool,
        state: &mut ParseState,
    ) -> Result<(), DescriptionError> {
        let name = attrs.element.as_str();
        let pending = state
            .fmi3
            .as_mut()
            .ok_or_else(|| attrs.error("not FMI 3.0".into()))?;
        note_clock(&attrs, state.md.as_mut());
        if INTEGERS.contains(&name)
            && let Some(start) = attrs.optional("start")
            && let Some(vr) = attrs.parsed::<u32>("valueReference", "an unsigned integer")?
            && let Ok(start) = start.trim().parse::<i64>()
        {
            pending.integers.insert(vr, start);
        }
        let typed = if READ.contains(&name) {
            let mut scalar = attrs.clone();
            // An array's start lists its values; the first stands for all.
            if let Some(start) = scalar.values.get_mut("start")
                && let Some(first) = start.split_whitespace().next()
            {
                *start = first.to_owned();
            }
            Some(Self::variable(&attrs, &scalar)?)
        } else {
            None
        };
        state.variable = Some((attrs, typed));
        if is_empty {
            self.finish_variable3(state)?;
        }
        Ok(())
    }

    /// The end of a variable element: kept when its type is read.
    pub(super) fn finish_variable3(
        &mut self,
        state: &mut ParseState,
    ) -> Result<(), DescriptionError> {
        match state.variable.take() {
            Some((attrs, Some(v))) => self.finish_variable(&mut state.md, Some((attrs, Some(v)))),
            _ => Ok(()),
        }
    }

    fn co_simulation3(attrs: &Attributes) -> Result<CoSimulation, DescriptionError> {
        Ok(CoSimulation {
            model_identifier: attrs.required("modelIdentifier")?.to_owned(),
            can_handle_variable_communication_step_size: attrs
                .flag("canHandleVariableCommunicationStepSize")?,
            // FMI 3.0 co-simulation has no input derivatives.
            can_interpolate_inputs: false,
            max_output_derivative_order: attrs
                .parsed("maxOutputDerivativeOrder", "an unsigned integer")?
                .unwrap_or(0),
            can_get_and_set_fmu_state: attrs.flag("canGetAndSetFMUState")?,
            can_serialize_fmu_state: attrs.flag("canSerializeFMUState")?,
            provides_directional_derivative: attrs.flag("providesDirectionalDerivatives")?,
        })
    }

    fn unknown3(attrs: &Attributes, output: bool) -> Result<Unknown3, DescriptionError> {
        let vr = attrs
            .parsed("valueReference", "a value reference")?
            .ok_or_else(|| attrs.error("missing required attribute `valueReference`".into()))?;
        let dependencies = attrs.list("dependencies", "a value reference")?;
        Ok((output, vr, dependencies, attrs.line))
    }
}

/// A clock or a clocked variable into the description's `clocks` (the
/// importer refuses an FMU that has any).
fn note_clock(attrs: &Attributes, md: Option<&mut ModelDescription>) {
    let clocked = attrs.optional("clocks");
    if attrs.element != "Clock" && clocked.is_none() {
        return;
    }
    let variable = attrs.optional("name").unwrap_or("?");
    let entry = match clocked {
        Some(c) => format!("{variable} (clocked by {c})"),
        None => variable.to_owned(),
    };
    if let Some(m) = md {
        m.clocks.push(entry);
    }
}
