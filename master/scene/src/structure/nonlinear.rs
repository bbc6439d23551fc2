//! The `nonlinear` and `linear` fidelities of a section: the model's own
//! unit over the section's arc-length range, coupled at its cuts (`linear`:
//! stepped linearised about its start, `linear = true`).

use super::Built;
use super::cuts::{End, coupled_displacement, coupled_load, coupled_motion};
use super::layout::SectionOutputs;
use super::model::{SectionAt, SectionModel, outputs_of};
use super::sections::{Cut, Fidelity, Segment};
use toml::{Table, Value};

/// The `nonlinear` fidelity (the geometrically nonlinear unit) and, with
/// `linear`, the `linear` one (that unit linearised about its start).
pub(super) struct Section {
    linear: bool,
}

/// The `nonlinear` fidelity.
pub(super) const NONLINEAR: Section = Section { linear: false };

/// The `linear` fidelity.
pub(super) const LINEAR: Section = Section { linear: true };

/// The `nonlinear` unit's outputs: end forces, the touchdown point
/// interpolated where the seabed gap closes (`touchdown_arc`), sag-bend and
/// overbend moments, and stations (not through an FMU, whose outputs are
/// fixed when it is exported).
pub(super) fn section_outputs(fmu: bool, seabed: bool, stinger: bool) -> SectionOutputs {
    let ends = ["start", "end"];
    let mut outputs = outputs_of(ends, false, Some("touchdown_arc"), true, (seabed, stinger));
    outputs.stations = !fmu;
    outputs
}

impl SectionModel for Section {
    fn name(&self) -> &'static str {
        if self.linear { "linear" } else { "nonlinear" }
    }
    fn is_section_unit(&self) -> bool {
        true
    }
    fn outputs(&self, fmu: bool, seabed: bool, stinger: bool, _: bool) -> SectionOutputs {
        section_outputs(fmu, seabed, stinger)
    }
    fn unit(&self, at: &SectionAt) -> Result<Table, String> {
        at.built.section_unit(at.cut(), at.ends)
    }
    /// A linear section cannot follow a stinger's moving rollers.
    fn refuse(&self, built: &Built, cut: &Cut) -> Result<(), String> {
        match self.linear {
            true => built.refuse_linear_on_stinger(cut),
            false => Ok(()),
        }
    }
    fn contact_state_kept(&self) -> Option<&'static str> {
        (self.linear).then_some(
            "a linear section cannot follow: it keeps the seabed as springs where it lay",
        )
    }
}

