//! A structure's quantities of interest, read from whatever units its sections
//! are: the force at its top end and at its start (the anchor or the laid pipe's
//! end), and, where the model has them, the touchdown point, the largest sag-bend
//! and overbend moments; and the force each cut transmits (its magnitude, N:
//! `cut_<lower>_<upper>`: the mean of the internal forces of the elements on
//! both sides, from stations; a section's end force where a side has no
//! elements). Each is a time series built from the recorded outputs
//! of the sections' units (`nonlinear`, `cable`, or a `static` section's static
//! touchdown estimate), so every combination of fidelities and the monolithic
//! reference are measured the same way.

use crate::record::Recorder;

/// One section of a run: its unit, its kind and where it starts (m of arc).
#[derive(Clone, Debug)]
pub struct SectionUnit {
    pub unit: String,
    pub kind: String,
    pub from: f64,
    /// The whole structure as one unit (the reference): the number of its
    /// first station at a cut (the cuts' stations follow in order).
    pub cut_stations: Option<usize>,
    /// A `nonlinear` section: the numbers of its stations in its first and in
    /// its last element, at its cuts.
    pub end_stations: [Option<usize>; 2],
}

/// What the structure's model has: seabed contact (touchdown, sag bend), a
/// stinger (overbend), and its cuts (their quantities' names).
#[derive(Clone, Debug, Default)]
pub struct Features {
    pub seabed: bool,
    pub stinger: bool,
    pub cuts: Vec<String>,
}

/// The quantities' names for a model with `features`.
pub fn names(features: &Features) -> Vec<String> {
    let mut names = vec!["top_force", "start_force"];
    if features.seabed {
        names.extend(["touchdown", "sagbend_moment"]);
    }
    if features.stinger {
        names.push("overbend_moment");
    }
    let mut names: Vec<String> = names.into_iter().map(str::to_owned).collect();
    names.extend(features.cuts.iter().cloned());
    names
}

/// How a run gives the force at a cut.
enum CutReading {
    /// The mean of these internal-force magnitudes (N).
    Mean(Vec<String>),
    /// The magnitude of a force's x and z components (N).
    Components(Vec<String>),
}

impl CutReading {
    fn signals(&self) -> &[String] {
        match self {
            CutReading::Mean(s) | CutReading::Components(s) => s,
        }
    }
}

/// The force at cut `k` (between sections k and k + 1): in the reference its
/// station there (the mean of the two elements at the node); where both sides
/// are `nonlinear`, the mean of their elements' forces at the cut, the same
/// measure; else the lower section's end force (the upper section's start
/// force where the lower one is a cable or a chord section, whose end takes its
/// force as an input).
fn cut_reading(sections: &[SectionUnit], k: usize) -> CutReading {
    if let [whole] = sections
        && let Some(first) = whole.cut_stations
    {
        return CutReading::Mean(vec![format!("{}.force_{}", whole.unit, first + k)]);
    }
    let (lower, upper) = (&sections[k], &sections[k + 1]);
    if let (Some(a), Some(b)) = (lower.end_stations[1], upper.end_stations[0]) {
        return CutReading::Mean(vec![
            format!("{}.force_{a}", lower.unit),
            format!("{}.force_{b}", upper.unit),
        ]);
    }
    let (section, top) = match lower.kind.as_str() {
        "beam" | "span" | "cable" => (upper, false),
        _ => (lower, true),
    };
    CutReading::Components(end_force(section, top).map(|(_, p)| p).to_vec())
}

/// The outputs to record for the quantities of `sections`.
pub fn signals(sections: &[SectionUnit], features: &Features) -> Vec<String> {
    let mut signals = Vec::new();
    if let Some(last) = sections.last() {
        signals.extend(end_force(last, true).map(|(_, p)| p));
    }
    if let Some(first) = sections.first() {
        signals.extend(end_force(first, false).map(|(_, p)| p));
    }
    for s in sections.iter().filter(|s| touches(s)) {
        if features.seabed {
            signals.push(touchdown_signal(s));
            signals.push(format!("{}.sagbend_moment", s.unit));
        }
        if features.stinger && s.kind == "nonlinear" {
            signals.push(format!("{}.overbend_moment", s.unit));
        }
    }
    for k in 0..features.cuts.len() {
        signals.extend(cut_reading(sections, k).signals().iter().cloned());
    }
    signals
}

