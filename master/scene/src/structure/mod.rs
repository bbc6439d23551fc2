//! `[structure]`: one planar slender structure described once and cut into
//! sections, each its own unit, written out as plain `[[units]]` and
//! `[[connections]]` before the scene is checked (`slender expand` prints the
//! result, so nothing is hidden).
//!
//! The structure is a `nonlinear` section's parameters (`[structure.model]`:
//! segments from the start, ends, environment, integrator). `[[structure.sections]]`
//! cut it by arc length (`to`, m; the last runs to the end), each with a
//! `fidelity` and, optionally, its element count. At a cut the upper section's end
//! follows the lower section's start in velocity (x, z, rotation) and the lower
//! start carries the force and moment the upper end exerts (with `static_start`,
//! the other way round): force and velocity in the global frame, rotation and
//! moment where both sides carry bending. `reference = true` adds the whole structure as one unit
//! (`<name>_reference`), the monolithic twin to measure the sections against.
//!
//! With `static_start`, the whole structure's equilibrium is solved once here;
//! each section starts its own static solve from that shape, and each moving cut
//! end is placed where the equilibrium puts it (`velocity_from`), so the
//! master's initial iterations find the same state.
//!
//! Fidelities today: `nonlinear` (the geometrically nonlinear section at the
//! given element count).

mod cable;
mod cuts;
mod load;
mod statics;

use cuts::{End, Side, coupled_load, coupled_motion};
use toml::{Table, Value};

/// Expands `[structure]` in `scene` into units and connections; false when the
/// scene has none. The error names the key.
pub fn expand(scene: &mut Table) -> Result<bool, String> {
    let Some(structure) = scene.remove("structure") else {
        return Ok(false);
    };
    let structure = structure
        .as_table()
        .ok_or("`structure`: expected a table")?
        .clone();
    let name = structure
        .get("name")
        .and_then(Value::as_str)
        .ok_or("`structure.name`: expected the name the section units start with")?
        .to_owned();
    let mut model = structure
        .get("model")
        .and_then(Value::as_table)
        .ok_or("`structure.model`: expected the parameters of a `nonlinear` unit")?
        .clone();
    let top_load = load::TopLoad::of(&structure, &model)?;
    let statics_model = match &top_load {
        Some(load) => load.held_at_rest(&model),
        None => model.clone(),
    };
    if let Some(load) = &top_load {
        load.take_input(&mut model);
    }
    let segments = segments_of(&model)?;
    let length: f64 = segments.iter().map(|s| s.length).sum();
    let cuts = cuts_of(&structure, length)?;
    let statics = if model.get("static_start").and_then(Value::as_bool) == Some(true) {
        Some(statics::Equilibrium::solve(&statics_model)?)
    } else {
        None
    };
    let built = Built {
        water: cable::Water::of(&structure)?,
        name,
        model,
        segments,
        statics,
        top_load,
    };
    // At each cut one side moves with the other's velocity and the other carries
    // the force: by default the upper section's end moves and the lower start is
    // loaded (the more robust coupling in the tests); with a static start the
    // other way round, so that in the master's first initial iterate every
    // section hangs from what holds it and its own static solve is well posed.
    // A cable's top takes force and its bottom velocity: its cuts are always
    // the second way round.
    let force_on_upper: Vec<bool> = cuts
        .windows(2)
        .map(|w| built.statics.is_some() || w.iter().any(|c| c.fidelity == Fidelity::Cable))
        .collect();
    let mut units = Vec::new();
    let mut connections = Vec::new();
    for k in 0..cuts.len() {
        units.push(Value::Table(built.section(&cuts, k, &force_on_upper)?));
        if k + 1 < cuts.len() {
            let (links, artefacts) = cuts::cut_connections(
                &built.side(&cuts[k]),
                &built.side(&cuts[k + 1]),
                force_on_upper[k],
            )?;
            connections.extend(links);
            units.extend(artefacts);
        }
    }
    if let (Some(load), Some(last)) = (&built.top_load, cuts.last()) {
        connections.extend(load.links(&built.side(last).unit, last.fidelity));
    }
    if let Some((unit, fidelity)) = built.reference(&structure, length)? {
        if let Some(load) = &built.top_load {
            connections.extend(load.links(&format!("{}_reference", built.name), fidelity));
        }
        units.push(Value::Table(unit));
    }
    append(scene, "units", units)?;
    append(scene, "connections", connections)?;
    Ok(true)
}