/// The `nonlinear` unit of one section: the model's segments clipped to its range,
/// its start at the stress-free position of the cut, the structure's ends at the
/// structure's ends, and at a cut (`coupling`: start, end; None at the
/// structure's ends) a moving or loaded end.
pub(super) fn section_unit(
    name: &str,
    model: &Table,
    segments: &[Segment],
    cut: &Cut,
    coupling: (Option<End>, Option<End>),
) -> Result<Table, String> {
    let mut parameters = model.clone();
    let (mut position, mut arc) = (start_of(model), 0.0f64);
    let mut clipped = Vec::new();
    // The model's own (unrounded) element count on each clipped segment.
    let mut density = Vec::new();
    let mut start = None;
    for s in segments {
        let (c, sn) = (
            s.angle_deg.to_radians().cos(),
            s.angle_deg.to_radians().sin(),
        );
        if let Some(elements) = s.elements_over(cut.from, cut.to) {
            if start.is_none() {
                let d = cut.from - arc;
                start = Some([position[0] + d * c, position[1] + d * sn]);
            }
            let mut t = s.table.clone();
            let length = s.overlap(cut.from, cut.to);
            let share = length / s.length;
            t.insert("length".into(), Value::Float(length));
            t.insert("elements".into(), Value::Integer(elements as i64));
            clipped.push(t);
            density.push(s.elements * share);
        }
        position = [position[0] + s.length * c, position[1] + s.length * sn];
        arc += s.length;
    }
    if let Some(n) = cut.elements {
        distribute(&mut clipped, &density, n);
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
    let length = segments.iter().map(|s| s.length).sum();
    for (key, list) in along(model, cut, length)? {
        match list.is_empty() {
            true => parameters.remove(key),
            false => parameters.insert(key.into(), Value::Array(list)),
        };
    }
    let ends = coupled_ends(model, coupling);
    parameters.insert("ends".into(), Value::Table(ends));
    let mut unit = Table::new();
    unit.insert(
        "name".into(),
        Value::String(super::unit_name(name, &cut.name)),
    );
    unit.insert("kind".into(), Value::String("nonlinear".into()));
    unit.insert("parameters".into(), Value::Table(parameters));
    Ok(unit)
}

/// The model's ends with the section's cuts in their place: a moving end (by
/// velocity, or by displacement next to a chord section) or a loaded one.
fn coupled_ends(model: &Table, coupling: (Option<End>, Option<End>)) -> Table {
    let mut ends = model
        .get("ends")
        .and_then(Value::as_table)
        .cloned()
        .unwrap_or_default();
    for (key, coupled) in [("start", coupling.0), ("end", coupling.1)] {
        match coupled {
            Some(End {
                moving: true,
                by_displacement: true,
                ..
            }) => ends.insert(key.into(), coupled_displacement()),
            Some(End {
                moving: true,
                pinned,
                ..
            }) => ends.insert(key.into(), coupled_motion(pinned)),
            Some(End {
                moving: false,
                pinned,
                ..
            }) => ends.insert(key.into(), coupled_load(pinned)),
            None => None,
        };
    }
    ends
}

/// The model's `supports`, `loads` and `stations` that fall inside the section,
/// in the section's own arc length (m from its start): a load clipped to it, a
/// station in [from, to) (the last section keeps its end). A support at a cut
/// is refused: the cut's coupling moves or loads that node.
pub(super) fn along(
    model: &Table,
    cut: &Cut,
    length: f64,
) -> Result<[(&'static str, Vec<Value>); 3], String> {
    let tolerance = 1e-9 * length;
    let number = |v: Option<&Value>| {
        v.and_then(|v| v.as_float().or_else(|| v.as_integer().map(|i| i as f64)))
    };
    let list = |key: &str| {
        model
            .get(key)
            .and_then(Value::as_array)
            .cloned()
            .unwrap_or_default()
    };
    let last = cut.to >= length - tolerance;
    let mut supports = Vec::new();
    for (i, support) in list("supports").into_iter().enumerate() {
        let at = number(support.get("at")).ok_or(format!(
            "`structure.model.supports[{i}].at`: expected an arc length (m)"
        ))?;
        let at_cut =
            |c: f64| c > tolerance && c < length - tolerance && (at - c).abs() <= tolerance;
        if at_cut(cut.from) || at_cut(cut.to) {
            return Err(format!(
                "`structure.model.supports[{i}].at` = {at}: a support at the cut of section `{}`; move the cut or the support",
                cut.name
            ));
        }
        if at > cut.from - tolerance && at < cut.to + tolerance {
            supports.push(shifted(support, "at", at - cut.from));
        }
    }
    let mut loads = Vec::new();
    for load in list("loads") {
        let from = number(load.get("from")).unwrap_or(0.0).max(cut.from);
        let to = number(load.get("to")).unwrap_or(f64::INFINITY).min(cut.to);
        if to > from + tolerance {
            let clipped = shifted(load, "from", from - cut.from);
            loads.push(shifted(clipped, "to", to - cut.from));
        }
    }
    let stations = list("stations")
        .into_iter()
        .filter_map(|v| number(Some(&v)))
        .filter(|&s| s >= cut.from - tolerance && (s < cut.to - tolerance || last))
        .map(|s| Value::Float((s - cut.from).max(0.0)))
        .collect();
    Ok([
        ("supports", supports),
        ("loads", loads),
        ("stations", stations),
    ])
}

/// `table` with `key` set to `value`.
fn shifted(mut table: Value, key: &str, value: f64) -> Value {
    if let Some(t) = table.as_table_mut() {
        t.insert(key.into(), Value::Float(value));
    }
    table
}

pub(super) fn start_of(model: &Table) -> [f64; 2] {
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

/// Spreads `n` elements over the clipped segments in proportion to the
/// model's own counts there (`weights`), so a graded mesh stays graded (a
/// uniform one: in proportion to the lengths); at least one each, the
/// remainders to the largest fractions, so they sum to `n` where `n` is at
/// least the number of segments.
fn distribute(segments: &mut [Table], weights: &[f64], n: usize) {
    let total: f64 = weights.iter().sum();
    let shares: Vec<f64> = weights.iter().map(|w| n as f64 * w / total).collect();
    let mut counts: Vec<usize> = shares.iter().map(|s| (s.floor() as usize).max(1)).collect();
    let mut order: Vec<usize> = (0..shares.len()).collect();
    order.sort_by(|&a, &b| {
        (shares[b] - shares[b].floor()).total_cmp(&(shares[a] - shares[a].floor()))
    });
    let mut left = n.saturating_sub(counts.iter().sum());
    // The fractions sum to less than the number of segments: one pass.
    for &k in &order {
        if left == 0 {
            break;
        }
        counts[k] += 1;
        left -= 1;
    }
    for (t, e) in segments.iter_mut().zip(counts) {
        t.insert("elements".into(), Value::Integer(e as i64));
    }
}

impl super::Built {
    /// A `nonlinear` or `linear` section's unit, started from the
    /// equilibrium where there is one.
    pub(super) fn section_unit(
        &self,
        cut: &Cut,
        (start, end): (Option<End>, Option<End>),
    ) -> Result<Table, String> {
        let mut unit = section_unit(&self.name, &self.model, &self.segments, cut, (start, end))?;
        if cut.fidelity == Fidelity::Linear {
            if let Some(Value::Table(parameters)) = unit.get_mut("parameters") {
                parameters.insert("linear".into(), Value::Boolean(true));
            }
        }
        if let Some(equilibrium) = &self.statics {
            equilibrium.start_section(&mut unit, (cut.from, cut.to))?;
            let loaded = (
                start.is_some_and(|e| !e.moving),
                end.is_some_and(|e| !e.moving),
            );
            equilibrium.first_guess_loads(&mut unit, (cut.from, cut.to), loaded);
        }
        Ok(unit)
    }
}