/// A section's touchdown point (m of arc from its start): where the seabed
/// gap crosses zero, interpolated between the nodes (a `nonlinear` section's
/// `touchdown_arc`, a `static` one's estimate `touchdown`), not the first
/// node on the seabed, which jumps by whole elements.
fn touchdown_signal(section: &SectionUnit) -> String {
    match section.kind.as_str() {
        "nonlinear" => format!("{}.touchdown_arc", section.unit),
        _ => format!("{}.touchdown", section.unit),
    }
}

/// Whether a section reports the touchdown point and the sag-bend moment: a
/// `nonlinear` one, and a `static` one through its static touchdown estimate.
fn touches(section: &SectionUnit) -> bool {
    matches!(section.kind.as_str(), "nonlinear" | "static")
}

/// The two force components at a section's end (`top`) or start, by kind.
fn end_force(section: &SectionUnit, top: bool) -> [(usize, String); 2] {
    let side = match (section.kind.as_str(), top) {
        ("cable", true) => "top",
        ("cable", false) => "bottom",
        (_, true) => "end",
        (_, false) => "start",
    };
    [0, 1].map(|k| {
        (
            k,
            format!("{}.{side}_force_{}", section.unit, ["x", "z"][k]),
        )
    })
}

/// The quantity `name`'s time series from a run's recording; the error names a
/// missing output.
pub fn series(
    name: &str,
    sections: &[SectionUnit],
    features: &Features,
    recorder: &Recorder,
) -> Result<Vec<f64>, String> {
    let column = |signal: &str| {
        recorder
            .column(signal)
            .ok_or(format!("the run recorded no `{signal}`"))
    };
    let magnitude = |section: Option<&SectionUnit>, top: bool| -> Result<Vec<f64>, String> {
        let section = section.ok_or("a structure without sections")?;
        let [(_, x), (_, z)] = end_force(section, top);
        let (x, z) = (column(&x)?, column(&z)?);
        Ok(x.iter().zip(z).map(|(x, z)| x.hypot(*z)).collect())
    };
    let bending: Vec<&SectionUnit> = sections.iter().filter(|s| touches(s)).collect();
    let largest = |output: &str| -> Result<Vec<f64>, String> {
        let mut out = vec![0.0f64; recorder.time.len()];
        let overbend = output == "overbend_moment";
        for s in bending
            .iter()
            .filter(|s| !overbend || s.kind == "nonlinear")
        {
            for (o, v) in out.iter_mut().zip(column(&format!("{}.{output}", s.unit))?) {
                *o = o.max(v.abs());
            }
        }
        Ok(out)
    };
    match name {
        "top_force" => magnitude(sections.last(), true),
        "start_force" => magnitude(sections.first(), false),
        "sagbend_moment" | "overbend_moment" => largest(name),
        "touchdown" => {
            // The highest section in contact gives the touchdown point: its own
            // arc length from its start, plus where it starts.
            let columns: Vec<(f64, &[f64])> = bending
                .iter()
                .rev()
                .map(|s| Ok((s.from, column(&touchdown_signal(s))?)))
                .collect::<Result<_, String>>()?;
            Ok((0..recorder.time.len())
                .map(|k| {
                    columns
                        .iter()
                        .find(|(_, c)| c[k] > 0.0)
                        .map_or(0.0, |(from, c)| from + c[k])
                })
                .collect())
        }
        cut => {
            let k = features
                .cuts
                .iter()
                .position(|c| c == cut)
                .ok_or(format!("no quantity `{cut}`"))?;
            let reading = cut_reading(sections, k);
            let columns: Vec<&[f64]> = reading
                .signals()
                .iter()
                .map(|s| column(s))
                .collect::<Result<_, String>>()?;
            let n = columns.len() as f64;
            Ok((0..recorder.time.len())
                .map(|i| match reading {
                    CutReading::Mean(_) => columns.iter().map(|c| c[i]).sum::<f64>() / n,
                    CutReading::Components(_) => {
                        columns.iter().map(|c| c[i] * c[i]).sum::<f64>().sqrt()
                    }
                })
                .collect())
        }
    }
}