/// What every section is built from.
struct Built {
    name: String,
    /// The model as the units take it (a top load as a coupled input).
    model: Table,
    segments: Vec<Segment>,
    statics: Option<statics::Equilibrium>,
    water: Option<cable::Water>,
    top_load: Option<load::TopLoad>,
}

impl Built {
    /// Section `k`'s unit.
    fn section(&self, cuts: &[Cut], k: usize, force_on_upper: &[bool]) -> Result<Table, String> {
        let cut = &cuts[k];
        // Per end at a cut: whether this section is the moving (velocity) side,
        // and whether the cut is pinned (a side without bending).
        let start = (k > 0).then(|| End {
            moving: force_on_upper[k - 1],
            pinned: !cuts[k - 1].fidelity.bends() || !cut.fidelity.bends(),
        });
        let end = (k + 1 < cuts.len()).then(|| End {
            moving: !force_on_upper[k],
            pinned: !cuts[k + 1].fidelity.bends() || !cut.fidelity.bends(),
        });
        let mut unit = match cut.fidelity {
            Fidelity::Nonlinear => {
                let mut unit =
                    section_unit(&self.name, &self.model, &self.segments, cut, (start, end))?;
                if let Some(equilibrium) = &self.statics {
                    equilibrium.start_section(&mut unit, (cut.from, cut.to))?;
                    let loaded = (
                        start.is_some_and(|e| !e.moving),
                        end.is_some_and(|e| !e.moving),
                    );
                    equilibrium.first_guess_loads(&mut unit, (cut.from, cut.to), loaded);
                }
                unit
            }
            Fidelity::Cable => {
                cable_fits(&self.model, cuts, k, self.top_load.is_some())?;
                let anchor = self.statics.as_ref().map(|e| e.position_at(cut.from)).ok_or(format!(
                    "`structure.sections.{}.fidelity` = \"cable\": a cable section takes its static state from its top force, so the structure needs `structure.model.static_start = true` to place it",
                    cut.name
                ))?;
                let mut unit = cable::cable_unit(
                    &self.name,
                    &self.model,
                    &self.segments,
                    cut,
                    self.water,
                    anchor,
                )?;
                // Its static state needs the force at its top in the master's
                // first initial iterate: the equilibrium's, as the first guess.
                if let (Some(e), true) = (&self.statics, k + 1 < cuts.len()) {
                    statics::first_guess_force(&mut unit, "top", e.force_at(cut.to));
                }
                unit
            }
        };
        if let (Some(load), true) = (&self.top_load, k + 1 == cuts.len()) {
            load.first_guess(&mut unit, cut.fidelity);
        }
        Ok(unit)
    }

    /// How a cut sees a section.
    fn side<'a>(&self, cut: &'a Cut) -> Side<'a> {
        Side {
            unit: format!("{}_{}", self.name, cut.name),
            fidelity: cut.fidelity,
            physical: cut.physical.as_ref(),
        }
    }

    /// The monolithic twin `<name>_reference` (`reference = true` or
    /// "nonlinear": the model as one unit; "cable": the whole structure as one
    /// cable) and its fidelity; None without one.
    fn reference(
        &self,
        structure: &Table,
        length: f64,
    ) -> Result<Option<(Table, Fidelity)>, String> {
        let fidelity = match structure.get("reference") {
            None | Some(Value::Boolean(false)) => return Ok(None),
            Some(Value::Boolean(true)) => Fidelity::Nonlinear,
            Some(Value::String(word)) => Fidelity::parse("structure.reference", word)?,
            Some(other) => {
                return Err(format!(
                    "`structure.reference` = {other}: expected true, false or a fidelity ({})",
                    Fidelity::NAMES.join(", ")
                ));
            }
        };
        let mut unit = match fidelity {
            Fidelity::Nonlinear => {
                let mut unit = Table::new();
                unit.insert(
                    "name".into(),
                    Value::String(format!("{}_reference", self.name)),
                );
                unit.insert("kind".into(), Value::String("nonlinear".into()));
                unit.insert("parameters".into(), Value::Table(self.model.clone()));
                unit
            }
            Fidelity::Cable => {
                let whole = [Cut {
                    name: "reference".into(),
                    from: 0.0,
                    to: length,
                    fidelity,
                    elements: None,
                    physical: None,
                }];
                cable_fits(&self.model, &whole, 0, self.top_load.is_some())?;
                let start = start_of(&self.model);
                cable::cable_unit(
                    &self.name,
                    &self.model,
                    &self.segments,
                    &whole[0],
                    self.water,
                    start,
                )?
            }
        };
        if let Some(load) = &self.top_load {
            load.first_guess(&mut unit, fidelity);
        }
        Ok(Some((unit, fidelity)))
    }
}

