//! The watch on the touchdown point: a structure is cut so that the section
//! holding the touchdown point follows it as it moves (a `nonlinear`
//! section), while the laid pipe below may be `static` and the hanging pipe
//! above `linear`, which follow it only as far as their linearised statics
//! do. Where the point moves out of the section that held it, nothing says
//! so: the riser example's laid `static` section cut at 745 m, with the
//! point moving over 730-780 m, takes it at 10.7 s and the touchdown and
//! sag-bend moment are 50 % and 2 % off the whole riser; its sag bend ending
//! at 760 m under a `linear:30` top, the point reaches the top at 5.95 s, whose
//! seabed springs are those of its start (none) and which sinks into the
//! seabed there. Two warnings, once per section, each naming it and the
//! time: a section of a `[structure]` beside one that is not `nonlinear`,
//! which lay on the seabed at the start (`contact_length` > 0, m) and lies
//! on it nowhere later, names that neighbour; a `linear` or `reduced`
//! section (it keeps the contact state it starts with) clear of the seabed
//! at the start and touching it later. (A lone unit may leave the seabed as
//! it likes: a beam lifted off its bump.) It never stops a run: it says
//! where the model's reach ends, not that a result is implausible.

use slender_coupling::coupler::Master;
use slender_scene::Scene;

/// What a watched section's `contact_length` must not do.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Guard {
    /// Fall to zero: the point would leave for this neighbour (in words).
    Keep(String),
    /// Rise above zero: the section keeps the contact state it starts with
    /// (its fidelity).
    StayClear(String),
}

/// One watched section: its `contact_length` port and start value (m).
struct Watched {
    unit: usize,
    port: usize,
    start: f64,
    guard: Guard,
    warned: bool,
}

/// The sections of the scene's `[structure]` to watch, by unit: beside a
/// neighbour that is not `nonlinear` (to keep the point), or themselves
/// `linear` or `reduced` (to stay clear of it); none without a structure.
pub(super) fn guarded(scene: &Scene) -> Vec<(String, Guard)> {
    let layout = scene
        .keys()
        .ok()
        .and_then(|keys| slender_scene::structure::layout(&keys).ok().flatten());
    let Some(layout) = layout.filter(|l| l.seabed) else {
        return Vec::new();
    };
    let sections = &layout.sections;
    let follows = |k: usize| sections[k].choice.starts_with("nonlinear");
    let keeps_state = |k: usize| {
        let c = &sections[k].choice;
        c.starts_with("linear") || c.starts_with("reduced")
    };
    let mut watched = Vec::new();
    for (k, section) in sections.iter().enumerate() {
        let below = k.checked_sub(1).filter(|&b| !follows(b));
        let above = Some(k + 1).filter(|&a| a < sections.len() && !follows(a));
        if let Some(n) = below.or(above) {
            let side = if Some(n) == below { "below" } else { "above" };
            let words = format!(
                "the section {side} it, `{}`, is `{}`",
                sections[n].unit, sections[n].choice
            );
            watched.push((section.unit.clone(), Guard::Keep(words)));
        }
        if keeps_state(k) {
            watched.push((
                section.unit.clone(),
                Guard::StayClear(section.choice.clone()),
            ));
        }
    }
    watched
}

/// The watch on the sections' seabed contact.
pub(super) struct TouchdownWatch {
    sections: Vec<Watched>,
}

impl TouchdownWatch {
    /// The `guarded` sections (unit, guard) with a `contact_length` output
    /// that starts as its guard watches it (above zero to keep, zero to
    /// stay clear), after `Master::initialize`.
    pub(super) fn new(master: &Master, guarded: Vec<(String, Guard)>) -> TouchdownWatch {
        let sections = (guarded.into_iter())
            .filter_map(|(name, guard)| {
                let unit = master.unit_names().position(|u| u == name)?;
                let ports = &master.description(unit).outputs;
                let port = ports.iter().position(|p| p.name == "contact_length")?;
                let start = master.outputs(unit)[port];
                let watch = match guard {
                    Guard::Keep(_) => start > 0.0,
                    Guard::StayClear(_) => start == 0.0,
                };
                watch.then_some(Watched {
                    unit,
                    port,
                    start,
                    guard,
                    warned: false,
                })
            })
            .collect();
        TouchdownWatch { sections }
    }

    /// Checks the sections after a step at simulated time `t` (s), adding a
    /// warning to `warnings` the first time one does what its guard forbids.
    pub(super) fn observe(&mut self, master: &Master, t: f64, warnings: &mut Vec<String>) {
        for s in self.sections.iter_mut().filter(|s| !s.warned) {
            let now = master.outputs(s.unit)[s.port];
            let name = master.unit_names().nth(s.unit).unwrap_or("?");
            let warning = match &s.guard {
                Guard::Keep(neighbour) if now <= 0.0 => format!(
                    "the touchdown point left `{name}`: from t = {t} s none of it lies on the seabed (`{name}.contact_length` was {:.4e} m at the start), and {neighbour}, which follows the point only as far as its linearised statics do: cut the structure so that the point stays inside one `nonlinear` section (for a laid section, its end further from the point)",
                    s.start
                ),
                Guard::StayClear(fidelity) if now > 0.0 => format!(
                    "the touchdown point reached `{name}`: from t = {t} s it lies on the seabed over {now:.4e} m (`{name}.contact_length`), and it is `{fidelity}`, which keeps the contact state it starts with (clear of the seabed: nothing holds it up there): cut the structure so that the point stays inside one `nonlinear` section (for a hanging section, its start further from the point)"
                ),
                _ => continue,
            };
            s.warned = true;
            warnings.push(warning);
        }
    }
}
