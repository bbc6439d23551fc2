//! Envelopes along the line (issue 50): over the window a scene asks for
//! (`[output] envelopes = { from = S }`), the smallest, largest and mean value
//! of each unit's tension, curvature and bending moment at every node or
//! element, from the units' fields, against the arc length along the unit
//! (from its start, measured on its positions at the run's start: its static
//! shape). The buffers are made once, at the first observation; each step
//! only reads the fields into them.

use crate::plot::{Curve, PlotError, Profile};
use serde::Serialize;
use slender_coupling::coupler::Master;
use std::path::{Path, PathBuf};

/// The fields an envelope is kept of (by their names in `Unit::fields`).
const ENVELOPED: [&str; 3] = ["tension", "curvature", "moment"];

/// One field of one unit over the window.
#[derive(Clone, Debug, Serialize)]
pub struct Envelope {
    /// The unit whose field it is.
    pub unit: String,
    /// The field (e.g. `tension`).
    pub field: String,
    /// The field's unit of measure.
    pub unit_of_measure: String,
    /// The arc length (m) of each value from the unit's start: a node's, or
    /// an element's midpoint.
    pub arc: Vec<f64>,
    /// Smallest value at each point over the window.
    pub min: Vec<f64>,
    /// Largest value at each point.
    pub max: Vec<f64>,
    /// Mean value at each point.
    pub mean: Vec<f64>,
    /// The steps averaged.
    pub samples: usize,
}

/// A field being enveloped: where it is read from, and its buffers.
struct Track {
    unit: usize,
    field: usize,
    envelope: Envelope,
    values: Vec<f64>,
    sum: Vec<f64>,
}

/// The envelopes of every enveloped field of a master's units, observed
/// from `from` (s) on.
pub struct Envelopes {
    from: f64,
    /// Made at the first observation (the run's start).
    tracks: Option<Vec<Track>>,
}

impl Envelopes {
    /// Envelopes from `from` (s) on.
    pub fn new(from: f64) -> Envelopes {
        Envelopes { from, tracks: None }
    }

    /// The fields to envelope and their arc lengths (after `initialize`).
    fn tracks(master: &Master) -> Vec<Track> {
        let mut tracks = Vec::new();
        for (u, name) in master.unit_names().enumerate() {
            let fields = master.fields(u);
            let arc = node_arc(master, u, &fields);
            for (k, f) in fields.iter().enumerate() {
                if !ENVELOPED.contains(&f.name.as_str()) || f.len == 0 {
                    continue;
                }
                let arc = match &arc {
                    Some(nodes) if nodes.len() == f.len => nodes.clone(),
                    Some(nodes) if nodes.len() == f.len + 1 => {
                        nodes.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect()
                    }
                    _ => (0..f.len).map(|i| i as f64).collect(),
                };
                tracks.push(Track {
                    unit: u,
                    field: k,
                    envelope: Envelope {
                        unit: name.to_owned(),
                        field: f.name.clone(),
                        unit_of_measure: f.unit.clone(),
                        arc,
                        min: vec![f64::INFINITY; f.len],
                        max: vec![f64::NEG_INFINITY; f.len],
                        mean: vec![0.0; f.len],
                        samples: 0,
                    },
                    values: vec![0.0; f.len],
                    sum: vec![0.0; f.len],
                });
            }
        }
        tracks
    }

    /// Reads every tracked field at time `t` (s), when in the window.
    pub fn observe(&mut self, master: &Master, t: f64) {
        let tracks = self.tracks.get_or_insert_with(|| Self::tracks(master));
        if t < self.from {
            return;
        }
        for track in tracks {
            if master
                .field_values(track.unit, track.field, &mut track.values)
                .is_err()
            {
                continue;
            }
            let e = &mut track.envelope;
            for (i, &v) in track.values.iter().enumerate() {
                e.min[i] = e.min[i].min(v);
                e.max[i] = e.max[i].max(v);
                track.sum[i] += v;
            }
            e.samples += 1;
        }
    }

    /// The envelopes (the means divided out); none without samples.
    pub fn finish(self) -> Vec<Envelope> {
        (self.tracks.unwrap_or_default().into_iter())
            .filter(|t| t.envelope.samples > 0)
            .map(|mut t| {
                let n = t.envelope.samples as f64;
                t.envelope.mean = t.sum.iter().map(|s| s / n).collect();
                t.envelope
            })
            .collect()
    }
}