/// A straight segment of the stress-free shape.
#[derive(Clone, Debug)]
pub(crate) struct Segment {
    /// Arc length of its start (m).
    pub from: f64,
    pub length: f64,
    angle_deg: f64,
    pub elements: f64,
    /// The segment as written (its section properties).
    pub table: Table,
}

impl Segment {
    /// Length (m) of the segment inside [from, to].
    pub fn overlap(&self, from: f64, to: f64) -> f64 {
        ((self.from + self.length).min(to) - self.from.max(from)).max(0.0)
    }
}

fn segments_of(model: &Table) -> Result<Vec<Segment>, String> {
    let list = model
        .get("segments")
        .and_then(Value::as_array)
        .ok_or("`structure.model.segments`: expected a list of segments")?;
    let mut from = 0.0;
    list.iter()
        .enumerate()
        .map(|(i, s)| {
            let t = s
                .as_table()
                .ok_or(format!("`structure.model.segments[{i}]`: expected a table"))?;
            let number = |key: &str, default: Option<f64>| {
                t.get(key)
                    .and_then(|v| v.as_float().or_else(|| v.as_integer().map(|i| i as f64)))
                    .or(default)
                    .ok_or(format!(
                        "`structure.model.segments[{i}].{key}`: expected a number"
                    ))
            };
            let segment = Segment {
                from,
                length: number("length", None)?,
                angle_deg: number("angle", Some(0.0))?,
                elements: number("elements", None)?,
                table: t.clone(),
            };
            from += segment.length;
            Ok(segment)
        })
        .collect()
}

/// One section: its name, arc-length range (m), fidelity and element count
/// (None: as the model's segments).
#[derive(Clone, Debug)]
pub(crate) struct Cut {
    pub name: String,
    pub from: f64,
    pub to: f64,
    pub fidelity: Fidelity,
    pub elements: Option<usize>,
    /// A physical section's artefacts (`sensor`, `actuator`).
    pub physical: Option<Table>,
}

/// The fidelities a section can take, as written in scenes.
pub const FIDELITIES: [&str; 2] = Fidelity::NAMES;

/// Which model a section is.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum Fidelity {
    /// The geometrically nonlinear section (`nonlinear` unit).
    Nonlinear,
    /// Seed 000's cable, linear about its static state, no bending (`cable` unit).
    Cable,
}

