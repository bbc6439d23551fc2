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
use slender_scene::structure::SectionOutputs;

/// One section of a run: its unit, where it starts (m of arc) and which of
/// its outputs the quantities read.
#[derive(Clone, Debug)]
pub struct SectionUnit {
    /// The unit's name.
    pub unit: String,
    /// Where it starts (m of arc).
    pub from: f64,
    /// Which of its outputs the quantities read.
    pub outputs: SectionOutputs,
    /// The whole structure as one unit (the reference): the number of its
    /// first station at a cut (the cuts' stations follow in order).
    pub cut_stations: Option<usize>,
    /// A section that takes stations: the numbers of its stations in its
    /// first and in its last element, at its cuts.
    pub end_stations: [Option<usize>; 2],
}

/// What the structure's model has: seabed contact (touchdown, sag bend), a
/// stinger (overbend), and its cuts (their quantities' names).
#[derive(Clone, Debug, Default)]
pub struct Features {
    /// Seabed contact: touchdown and sag bend.
    pub seabed: bool,
    /// A stinger: the overbend.
    pub stinger: bool,
    /// The cuts' quantities' names.
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
    /// The magnitude of a force's components (N).
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
/// take stations, the mean of their elements' forces at the cut, the same
/// measure; else the lower section's end force (the upper section's start
/// force where the lower one's end takes its force as an input: a cable, a
/// chord section).
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
    let force = end_force(lower, true).or_else(|| end_force(upper, false));
    CutReading::Components(force.map_or(Vec::new(), |f| f.to_vec()))
}

/// The outputs to record for the quantities of `sections`.
pub fn signals(sections: &[SectionUnit], features: &Features) -> Vec<String> {
    let mut signals = Vec::new();
    if let Some(last) = sections.last() {
        signals.extend(end_force(last, true).into_iter().flatten());
    }
    if let Some(first) = sections.first() {
        signals.extend(end_force(first, false).into_iter().flatten());
    }
    for s in sections {
        let o = &s.outputs;
        for output in [&o.touchdown, &o.sagbend_moment, &o.overbend_moment] {
            signals.extend(output.as_ref().map(|output| format!("{}.{output}", s.unit)));
        }
    }
    for k in 0..features.cuts.len() {
        signals.extend(cut_reading(sections, k).signals().iter().cloned());
    }
    signals
}

/// A section's signal of one of its outputs, where it has it.
fn signal_of(section: &SectionUnit, output: &Option<String>) -> Option<String> {
    (output.as_ref()).map(|output| format!("{}.{output}", section.unit))
}

/// The force's components (x, z; x, y, z in 3D) at a section's end (`top`)
/// or start; none where that force is the section's input.
fn end_force(section: &SectionUnit, top: bool) -> Option<Vec<String>> {
    let o = &section.outputs;
    let ports = if top {
        o.end_force.as_ref()
    } else {
        Some(&o.start_force)
    };
    ports.map(|ports| {
        (ports.iter())
            .map(|p| format!("{}.{p}", section.unit))
            .collect()
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
        let components = end_force(section, top)
            .ok_or(format!("`{}`'s force there is its input", section.unit))?;
        let columns: Vec<&[f64]> = (components.iter())
            .map(|c| column(c))
            .collect::<Result<_, String>>()?;
        Ok((0..recorder.time.len())
            .map(|i| columns.iter().map(|c| c[i] * c[i]).sum::<f64>().sqrt())
            .collect())
    };
    // The largest magnitude over the sections that report an output.
    let largest = |output: fn(&SectionOutputs) -> &Option<String>| {
        let mut out = vec![0.0f64; recorder.time.len()];
        for signal in sections
            .iter()
            .filter_map(|s| signal_of(s, output(&s.outputs)))
        {
            for (o, v) in out.iter_mut().zip(column(&signal)?) {
                *o = o.max(v.abs());
            }
        }
        Ok::<_, String>(out)
    };
    match name {
        "top_force" => magnitude(sections.last(), true),
        "start_force" => magnitude(sections.first(), false),
        "sagbend_moment" => largest(|o| &o.sagbend_moment),
        "overbend_moment" => largest(|o| &o.overbend_moment),
        "touchdown" => {
            // The highest section in contact gives the touchdown point: its own
            // arc length from its start, plus where it starts.
            let columns: Vec<(f64, &[f64])> = (sections.iter().rev())
                .filter_map(|s| Some((s.from, signal_of(s, &s.outputs.touchdown)?)))
                .map(|(from, signal)| Ok((from, column(&signal)?)))
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