/// The arc length (m) of each node of unit `u` from its start, from its
/// position fields (`x`, `y`, `z`) now; None without them.
fn node_arc(
    master: &Master,
    u: usize,
    fields: &[slender_units::contract::Field],
) -> Option<Vec<f64>> {
    let axes: Vec<usize> = ["x", "y", "z"]
        .iter()
        .filter_map(|a| fields.iter().position(|f| f.name == *a))
        .collect();
    let len = fields.get(*axes.first()?)?.len;
    let mut positions = vec![vec![0.0; len]; axes.len()];
    for (a, &k) in axes.iter().enumerate() {
        master.field_values(u, k, &mut positions[a]).ok()?;
    }
    let mut arc = vec![0.0; len];
    for i in 1..len {
        let step: f64 = (positions.iter())
            .map(|p| (p[i] - p[i - 1]).powi(2))
            .sum::<f64>()
            .sqrt();
        arc[i] = arc[i - 1] + step;
    }
    Some(arc)
}

/// What `summary.json` says of an envelope: its extremes and where they are.
#[derive(Clone, Debug, Serialize)]
pub struct EnvelopeExtremes {
    /// The unit whose field it is.
    pub unit: String,
    /// The field.
    pub field: String,
    /// The field's unit of measure.
    pub unit_of_measure: String,
    /// The largest value anywhere along the unit over the window.
    pub max: f64,
    /// Where (m of arc from the unit's start).
    pub max_arc_m: f64,
    /// Smallest value anywhere over the window.
    pub min: f64,
    /// Where (m of arc from the unit's start).
    pub min_arc_m: f64,
    /// How many recorded steps the envelope is over.
    pub samples: usize,
}

impl Envelope {
    /// The envelope's largest and smallest values and where they are.
    pub fn extremes(&self) -> EnvelopeExtremes {
        let at = |values: &[f64], better: fn(f64, f64) -> bool| {
            (values.iter().enumerate()).fold((f64::NAN, f64::NAN), |(v, a), (i, &x)| {
                if v.is_nan() || better(x, v) {
                    (x, self.arc[i])
                } else {
                    (v, a)
                }
            })
        };
        let (max, max_arc_m) = at(&self.max, |x, v| x > v);
        let (min, min_arc_m) = at(&self.min, |x, v| x < v);
        EnvelopeExtremes {
            unit: self.unit.clone(),
            field: self.field.clone(),
            unit_of_measure: self.unit_of_measure.clone(),
            max,
            max_arc_m,
            min,
            min_arc_m,
            samples: self.samples,
        }
    }
}

/// Moves each structure section's arcs onto its structure's (its start
/// added), so that they line up with the twin's.
pub fn place(envelopes: &mut [Envelope], structures: &[Structure]) {
    let starts = structures.iter().flat_map(|s| &s.sections);
    for e in envelopes {
        if let Some((_, from)) = starts.clone().find(|(unit, _)| *unit == e.unit) {
            e.arc.iter_mut().for_each(|a| *a += from);
        }
    }
}

/// A structure cut into sections (`Scene::sectioned_structures`): a
/// `[structure]`, or a line of a `[mooring]`.
pub type Structure = slender_scene::analysis::SectionedStructure;

/// A structure's sections' envelope of one field joined along the structure:
/// the field and, per run of consecutive sections that have it, arc, min and
/// max (a section without the field, a `static` one, breaks the curve).
type Joined = (String, Vec<[Vec<f64>; 3]>);

/// The envelope of `unit`'s `field`, if it has one.
fn envelope_of<'a>(envelopes: &'a [Envelope], unit: &str, field: &str) -> Option<&'a Envelope> {
    envelopes
        .iter()
        .find(|e| e.unit == unit && e.field == field)
}

/// Per enveloped field, the sections' envelopes of it joined in order.
fn joined(envelopes: &[Envelope], structure: &Structure) -> Vec<Joined> {
    let has = |unit: &str, field: &str| envelope_of(envelopes, unit, field);
    let sections = &structure.sections;
    ENVELOPED
        .iter()
        .filter(|field| {
            has(&structure.twin, field).is_some()
                || sections.iter().any(|(u, _)| has(u, field).is_some())
        })
        .map(|field| {
            let mut runs: Vec<[Vec<f64>; 3]> = Vec::new();
            let mut open = false;
            for (unit, _) in sections {
                match has(unit, field) {
                    Some(e) => {
                        if !open {
                            runs.push(Default::default());
                        }
                        if let Some([arc, min, max]) = runs.last_mut() {
                            arc.extend(&e.arc);
                            min.extend(&e.min);
                            max.extend(&e.max);
                        }
                        open = true;
                    }
                    None => open = false,
                }
            }
            (field.to_string(), runs)
        })
        .collect()
}

/// The x range of a panel from its curves' arcs.
fn range<'a>(arcs: impl Iterator<Item = &'a Vec<f64>> + Clone) -> (f64, f64) {
    let lo = (arcs.clone().filter_map(|a| a.first())).fold(f64::INFINITY, |m, &v| m.min(v));
    let hi = (arcs.filter_map(|a| a.last())).fold(f64::NEG_INFINITY, |m, &v| m.max(v));
    if lo.is_finite() && hi.is_finite() {
        (lo, hi.max(lo + 1e-9))
    } else {
        (0.0, 1.0)
    }
}