impl Fidelity {
    /// The fidelities' names as written in scenes.
    pub const NAMES: [&'static str; 2] = ["nonlinear", "cable"];

    fn parse(key: &str, word: &str) -> Result<Fidelity, String> {
        match word {
            "nonlinear" => Ok(Fidelity::Nonlinear),
            "cable" => Ok(Fidelity::Cable),
            other => Err(format!(
                "`{key}` = \"{other}\": expected one of {} (the other fidelities are not built yet)",
                Fidelity::NAMES.join(", ")
            )),
        }
    }

    /// Whether the model carries bending (rotation and moment at its cuts).
    fn bends(self) -> bool {
        self == Fidelity::Nonlinear
    }
}

fn cuts_of(structure: &Table, length: f64) -> Result<Vec<Cut>, String> {
    let list = structure
        .get("sections")
        .and_then(Value::as_array)
        .filter(|l| !l.is_empty())
        .ok_or("`structure.sections`: expected at least one section")?;
    let mut cuts = Vec::new();
    let mut from = 0.0;
    for (i, s) in list.iter().enumerate() {
        let key = format!("structure.sections[{i}]");
        let t = s.as_table().ok_or(format!("`{key}`: expected a table"))?;
        let name = t
            .get("name")
            .and_then(Value::as_str)
            .ok_or(format!("`{key}.name`: expected a name"))?;
        let (fidelity, fidelity_elements) = fidelity_of(&key, t.get("fidelity"))?;
        let last = i + 1 == list.len();
        let to = match t
            .get("to")
            .and_then(|v| v.as_float().or_else(|| v.as_integer().map(|i| i as f64)))
        {
            Some(to) if !last && to > from && to < length => to,
            None if last => length,
            Some(to) if last && (to - length).abs() <= 1e-9 * length => length,
            other => {
                return Err(format!(
                    "`{key}.to` = {other:?}: expected an arc length in ({from}, {length}) m, increasing, and none (or the length) for the last section"
                ));
            }
        };
        let elements = match (t.get("elements"), fidelity_elements) {
            (None, elements) => elements,
            (Some(v), None) => Some(whole(&format!("{key}.elements"), v)?),
            (Some(_), Some(_)) => {
                return Err(format!(
                    "`{key}`: the element count is given twice (`elements` and `fidelity.elements`)"
                ));
            }
        };
        let physical = match t.get("physical") {
            None => None,
            Some(Value::Table(p)) => Some(p.clone()),
            Some(_) => {
                return Err(format!(
                    "`{key}.physical`: expected a table {{ sensor = {{ ... }}, actuator = {{ ... }} }} of `artefact` parameters"
                ));
            }
        };
        cuts.push(Cut {
            name: name.to_owned(),
            from,
            to,
            fidelity,
            elements,
            physical,
        });
        from = to;
    }
    Ok(cuts)
}

/// Whether section `k` can be a cable: its top takes a coupled force, so it
/// cannot end the structure, and its bottom a coupled velocity, so at the
/// structure's start it must be anchored (x and z held).
fn cable_fits(model: &Table, cuts: &[Cut], k: usize, top_load: bool) -> Result<(), String> {
    let key = format!("structure.sections.{}.fidelity", cuts[k].name);
    if k + 1 == cuts.len() && !top_load {
        return Err(format!(
            "`{key}` = \"cable\": the cable's top takes a coupled force, so a cable can be the structure's last section only under `structure.top_load`; otherwise give the end to a nonlinear section"
        ));
    }
    if k == 0 {
        let start = model
            .get("ends")
            .and_then(|e| e.get("start"))
            .and_then(Value::as_table);
        let word = |k: &str| start.and_then(|s| s.get(k)).and_then(Value::as_str);
        let anchored = matches!(word("kind"), Some("fixed" | "pinned"))
            || (word("x") == Some("held") && word("z") == Some("held"));
        if !anchored {
            return Err(format!(
                "`{key}` = \"cable\": a cable at the structure's start needs an anchor there (`structure.model.ends.start`: kind \"pinned\" or \"fixed\")"
            ));
        }
    }
    Ok(())
}

/// A section's `fidelity`: a name, or a table `{ kind = NAME, elements = N }`
/// (default: nonlinear).
fn fidelity_of(key: &str, value: Option<&Value>) -> Result<(Fidelity, Option<usize>), String> {
    let key = format!("{key}.fidelity");
    match value {
        None => Ok((Fidelity::Nonlinear, None)),
        Some(Value::String(word)) => Ok((Fidelity::parse(&key, word)?, None)),
        Some(Value::Table(t)) => {
            if let Some(unknown) = t.keys().find(|k| *k != "kind" && *k != "elements") {
                return Err(format!(
                    "`{key}.{unknown}`: unknown key; expected `kind` and optionally `elements`"
                ));
            }
            let word = t.get("kind").and_then(Value::as_str).ok_or(format!(
                "`{key}.kind`: expected one of {}",
                Fidelity::NAMES.join(", ")
            ))?;
            let elements = t
                .get("elements")
                .map(|v| whole(&format!("{key}.elements"), v))
                .transpose()?;
            Ok((Fidelity::parse(&format!("{key}.kind"), word)?, elements))
        }
        Some(_) => Err(format!(
            "`{key}`: expected a name ({}) or a table {{ kind, elements }}",
            Fidelity::NAMES.join(", ")
        )),
    }
}

/// A whole number >= 1 at `key`.
fn whole(key: &str, v: &Value) -> Result<usize, String> {
    v.as_integer()
        .filter(|&n| n >= 1)
        .map(|n| n as usize)
        .ok_or(format!("`{key}`: expected a whole number >= 1"))
}

/// The `nonlinear` unit of one section: the model's segments clipped to its range,
/// its start at the stress-free position of the cut, the structure's ends at the
/// structure's ends, and at a cut (`coupling`: start, end; None at the
/// structure's ends) a moving or loaded end.
fn section_unit(
    name: &str,
    model: &Table,
    segments: &[Segment],
    cut: &Cut,
    coupling: (Option<End>, Option<End>),
) -> Result<Table, String> {
    let mut parameters = model.clone();
    let (mut position, mut arc) = (start_of(model), 0.0f64);
    let mut clipped = Vec::new();
    let mut start = None;
    for s in segments {
        let (a, b) = (arc.max(cut.from), (arc + s.length).min(cut.to));
        let (c, sn) = (
            s.angle_deg.to_radians().cos(),
            s.angle_deg.to_radians().sin(),
        );
        if b > a + 1e-12 * s.length {
            if start.is_none() {
                let d = cut.from - arc;
                start = Some([position[0] + d * c, position[1] + d * sn]);
            }
            let mut t = s.table.clone();
            let share = (b - a) / s.length;
            t.insert("length".into(), Value::Float(b - a));
            let elements = (s.elements * share).round().max(1.0);
            t.insert("elements".into(), Value::Integer(elements as i64));
            clipped.push(t);
        }
        position = [position[0] + s.length * c, position[1] + s.length * sn];
        arc += s.length;
    }
    if let Some(n) = cut.elements {
        distribute(&mut clipped, n);
    }
    let start = start.ok_or(format!("section `{}` is empty", cut.name))?;
    parameters.insert(
        "start".into(),
        Value::Array(vec![Value::Float(start[0]), Value::Float(start[1])]),
    );
    parameters.insert(
        "segments".into(),
        Value::Array(clipped.into_iter().map(Value::Table).collect()),
    );
    for key in ["supports", "loads", "stations"] {
        if parameters.contains_key(key) {
            return Err(format!(
                "`structure.model.{key}`: not yet available for a cut structure"
            ));
        }
    }
    let mut ends = model
        .get("ends")
        .and_then(Value::as_table)
        .cloned()
        .unwrap_or_default();
    for (key, coupled) in [("start", coupling.0), ("end", coupling.1)] {
        match coupled {
            Some(End {
                moving: true,
                pinned,
            }) => ends.insert(key.into(), coupled_motion(pinned)),
            Some(End {
                moving: false,
                pinned,
            }) => ends.insert(key.into(), coupled_load(pinned)),
            None => None,
        };
    }
    parameters.insert("ends".into(), Value::Table(ends));
    let mut unit = Table::new();
    unit.insert("name".into(), Value::String(format!("{name}_{}", cut.name)));
    unit.insert("kind".into(), Value::String("nonlinear".into()));
    unit.insert("parameters".into(), Value::Table(parameters));
    Ok(unit)
}

fn start_of(model: &Table) -> [f64; 2] {
    let at = |i: usize| {
        model
            .get("start")
            .and_then(Value::as_array)
            .and_then(|a| a.get(i))
            .and_then(|v| v.as_float().or_else(|| v.as_integer().map(|i| i as f64)))
            .unwrap_or(0.0)
    };
    [at(0), at(1)]
}

/// Spreads `n` elements over the clipped segments in proportion to their lengths
/// (at least one each).
fn distribute(segments: &mut [Table], n: usize) {
    let lengths: Vec<f64> = segments
        .iter()
        .map(|t| t["length"].as_float().unwrap_or(0.0))
        .collect();
    let total: f64 = lengths.iter().sum();
    for (t, l) in segments.iter_mut().zip(&lengths) {
        let e = ((n as f64) * l / total).round().max(1.0);
        t.insert("elements".into(), Value::Integer(e as i64));
    }
}

fn append(scene: &mut Table, key: &str, items: Vec<Value>) -> Result<(), String> {
    let list = scene
        .entry(key.to_owned())
        .or_insert_with(|| Value::Array(Vec::new()))
        .as_array_mut()
        .ok_or(format!("`{key}`: expected a list"))?;
    list.extend(items);
    Ok(())
}
