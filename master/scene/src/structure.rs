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
    let model = structure
        .get("model")
        .and_then(Value::as_table)
        .ok_or("`structure.model`: expected the parameters of a `nonlinear` unit")?
        .clone();
    let segments = segments_of(&model)?;
    let length: f64 = segments.iter().map(|s| s.length).sum();
    let cuts = cuts_of(&structure, length)?;
    let statics = if model.get("static_start").and_then(Value::as_bool) == Some(true) {
        Some(crate::structure_statics::Equilibrium::solve(&model)?)
    } else {
        None
    };
    // At each cut one side moves with the other's velocity and the other carries
    // the force: by default the upper section's end moves and the lower start is
    // loaded (the more robust coupling in the tests); with a static start the
    // other way round, so that in the master's first initial iterate every
    // section hangs from what holds it and its own static solve is well posed.
    let force_on_upper = vec![statics.is_some(); cuts.len().saturating_sub(1)];
    let mut units = Vec::new();
    let mut connections = Vec::new();
    for (k, cut) in cuts.iter().enumerate() {
        // Whether this section's start / end is the moving (velocity) side of its cut.
        let moving_start = k > 0 && force_on_upper[k - 1];
        let moving_end = k + 1 < cuts.len() && !force_on_upper[k];
        let coupling = (
            (k > 0).then_some(moving_start),
            (k + 1 < cuts.len()).then_some(moving_end),
        );
        let mut unit = section_unit(&name, &model, &segments, cut, coupling)?;
        if let Some(equilibrium) = &statics {
            equilibrium.start_section(&mut unit, (cut.from, cut.to), (moving_start, moving_end))?;
        }
        units.push(Value::Table(unit));
        if k + 1 < cuts.len() {
            let (upper, lower) = (
                format!("{name}_{}", cut.name),
                format!("{name}_{}", cuts[k + 1].name),
            );
            connections.extend(cut_connections(&upper, &lower, force_on_upper[k]));
        }
    }
    if structure.get("reference").and_then(Value::as_bool) == Some(true) {
        let mut unit = Table::new();
        unit.insert("name".into(), Value::String(format!("{name}_reference")));
        unit.insert("kind".into(), Value::String("nonlinear".into()));
        unit.insert("parameters".into(), Value::Table(model.clone()));
        units.push(Value::Table(unit));
    }
    append(scene, "units", units)?;
    append(scene, "connections", connections)?;
    Ok(true)
}

/// A straight segment of the stress-free shape.
#[derive(Clone, Debug)]
struct Segment {
    length: f64,
    angle_deg: f64,
    elements: f64,
    table: Table,
}

fn segments_of(model: &Table) -> Result<Vec<Segment>, String> {
    let list = model
        .get("segments")
        .and_then(Value::as_array)
        .ok_or("`structure.model.segments`: expected a list of segments")?;
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
            Ok(Segment {
                length: number("length", None)?,
                angle_deg: number("angle", Some(0.0))?,
                elements: number("elements", None)?,
                table: t.clone(),
            })
        })
        .collect()
}

/// One section: its name, arc-length range and element count (None: as the
/// model's segments).
#[derive(Clone, Debug)]
struct Cut {
    name: String,
    from: f64,
    to: f64,
    elements: Option<usize>,
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
        let fidelity = t
            .get("fidelity")
            .and_then(Value::as_str)
            .unwrap_or("nonlinear");
        if fidelity != "nonlinear" {
            return Err(format!(
                "`{key}.fidelity` = \"{fidelity}\": expected \"nonlinear\" (the other fidelities are not built yet)"
            ));
        }
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
        let elements = match t.get("elements") {
            None => None,
            Some(v) => Some(
                v.as_integer()
                    .filter(|&n| n >= 1)
                    .ok_or(format!("`{key}.elements`: expected a whole number >= 1"))?
                    as usize,
            ),
        };
        cuts.push(Cut {
            name: name.to_owned(),
            from,
            to,
            elements,
        });
        from = to;
    }
    Ok(cuts)
}

/// The `nonlinear` unit of one section: the model's segments clipped to its range,
/// its start at the stress-free position of the cut, the structure's ends at the
/// structure's ends, and at a cut (`coupling`: start, end; None at the
/// structure's ends) a moving end (true) or a loaded one (false).
fn section_unit(
    name: &str,
    model: &Table,
    segments: &[Segment],
    cut: &Cut,
    coupling: (Option<bool>, Option<bool>),
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
    for (key, moving) in [("start", coupling.0), ("end", coupling.1)] {
        match moving {
            Some(true) => ends.insert(key.into(), coupled_motion()),
            Some(false) => ends.insert(key.into(), coupled_load()),
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

/// The loaded side of a cut: the other side's force and moment.
fn coupled_load() -> Value {
    let force = || {
        let mut t = Table::new();
        t.insert("force".into(), Value::String("input".into()));
        Value::Table(t)
    };
    let mut t = Table::new();
    for dof in ["x", "z", "rotation"] {
        t.insert(dof.into(), force());
    }
    Value::Table(t)
}

/// The moving side of a cut: the other side's velocity.
fn coupled_motion() -> Value {
    let mut t = Table::new();
    for dof in ["x", "z", "rotation"] {
        t.insert(dof.into(), Value::String("velocity".into()));
    }
    Value::Table(t)
}

/// The six links of a cut: velocity from the loaded side to the moving side and
/// force back (`force_on_upper`: the upper section's end is the loaded side).
fn cut_connections(upper: &str, lower: &str, force_on_upper: bool) -> Vec<Value> {
    let link = |from: String, to: String| {
        let mut t = Table::new();
        t.insert("from".into(), Value::String(from));
        t.insert("to".into(), Value::String(to));
        Value::Table(t)
    };
    let (loaded, moving) = if force_on_upper {
        (format!("{upper}.end"), format!("{lower}.start"))
    } else {
        (format!("{lower}.start"), format!("{upper}.end"))
    };
    let mut links = Vec::new();
    for (motion, load) in [
        ("velocity_x", "force_x"),
        ("velocity_z", "force_z"),
        ("angular_velocity", "moment"),
    ] {
        links.push(link(
            format!("{loaded}_{motion}"),
            format!("{moving}_{motion}"),
        ));
        links.push(link(format!("{moving}_{load}"), format!("{loaded}_{load}")));
    }
    links
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
