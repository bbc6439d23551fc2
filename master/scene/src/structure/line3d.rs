//! A `[structure]` whose model is a 3D line (`structure.model.kind =
//! "line3d"`, the rest of the model a `line3d` unit's parameters; its ends
//! fixed, moved or moved by coupled velocities, which the first and last
//! sections and the twin then take as inputs): its statics are solved once
//! as the whole line (a coupled end held where it is), each section becomes a
//! `line3d` unit between the equilibrium's points at its cuts, and each cut
//! couples the lower section's end (moved by the upper start's velocity) with
//! the upper section's start (loaded by the lower end's pull), x, y and z.
//! A section's fidelity is the 3D line (`nonlinear`) at the model's mesh or
//! at its own (`elements`), the same linearised about its static state
//! (`linear`), or, for the first section from a fixed anchor, the elastic
//! catenary (`static`, kind `catenary3d`); `reference = true` adds the whole
//! line as one unit, the twin. The other fidelities (cable, reduced, chords),
//! physical sections, FMUs, sub-steps, a top load and a hang-off angle are
//! planar so far and are refused here by name.

use super::layout::{Layout, SectionLayout, SectionOutputs, choice_of};
use super::sections::{Cut, Fidelity, SectionFile, cuts_of};
use super::spec::typed;
use super::unit::{Parameters, SectionUnit};
use super::{Link, Written, reference_name, unit_name};
use serde::Deserialize;
use slender_units::line3d::params::EndSpec;
use slender_units::line3d::{EndCondition, Line3d, Line3dParams};
use slender_units::{Driver, Time, Unit};
use toml::{Table, Value};

/// `[structure]` with a 3D line as its model, as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Structure3dFile {
    name: String,
    model: Table,
    #[serde(default)]
    sections: Vec<SectionFile>,
    #[serde(default)]
    reference: bool,
}

/// Whether `[structure]` describes a 3D line.
pub(super) fn is_3d(structure: &Table) -> bool {
    let kind = structure.get("model").and_then(|m| m.get("kind"));
    kind.and_then(Value::as_str) == Some("line3d")
}

/// The line the model makes (its parameters without `kind`), checked.
fn model_of(model: &Table) -> Result<Line3dParams, String> {
    let mut parameters = model.clone();
    parameters.remove("kind");
    let params: Line3dParams = typed("structure.model", &parameters)?;
    params
        .validate()
        .map_err(|e| format!("`structure.model`: {e}"))?;
    for (side, end) in [("start", &params.start), ("end", &params.end)] {
        if end.condition == EndCondition::Force {
            return Err(format!(
                "`structure.model.{side}.condition` = \"force\": a 3D structure's ends are fixed, moved (`motion`) or moved by coupled velocities (`velocity`: a vessel's or a body's fairlead); a loaded end needs its force at the start, which the structure's statics do not know"
            ));
        }
    }
    Ok(params)
}

/// A 3D line's `[structure]` read and checked: its name, the line, its
/// sections and whether it has a twin. A `[mooring]` makes one per line.
#[derive(Clone, Debug)]
pub(crate) struct Line3dStructure {
    /// The prefix of its units' names.
    pub name: String,
    /// The whole line.
    pub params: Line3dParams,
    /// Its sections, by arc length.
    pub(super) cuts: Vec<Cut>,
    /// It has a twin, the whole line as one unit.
    pub reference: bool,
}

impl Line3dStructure {
    /// Reads a `[structure]` whose model is a 3D line; the error names the key.
    pub(super) fn parse(structure: &Table) -> Result<Line3dStructure, String> {
        let file: Structure3dFile = typed("structure", structure)?;
        Line3dStructure::new(
            file.name,
            model_of(&file.model)?,
            &file.sections,
            file.reference,
        )
    }