/// One structure's field along it: its sections' runs, beside its twin's
/// envelope where it has one; `prefix` before the field's name.
fn structure_panel<'a>(
    envelopes: &'a [Envelope],
    structure: &Structure,
    (field, runs): &'a Joined,
    prefix: &str,
) -> Option<Profile<'a>> {
    let unit_of_measure = &envelopes
        .iter()
        .find(|e| &e.field == field)?
        .unit_of_measure;
    let twin = envelope_of(envelopes, &structure.twin, field);
    let curve = |name: String, x: &'a [f64], y: &'a [f64]| Curve { name, x, y };
    let mut series = Vec::new();
    if let Some(t) = twin {
        series.push(curve("twin max".into(), &t.arc, &t.max));
        series.push(curve("twin min".into(), &t.arc, &t.min));
    }
    for (k, [arc, min, max]) in runs.iter().enumerate() {
        let part = if k == 0 {
            String::new()
        } else {
            format!(" {}", k + 1)
        };
        series.push(curve(format!("sections max{part}"), arc, max));
        series.push(curve(format!("sections min{part}"), arc, min));
    }
    let arcs = twin
        .map(|t| &t.arc)
        .into_iter()
        .chain(runs.iter().map(|r| &r[0]));
    Some(Profile {
        x_range: range(arcs),
        x_title: "arc length (m)",
        y_title: format!("{prefix}{field} ({unit_of_measure})"),
        series,
    })
}

/// The figure's panels: per structure and field its sections' envelope along
/// it, beside its twin's where it has one; then each other unit's own.
fn panels<'a>(
    envelopes: &'a [Envelope],
    structures: &[Structure],
    joined: &'a [Vec<Joined>],
) -> Vec<Profile<'a>> {
    let named = structures.len() > 1;
    let mut panels = Vec::new();
    for (structure, fields) in structures.iter().zip(joined) {
        let prefix = if named {
            format!("{} ", structure.name)
        } else {
            String::new()
        };
        let drawn = fields
            .iter()
            .filter_map(|f| structure_panel(envelopes, structure, f, &prefix));
        panels.extend(drawn);
    }
    let in_a_structure = |e: &Envelope| {
        (structures.iter())
            .any(|s| e.unit == s.twin || s.sections.iter().any(|(u, _)| *u == e.unit))
    };
    let curve = |name: &str, x: &'a [f64], y: &'a [f64]| Curve {
        name: name.into(),
        x,
        y,
    };
    for e in envelopes.iter().filter(|e| !in_a_structure(e)) {
        panels.push(Profile {
            x_range: range(std::iter::once(&e.arc)),
            x_title: "arc length (m)",
            y_title: format!("{} {} ({})", e.unit, e.field, e.unit_of_measure),
            series: vec![
                curve("max", &e.arc, &e.max),
                curve("mean", &e.arc, &e.mean),
                curve("min", &e.arc, &e.min),
            ],
        });
    }
    panels
}

/// Writes `envelopes.csv` (a row per unit, field and point: arc, min, max,
/// mean) and `envelopes.svg` into `dir`: per structure (a `[structure]`, or
/// each line of a `[mooring]`) and field its sections' envelope along it,
/// beside its twin's where it has one, then any other unit's.
pub fn write(
    dir: &Path,
    title: &str,
    envelopes: &[Envelope],
    structures: &[Structure],
) -> Result<Vec<PathBuf>, PlotError> {
    if envelopes.is_empty() {
        return Ok(Vec::new());
    }
    let mut csv = "unit,field,unit_of_measure,arc [m],min,max,mean\n".to_owned();
    for e in envelopes {
        for i in 0..e.arc.len() {
            csv += &format!(
                "{},{},{},{},{:e},{:e},{:e}\n",
                e.unit, e.field, e.unit_of_measure, e.arc[i], e.min[i], e.max[i], e.mean[i]
            );
        }
    }
    let csv_path = dir.join("envelopes.csv");
    crate::whole::write(&csv_path, csv).map_err(|e| PlotError::new(&csv_path, &e))?;
    let joined: Vec<Vec<Joined>> = structures.iter().map(|s| joined(envelopes, s)).collect();
    let panels = panels(envelopes, structures, &joined);
    let svg_path = dir.join("envelopes.svg");
    let title = format!("{title}: envelopes along the line");
    crate::whole::through(&svg_path, |p| crate::plot::profiles(p, &title, &panels))?;
    Ok(vec![csv_path, svg_path])
}
