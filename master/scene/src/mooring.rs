//! `[mooring]`: a body and the 3D lines that hold it, described once and
//! written out as units and connections when the scene is read (as
//! `[structure]` is; `slender expand` prints them).
//!
//! `[mooring.body]` is a `body` unit's parameters and its `name`;
//! `[mooring.line]` the lines' shared model (`kind = "line3d"` and a 3D
//! line's parameters but its ends); each `[[mooring.lines]]` names its
//! fairlead on the body, its anchor, its own changes to the model (`model`),
//! its sections with their fidelities and whether it has a twin, exactly as
//! a 3D `[structure]` (its units are `<line>_<section>`). Each line's upper
//! end moves with its fairlead's velocity and its pull is the fairlead's
//! force, x, y and z (the master iterates them, by Newton on the units'
//! Jacobians when the scene asks); a twin moves with the fairlead and pulls
//! nothing.
//!
//! `mooring.waves` is the sea (a 3D line's `waves` table), given to every
//! line and to the body where it has a force or motion RAO.
//!
//! A line with `break_at` lets go of its fairlead then (its top section's
//! end is released: free, pulling nothing), an accidental limit state.
//!
//! `mooring.body.fmu = { file, start, ... }` puts an external FMU (FMI 2.0
//! or 3.0: slender's own body exported, or another tool's) in the body's
//! place, with the body's ports; the body's parameters then describe it for
//! the statics and the fairleads, and the FMU must start where they put it.
//!
//! With `statics = true` (the default) the body starts at its equilibrium on
//! the lines' catenaries ([`slender_units::body::mooring`]), its
//! `initial_offset` counted from there, and each line solves its statics
//! with its end at the fairlead so placed.

use crate::structure::Layout;
use crate::structure::StructureError;
use crate::structure::{self, Line3dStructure, Link, Parameters, SectionFile, SectionUnit};
use serde::Deserialize;
use slender_units::Time;
use slender_units::body::mooring::{MooredLine, MooringStatics, equilibrium, fairlead_position};
use slender_units::body::{Body, BodyParams};
use slender_units::line3d::catenary_section::CatenarySection;
use slender_units::line3d::params::EndSpec;
use slender_units::line3d::{EndCondition, Line3dParams};
use toml::{Table, Value};

/// `[mooring]` as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MooringFile {
    body: Table,
    line: Table,
    lines: Vec<LineFile>,
    #[serde(default = "yes")]
    statics: bool,
    #[serde(default)]
    waves: Option<Table>,
}

fn yes() -> bool {
    true
}

/// One `[[mooring.lines]]`.
#[derive(Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct LineFile {
    name: String,
    fairlead: String,
    anchor: [f64; 3],
    #[serde(default)]
    model: Table,
    #[serde(default)]
    sections: Vec<SectionFile>,
    #[serde(default)]
    reference: bool,
    /// The time (s) the line breaks at its fairlead.
    #[serde(default)]
    break_at: Option<f64>,
}

/// A mooring system read and checked: the body and its lines.
pub struct Mooring {
    /// The body unit's name.
    pub name: String,
    /// The body's parameters as written.
    pub body: BodyParams,
    /// An external FMU in the body's place (`mooring.body.fmu`: the `fmu`
    /// kind's parameters), the parameters then describing it for the statics.
    fmu: Option<Table>,
    lines: Vec<Line>,
    statics: bool,
}

/// A line of the system.
struct Line {
    file: LineFile,
    /// The index of its fairlead among the body's.
    fairlead: usize,
    /// The line from its anchor (its end placed at the fairlead when the
    /// system is written out), cut into its sections.
    structure: Line3dStructure,
}