    /// The line `params` named `name`, cut into `sections`.
    pub(crate) fn new(
        name: String,
        params: Line3dParams,
        sections: &[SectionFile],
        reference: bool,
    ) -> Result<Line3dStructure, String> {
        let cuts = cuts_of(sections, params.length)?;
        Ok(Line3dStructure {
            name,
            params,
            cuts,
            reference,
        })
    }

    /// The unit of its last section (the one at the line's end).
    pub(crate) fn top_unit(&self) -> String {
        let last = self.cuts.last().map_or("", |c| c.name.as_str());
        unit_name(&self.name, last)
    }

    /// Writes the line out at `t0` (its statics solved there).
    pub(crate) fn write(&self, t0: Time) -> Result<Written, String> {
        let (params, cuts) = (&self.params, &self.cuts);
        for (k, cut) in cuts.iter().enumerate() {
            refuse_planar(cut, k, cuts.len(), params)?;
        }
        let shape = static_shape(params, t0)?;
        let mut units = Vec::new();
        let mut connections = Vec::new();
        for (k, cut) in cuts.iter().enumerate() {
            let mut section = params.clone();
            section.length = cut.to - cut.from;
            section.elements = cut.elements.unwrap_or_else(|| mesh_of(cut, params));
            if k > 0 {
                section.start = EndSpec::at(shape.at(cut.from), EndCondition::Force);
            }
            if k + 1 < cuts.len() {
                section.end = EndSpec::at(shape.at(cut.to), EndCondition::Velocity);
            }
            section.linear |= cut.fidelity == Fidelity::Linear;
            let name = unit_name(&self.name, &cut.name);
            if k > 0 {
                let lower = unit_name(&self.name, &cuts[k - 1].name);
                connections.extend(cut_links(&lower, &name));
            }
            let section = Box::new(section);
            let parameters = match cut.fidelity {
                Fidelity::Static => Parameters::Catenary3d(section),
                _ => Parameters::Line3d(section),
            };
            units.push(SectionUnit::new(name, parameters));
        }
        if self.reference {
            let twin = Parameters::Line3d(Box::new(params.clone()));
            units.push(SectionUnit::new(reference_name(&self.name), twin));
        }
        Ok(Written {
            units,
            connections,
            advisories: Vec::new(),
        })
    }
}

/// Writes out a 3D line's `[structure]` at `t0` (its statics solved there).
pub(super) fn expand(structure: &Table, t0: Time) -> Result<Written, String> {
    Line3dStructure::parse(structure)?.write(t0)
}

/// The model's own element count over the section `cut` (at least 2).
fn mesh_of(cut: &Cut, params: &Line3dParams) -> usize {
    let share = (cut.to - cut.from) / params.length * params.elements as f64;
    (share.round() as usize).max(2)
}

/// What a 3D structure's runs show (for `slender fidelity`): each section's
/// unit and the outputs carrying its end forces (x, y, z), its touchdown
/// point and its largest bending moment (a catenary section has none).
pub(super) fn layout(structure: &Table) -> Result<Layout, String> {
    Ok(Line3dStructure::parse(structure)?.layout())
}

impl Line3dStructure {
    /// What its runs show (for `slender fidelity`).
    pub(crate) fn layout(&self) -> Layout {
        let (params, cuts) = (&self.params, &self.cuts);
        let seabed = params.seabed.is_some();
        let forces = |side: &str| {
            ["x", "y", "z"]
                .map(|c| format!("{side}_force_{c}"))
                .to_vec()
        };
        let sections = cuts
            .iter()
            .map(|cut| SectionLayout {
                name: cut.name.clone(),
                unit: unit_name(&self.name, &cut.name),
                from: cut.from,
                to: cut.to,
                choice: choice_of(cut),
                plain: cut.elements.is_none() && cut.substeps.is_none() && cut.options.is_none(),
                mesh: mesh_of(cut, params),
                outputs: SectionOutputs {
                    start_force: forces("start"),
                    end_force: Some(forces("end")),
                    touchdown: seabed.then(|| "touchdown_arc".to_owned()),
                    sagbend_moment: (cut.fidelity != Fidelity::Static)
                        .then(|| "largest_moment".to_owned()),
                    overbend_moment: None,
                    stations: false,
                },
            })
            .collect();
        Layout {
            name: self.name.clone(),
            sections,
            seabed,
            stinger: false,
            planar: false,
        }
    }
}

