//! The watch on the touchdown point: a structure is cut so that the section
//! holding the touchdown point follows it as it moves (a `nonlinear`
//! section), while the laid pipe below may be `static` and the hanging pipe
//! above `linear`, which follow it only as far as their linearised statics
//! do. Where the point moves out of the section that held it, no node of
//! that section lies on the seabed any more: the riser example cut at 745 m,
//! with the point moving over 730-780 m, loses it at 10.7 s and its
//! touchdown and sag-bend moment are 50 % and 2 % off the whole riser
//! without a word. A section of a `[structure]` beside one that is not
//! `nonlinear`, which lay on the seabed at the start (`contact_length` > 0,
//! m) and lies on it nowhere later, is a warning, once per section, naming
//! that neighbour. (A lone unit may leave the seabed as it likes: a beam
//! lifted off its bump.) It never stops a run: it says where the model's
//! reach ends, not that a result is implausible.

use slender_coupling::coupler::Master;
use slender_scene::Scene;

/// One section that lay on the seabed at the start: its `contact_length`
/// port, and the neighbour that cannot follow the point, in words.
struct Lying {
    unit: usize,
    port: usize,
    start: f64,
    neighbour: String,
    warned: bool,
}

/// The sections of the scene's `[structure]` with a neighbour that is not
/// `nonlinear`: each section's unit and that neighbour in words (none
/// without a structure).
pub(super) fn guarded(scene: &Scene) -> Vec<(String, String)> {
    let layout = scene
        .keys()
        .ok()
        .and_then(|keys| slender_scene::structure::layout(&keys).ok().flatten());
    let Some(layout) = layout.filter(|l| l.seabed) else {
        return Vec::new();
    };
    let sections = &layout.sections;
    let follows = |k: usize| sections[k].choice.starts_with("nonlinear");
    (0..sections.len())
        .filter_map(|k| {
            let below = k.checked_sub(1).filter(|&b| !follows(b));
            let above = Some(k + 1).filter(|&a| a < sections.len() && !follows(a));
            let n = below.or(above)?;
            let side = if Some(n) == below { "below" } else { "above" };
            let words = format!(
                "the section {side} it, `{}`, is `{}`",
                sections[n].unit, sections[n].choice
            );
            Some((sections[k].unit.clone(), words))
        })
        .collect()
}

/// The watch on the sections that hold seabed contact.
pub(super) struct TouchdownWatch {
    sections: Vec<Lying>,
}

impl TouchdownWatch {
    /// The `guarded` sections (unit, neighbour in words) with a
    /// `contact_length` output above zero at the start, after
    /// `Master::initialize`.
    pub(super) fn new(master: &Master, guarded: Vec<(String, String)>) -> TouchdownWatch {
        let sections = (guarded.into_iter())
            .filter_map(|(name, neighbour)| {
                let unit = master.unit_names().position(|u| u == name)?;
                let ports = &master.description(unit).outputs;
                let port = ports.iter().position(|p| p.name == "contact_length")?;
                let start = master.outputs(unit)[port];
                (start > 0.0).then_some(Lying {
                    unit,
                    port,
                    start,
                    neighbour,
                    warned: false,
                })
            })
            .collect();
        TouchdownWatch { sections }
    }

    /// Checks the sections after a step at simulated time `t` (s), adding a
    /// warning to `warnings` the first time one lies on the seabed nowhere.
    pub(super) fn observe(&mut self, master: &Master, t: f64, warnings: &mut Vec<String>) {
        for s in self.sections.iter_mut().filter(|s| !s.warned) {
            if master.outputs(s.unit)[s.port] <= 0.0 {
                s.warned = true;
                let name = master.unit_names().nth(s.unit).unwrap_or("?");
                warnings.push(format!(
                    "the touchdown point left `{name}`: from t = {t} s none of it lies on the seabed (`{name}.contact_length` was {:.4e} m at the start), and {}, which follows the point only as far as its linearised statics do: cut the structure so that the point stays inside one `nonlinear` section (for a laid section, its end further from the point)",
                    s.start, s.neighbour
                ));
            }
        }
    }
}