impl Mooring {
    /// Reads `[mooring]`; an error names the key.
    pub fn parse(mooring: &Value) -> Result<Mooring, StructureError> {
        let table = mooring.as_table().ok_or("`mooring`: expected a table")?;
        let file: MooringFile = structure::typed("mooring", table)?;
        let mut body_table = file.body.clone();
        let name = match body_table.remove("name") {
            Some(Value::String(name)) => name,
            _ => {
                return Err("`mooring.body.name`: expected the body unit's name (a string)".into());
            }
        };
        if let Some(waves) = &file.waves {
            if body_table.contains_key("force_rao") || body_table.contains_key("motion_rao") {
                body_table.insert("waves".into(), Value::Table(waves.clone()));
            }
        }
        let fmu = match body_table.remove("fmu") {
            None => None,
            Some(Value::Table(t)) => Some(t),
            Some(_) => {
                return Err("`mooring.body.fmu`: expected a table of the `fmu` kind's parameters (`{ file = \"body.fmu\", start = { ... } }`)".into());
            }
        };
        for (key, table) in [("body", &file.body), ("line", &file.line)] {
            if file.waves.is_some() && table.contains_key("waves") {
                return Err(format!(
                    "`mooring.{key}.waves`: the sea is `mooring.waves`, shared by the body and the lines; give it once"
                )
                .into());
            }
        }
        let body: BodyParams = structure::typed("mooring.body", &body_table)?;
        Body::new(body.clone()).map_err(|e| format!("`mooring.body`: {e}"))?;
        if file.lines.is_empty() {
            return Err("`mooring.lines`: expected at least one line".into());
        }
        let mut shared = file.line.clone();
        if let Some(waves) = &file.waves {
            shared.insert("waves".into(), Value::Table(waves.clone()));
        }
        let lines = (file.lines.iter())
            .map(|l| Line::new(l, &shared, &body))
            .collect::<Result<Vec<_>, _>>()?;
        for (k, l) in lines.iter().enumerate() {
            if l.file.name == name || lines[..k].iter().any(|m| m.file.name == l.file.name) {
                return Err(format!(
                    "`mooring.lines[{k}].name` = \"{}\": a name neither the body nor another line has (it prefixes the line's units)",
                    l.file.name
                )
                .into());
            }
        }
        Ok(Mooring {
            name,
            body,
            fmu,
            lines,
            statics: file.statics,
        })
    }

    /// The lines as catenaries from their anchors, for the statics; the
    /// error names the line whose model a catenary cannot stand for.
    pub fn catenaries(&self) -> Result<Vec<MooredLine>, StructureError> {
        (self.lines.iter())
            .map(|l| {
                let mut params = l.structure.params.clone();
                params.end.condition = slender_units::line3d::EndCondition::Fixed;
                let line = CatenarySection::new(params).map_err(|e| {
                    format!(
                        "`mooring.lines.{}`: the system's statics take each line as its elastic catenary: {e} (or set `mooring.statics = false`)",
                        l.file.name
                    )
                })?;
                Ok(MooredLine {
                    fairlead: l.fairlead,
                    line,
                })
            })
            .collect()
    }

    /// The body's equilibrium on its lines.
    pub fn equilibrium(&self) -> Result<MooringStatics, StructureError> {
        self.equilibrium_on(&self.catenaries()?)
    }

    /// The body's equilibrium on `lines` (its [`Mooring::catenaries`]), for
    /// a caller that keeps them for more statics.
    pub fn equilibrium_on(&self, lines: &[MooredLine]) -> Result<MooringStatics, StructureError> {
        equilibrium(&self.body, lines).map_err(|e| format!("`mooring`: {e}").into())
    }

    /// Whether the body starts at its equilibrium (`mooring.statics`).
    pub fn statics(&self) -> bool {
        self.statics
    }

    /// The lines' names and their fairleads' names.
    pub fn line_names(&self) -> Vec<(String, String)> {
        (self.lines.iter())
            .map(|l| (l.file.name.clone(), l.file.fairlead.clone()))
            .collect()
    }

    /// Each line's name and layout (its sections, units and the outputs a
    /// study reads), its fairlead where the body's initial offset puts it.
    pub fn line_layouts(&self) -> Vec<(String, Layout)> {
        (self.lines.iter())
            .map(|l| (l.file.name.clone(), l.structure.layout()))
            .collect()
    }

    /// Writes the system out at `t0`: the body (at its equilibrium with
    /// `statics`), each line as a 3D structure from its anchor to its
    /// fairlead, and the connections between them.
    pub(crate) fn expand(&self, t0: Time) -> Result<structure::Written, StructureError> {
        let mut offset = self.body.initial_offset;
        if self.statics {
            let eq = self.equilibrium()?;
            for (o, e) in offset.iter_mut().zip(eq.offset) {
                *o += e;
            }
        }
        let body = match &self.fmu {
            Some(fmu) => Parameters::Fmu(fmu.clone()),
            None => Parameters::Body(Box::new(BodyParams {
                initial_offset: offset,
                ..self.body.clone()
            })),
        };
        let mut units = vec![SectionUnit::new(self.name.clone(), body)];
        let mut connections = Vec::new();
        let mut advisories = Vec::new();
        for line in &self.lines {
            let at = fairlead_position(&self.body, line.fairlead, &offset);
            let written = line.expand(at, t0)?;
            units.extend(written.units);
            connections.extend(written.connections);
            advisories.extend(written.advisories);
            connections.extend(line.links(&self.name));
        }
        Ok(structure::Written {
            units,
            connections,
            advisories,
        })
    }
}