/// Refuses what a 3D section cannot be yet: section `k` of `count` of the
/// line `params`.
fn refuse_planar(cut: &Cut, k: usize, count: usize, params: &Line3dParams) -> Result<(), String> {
    let key = format!("structure.sections.{}", cut.name);
    match cut.fidelity {
        Fidelity::Nonlinear | Fidelity::Linear => {}
        Fidelity::Static
            if k == 0 && count > 1 && params.start.condition == EndCondition::Fixed => {}
        Fidelity::Static => {
            return Err(format!(
                "`{key}.fidelity` = \"static\": a 3D line's static section is its elastic catenary from a fixed anchor: the first of several sections, the model's start fixed"
            ));
        }
        other => {
            return Err(format!(
                "`{key}.fidelity` = \"{}\": a 3D line's section is `nonlinear` (the 3D line, at the model's mesh or at the section's own `elements`), `linear` (the same linearised about its statics) or `static` (the elastic catenary, the first section); the other fidelities are planar so far",
                other.name()
            ));
        }
    }
    let planar = [
        ("physical", cut.physical.is_some()),
        ("fmu", cut.fmu.is_some()),
        ("substeps", cut.substeps.is_some()),
        ("options", cut.options.is_some()),
    ];
    match planar.iter().find(|(_, given)| *given) {
        Some((what, _)) => Err(format!(
            "`{key}`: `{what}` is not offered on a 3D line's section yet"
        )),
        None => Ok(()),
    }
}

/// The whole line's static node positions (m), by unstretched arc length.
struct Shape {
    element: f64,
    nodes: Vec<[f64; 3]>,
}

impl Shape {
    /// The point at arc `s` (m), linear between the nodes.
    fn at(&self, s: f64) -> [f64; 3] {
        let last = self.nodes.len() - 1;
        let x = (s / self.element).clamp(0.0, last as f64);
        let i = (x.floor() as usize).min(last - 1);
        let f = x - i as f64;
        let (a, b) = (self.nodes[i], self.nodes[i + 1]);
        [0, 1, 2].map(|c| a[c] + f * (b[c] - a[c]))
    }
}

/// Solves the whole line's statics at `t0`.
fn static_shape(params: &Line3dParams, t0: Time) -> Result<Shape, String> {
    let unit = Line3d::new(params.clone()).map_err(|e| format!("`structure.model`: {e}"))?;
    let mut driver = Driver::new(unit);
    driver
        .initialize(t0)
        .map_err(|e| format!("`structure.model`: the whole line's statics: {e}"))?;
    let nodes = params.elements + 1;
    let mut axes = vec![vec![0.0; nodes]; 3];
    for (index, values) in axes.iter_mut().enumerate() {
        driver
            .unit()
            .field_values(index, values)
            .map_err(|e| format!("`structure.model`: {e}"))?;
    }
    Ok(Shape {
        element: params.length / params.elements as f64,
        nodes: (0..nodes)
            .map(|i| [axes[0][i], axes[1][i], axes[2][i]])
            .collect(),
    })
}

/// The cut between `lower` and `upper`: the lower end follows the upper
/// start's velocity, the upper start carries the lower end's pull.
fn cut_links(lower: &str, upper: &str) -> Vec<Link> {
    let link = Link::new;
    ["x", "y", "z"]
        .iter()
        .flat_map(|c| {
            [
                link(
                    format!("{upper}.start_velocity_{c}"),
                    format!("{lower}.end_velocity_{c}"),
                ),
                link(
                    format!("{lower}.end_force_{c}"),
                    format!("{upper}.start_force_{c}"),
                ),
            ]
        })
        .collect()
}
