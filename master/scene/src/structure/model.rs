//! What a fidelity is, as the expansion and the tools read it: one type per
//! fidelity behind `SectionModel`, each in its own file (`nonlinear.rs`:
//! `nonlinear` and `linear`; `cable.rs`; `static_fidelity.rs`; `reduced.rs`;
//! `chord.rs`: `beam` and `span`), registered once in `Fidelity::model`
//! (`sections.rs` holds the names). The trait says which unit a fidelity
//! writes, what its ends are called, how it needs its cuts coupled, its keys,
//! where it reports what a study measures and what it refuses.

use super::Built;
use super::cuts::End;
use super::layout::SectionOutputs;
use super::sections::Cut;
use super::unit::SectionUnit;

/// Where a section is and how the structure starts, for a fidelity's needs
/// at its cuts.
#[derive(Copy, Clone, Debug)]
pub(super) struct Place {
    /// The section's index, first at the structure's start.
    pub k: usize,
    /// The structure's equilibrium is solved at the start.
    pub static_start: bool,
    /// The first section is static and takes force
    /// (`statics::static_takes_force`).
    pub holding_static: bool,
}

/// The section a fidelity writes its unit for: the structure, its cuts,
/// which section (`k`, first at the structure's start) and how its ends are
/// coupled at its cuts (None at the structure's ends).
pub(super) struct SectionAt<'a> {
    pub built: &'a Built,
    pub cuts: &'a [Cut],
    pub k: usize,
    pub ends: (Option<End>, Option<End>),
}

impl SectionAt<'_> {
    /// The section's own cut (its name, range and fidelity).
    pub(super) fn cut(&self) -> &Cut {
        &self.cuts[self.k]
    }
}

/// How a fidelity needs its cuts coupled: per cut, whether the upper side
/// is the loaded one (`true`) or the moving one; None: either way.
#[derive(Copy, Clone, Debug, Default)]
pub(super) struct CutNeeds {
    /// The cut at the section's start.
    pub below: Option<bool>,
    /// The cut at the section's end.
    pub above: Option<bool>,
    /// Every cut of the structure (a static first section that every
    /// section above hangs from).
    pub all: Option<bool>,
}

impl CutNeeds {
    /// A section that moves with the section below at its start and is
    /// loaded by the section above at its end (a cable, a chord).
    pub(super) const MOVING_START_LOADED_END: CutNeeds = CutNeeds {
        below: Some(true),
        above: Some(true),
        all: None,
    };
}

/// One fidelity of a section.
pub(super) trait SectionModel: Sync {
    /// The name as written in scenes.
    fn name(&self) -> &'static str;

    /// The keys its table form `{ kind = NAME, ... }` takes, `kind` first;
    /// those besides `kind` and `elements` are handed to its unit. Empty: the
    /// table takes `kind` and `elements` only.
    fn option_keys(&self) -> &'static [&'static str] {
        &[]
    }

    /// The key a count after `:` on the command line sets.
    fn count_key(&self) -> &'static str {
        "elements"
    }

    /// Its unit is the `nonlinear` unit (same ports, stations and outputs).
    fn is_section_unit(&self) -> bool {
        false
    }

    /// It carries bending: rotation and moment cross its cuts.
    fn bends(&self) -> bool {
        true
    }

    /// A small-deflection model about its chord, coupled by position.
    fn is_chord(&self) -> bool {
        false
    }

    /// It models seabed contact (a section lying on the seabed in the
    /// equilibrium cannot be a model without).
    fn has_seabed(&self) -> bool {
        true
    }

    /// Its ports' prefixes at its start and at its end (`start_force_x`).
    fn end_names(&self) -> [&'static str; 2] {
        ["start", "end"]
    }

    /// How it needs its cuts coupled at `place`.
    fn cut_needs(&self, _place: Place) -> CutNeeds {
        CutNeeds::default()
    }

    /// Where it reports what a study measures: its end forces (an end
    /// loaded by a coupled force reports none), and, in a model with a
    /// seabed or a stinger, its touchdown point and moments.
    /// The default: a model loaded at its end by the section above (no end
    /// force there) without a touchdown point or moments (a cable, a chord).
    fn outputs(
        &self,
        _fmu: bool,
        seabed: bool,
        stinger: bool,
        _static_start: bool,
    ) -> SectionOutputs {
        outputs_of(self.end_names(), true, None, false, (seabed, stinger))
    }

    /// Its unit for the section `at`; refuses with the reason where it
    /// cannot model the section.
    fn unit(&self, at: &SectionAt) -> Result<SectionUnit, String>;

    /// How it keeps the contact state it starts with, in words, where it
    /// does (so it cannot follow a moving touchdown point); None: it follows
    /// contact as it changes.
    fn contact_state_kept(&self) -> Option<&'static str> {
        None
    }

    /// Refuses what it cannot model before its unit is written (checked at
    /// `slender check`); the default refuses nothing.
    fn refuse(&self, _built: &Built, _cut: &Cut) -> Result<(), String> {
        Ok(())
    }
}

/// The outputs of a section reporting its end forces at `ends` (the end's
/// none where `end_loaded`), its touchdown point as `touchdown` with its
/// sag-bend moment where the model has a seabed, and its overbend moment
/// where `overbend` and the model has a stinger.
pub(super) fn outputs_of(
    ends: [&str; 2],
    end_loaded: bool,
    touchdown: Option<&str>,
    overbend: bool,
    (seabed, stinger): (bool, bool),
) -> SectionOutputs {
    let forces = |side: &str| vec![format!("{side}_force_x"), format!("{side}_force_z")];
    let touches = seabed && touchdown.is_some();
    SectionOutputs {
        start_force: forces(ends[0]),
        end_force: (!end_loaded).then(|| forces(ends[1])),
        touchdown: touchdown.filter(|_| touches).map(str::to_owned),
        sagbend_moment: touches.then(|| "sagbend_moment".to_owned()),
        overbend_moment: (stinger && overbend).then(|| "overbend_moment".to_owned()),
        stations: false,
    }
}

#[cfg(test)]
mod tests {
    use super::super::sections::Fidelity;

    #[test]
    fn every_fidelity_is_registered_under_its_name() {
        for (fidelity, name) in Fidelity::ALL.into_iter().zip(Fidelity::NAMES) {
            assert_eq!(fidelity.name(), name);
            assert_eq!(Fidelity::parse("fidelity", name), Ok(fidelity));
            let keys = fidelity.model().option_keys();
            assert!(keys.is_empty() || keys[0] == "kind", "{name}: {keys:?}");
            let count = fidelity.count_key();
            assert!(
                count == "elements" || keys.contains(&count),
                "{name}: {count}"
            );
        }
    }

    /// Adding a fidelity is its own file and one line in `fidelities!`: each
    /// name is registered once, and the enum, the names, the list and the
    /// models all come from that line.
    #[test]
    fn a_fidelity_is_registered_on_one_line() {
        let registry = include_str!("sections.rs");
        for name in Fidelity::NAMES {
            let line = format!("= \"{name}\" =>");
            assert_eq!(registry.matches(&line).count(), 1, "{name}");
        }
        assert_eq!(registry.matches("fidelities! {").count(), 1);
        assert_eq!(Fidelity::ALL.len(), Fidelity::NAMES.len());
    }
}