impl Line {
    /// The line `file` of the shared model `shared` on `body`.
    fn new(file: &LineFile, shared: &Table, body: &BodyParams) -> Result<Line, String> {
        let key = format!("mooring.lines.{}", file.name);
        let fairlead = (body.fairleads.iter())
            .position(|f| f.name == file.fairlead)
            .ok_or_else(|| {
                let names: Vec<&str> = body.fairleads.iter().map(|f| f.name.as_str()).collect();
                format!(
                    "`{key}.fairlead` = \"{}\": one of the body's fairleads ({})",
                    file.fairlead,
                    names.join(", ")
                )
            })?;
        let mut model = shared.clone();
        for (k, v) in &file.model {
            model.insert(k.clone(), v.clone());
        }
        if model.get("kind").and_then(Value::as_str) != Some("line3d") {
            return Err(format!(
                "`{key}`: the lines' model needs `kind = \"line3d\"` (in `mooring.line` or the line's `model`)"
            ));
        }
        for end in ["start", "end"] {
            if model.contains_key(end) {
                return Err(format!(
                    "`{key}.model.{end}`: a mooring line's ends are its `anchor` and its `fairlead`, not given in its model"
                ));
            }
        }
        model.remove("kind");
        // The ends are the anchor and the fairlead: typed with the model
        // and set below (the fairlead's position when it is written out).
        let placeholder = Value::try_from(EndSpec::at([0.0; 3], EndCondition::Fixed))
            .map_err(|e| format!("`{key}`: {e}"))?;
        for end in ["start", "end"] {
            model.insert(end.into(), placeholder.clone());
        }
        let mut params: Line3dParams = structure::typed(&format!("{key}.model"), &model)?;
        params.start = EndSpec::at(file.anchor, EndCondition::Fixed);
        params.end = EndSpec::at([0.0; 3], EndCondition::Velocity);
        let sections = match file.sections.is_empty() {
            true => vec![SectionFile::whole("full")],
            false => file.sections.clone(),
        };
        let structure = Line3dStructure::new(file.name.clone(), params, &sections, file.reference)
            .map_err(|e| e.replace("`structure", &format!("`{key}")))?;
        Ok(Line {
            file: file.clone(),
            fairlead,
            structure,
        })
    }

    /// The line written out with its end at `fairlead` (m), released at
    /// its `break_at`.
    fn expand(&self, fairlead: [f64; 3], t0: Time) -> Result<structure::Written, String> {
        let mut line = self.structure.clone();
        line.params.end = EndSpec {
            released_at: self.file.break_at,
            ..EndSpec::at(fairlead, EndCondition::Velocity)
        };
        let key = format!("`mooring.lines.{}", self.file.name);
        line.write(t0).map_err(|e| e.replace("`structure", &key))
    }

    /// The unit of its top section.
    fn top_unit(&self) -> String {
        self.structure.top_unit()
    }

    /// Its top moves with the fairlead of `body` and pulls it; its twin
    /// moves with it too.
    fn links(&self, body: &str) -> Vec<Link> {
        let f = &self.file.fairlead;
        let top = self.top_unit();
        let mut out = Vec::new();
        for c in ["x", "y", "z"] {
            out.push(Link::new(
                format!("{body}.{f}_velocity_{c}"),
                format!("{top}.end_velocity_{c}"),
            ));
            out.push(Link::new(
                format!("{top}.end_force_{c}"),
                format!("{body}.{f}_force_{c}"),
            ));
            if self.file.reference {
                out.push(Link::new(
                    format!("{body}.{f}_velocity_{c}"),
                    format!(
                        "{}.end_velocity_{c}",
                        structure::reference_name(&self.file.name)
                    ),
                ));
            }
        }
        out
    }
}

/// The scene's `[mooring]` as it runs (with the changes `--set` made)
/// read and checked; None when it has none.
pub fn of_scene(scene: &crate::Scene) -> Result<Option<Mooring>, StructureError> {
    let table = scene.keys().map_err(|e| e.to_string())?;
    table.get("mooring").map(Mooring::parse).transpose()
}
