//! What a section's fidelity cannot model, refused when the scene is
//! written out (`slender check`) with the reason, rather than at the start
//! of a run: a model without seabed contact on a section lying on the
//! seabed; a `linear` section, or a `reduced` one with sampled forces, over
//! a stinger's rollers. And what it models
//! poorly, said as an advisory (`slender check` and the run's warnings): a
//! model that keeps its contact state on a section that holds the touchdown
//! point.

use super::Built;
use super::sections::Cut;
use slender_units::contact::surface::Shape;

impl Built {
    /// Refuses a model without seabed contact (`Fidelity::lacks_seabed`) on
    /// a section that lies on a flat seabed in the equilibrium, rather than
    /// letting it fail at the start.
    pub(super) fn refuse_without_seabed(&self, cut: &Cut) -> Result<(), String> {
        if !cut.fidelity.lacks_seabed() {
            return Ok(());
        }
        match self.lying(cut) {
            Some((first, last)) => Err(format!(
                "`structure.sections.{}.fidelity` = \"{}\": the section lies on the seabed from {first:.2} to {last:.2} m of arc in the static equilibrium, and a {} model has no seabed contact; choose \"nonlinear\" (or \"static\" for a first, laid section), or cut it above the touchdown point",
                cut.name,
                cut.fidelity.name(),
                cut.fidelity.name()
            )),
            None => Ok(()),
        }
    }

    /// The arc lengths (m) of the first and last nodes of `cut` on a flat
    /// seabed in the equilibrium; None where none lies (or without a static
    /// start or a flat seabed).
    fn lying(&self, cut: &Cut) -> Option<(f64, f64)> {
        let height = match self.model.contact.as_ref()?.surface.shape {
            Shape::Flat { height } => height,
            _ => return None,
        };
        self.statics.as_ref()?.on_seabed((cut.from, cut.to), height)
    }

    /// An advisory where a model that keeps its contact state (its
    /// `contact_state_kept`) is given a section holding the touchdown point
    /// in the equilibrium: it lies on the seabed up to a point inside it and
    /// hangs above, and the point moves along it.
    pub(super) fn advise_on_touchdown(&self, cut: &Cut) -> Option<String> {
        let how = cut.fidelity.model().contact_state_kept()?;
        // The pipe lies from the structure's start and lifts off the seabed
        // towards its top: the last node lying is the touchdown point where
        // it is not the section's end (its start, an anchor, may lie above).
        let (_, at) = self.lying(cut)?;
        let holds = at < cut.to - 1e-9 * (cut.to - cut.from);
        holds.then(|| format!(
            "`structure.sections.{}.fidelity` = \"{}\": the touchdown point lies in this section (at {at:.1} m of arc in the static equilibrium) and moves along it, which {how}; expect errors of several per cent (the riser's sag bend over 200 s: `linear` 42 % on the sag-bend moment, `reduced` 11 % on the top force); \"nonlinear\" follows it",
            cut.name,
            cut.fidelity.name()
        ))
    }

    /// Refuses a `linear` section (its model's `refuse`) whose equilibrium
    /// passes over a stinger's rollers (by x): the rollers move and the pipe
    /// lifts off them, which a linear model cannot follow (the unit refuses
    /// it again at its start, from its own contact state).
    pub(super) fn refuse_linear_on_stinger(&self, cut: &Cut) -> Result<(), String> {
        match self.roller_over(cut) {
            Some(x) => Err(format!(
                "`structure.sections.{}.fidelity` = \"linear\": the section passes over the stinger's roller at x = {x} m in the static equilibrium, and a linear section cannot follow rollers that move and that the pipe lifts off; choose \"nonlinear\" there",
                cut.name
            )),
            None => Ok(()),
        }
    }

    /// Refuses a `reduced` section with sampled forces (`training`) whose
    /// equilibrium passes over a stinger's rollers: a roller meets whichever
    /// element passes over it, so no fixed sample holds its force (the unit
    /// stops with the reason where a roller presses on it later).
    pub(super) fn refuse_sampling_on_stinger(&self, cut: &Cut) -> Result<(), String> {
        let sampled = (cut.options.as_ref()).is_some_and(|o| o.contains_key("training"));
        match self.roller_over(cut).filter(|_| sampled) {
            Some(x) => Err(format!(
                "`structure.sections.{}.fidelity.training`: the section passes over the stinger's roller at x = {x} m in the static equilibrium, and sampled forces cannot hold a roller's (it meets whichever element passes over it); leave `training` out there",
                cut.name
            )),
            None => Ok(()),
        }
    }

    /// The x (m) of a stinger's roller the section passes over in the static
    /// equilibrium, if any.
    fn roller_over(&self, cut: &Cut) -> Option<f64> {
        let Shape::Rollers { positions, .. } = &self.model.stinger.as_ref()?.surface.shape else {
            return None;
        };
        let equilibrium = self.statics.as_ref()?;
        let samples = 200;
        let xs = (0..=samples).map(|i| {
            let s = cut.from + (cut.to - cut.from) * f64::from(i) / f64::from(samples);
            equilibrium.position_at(s)[0]
        });
        let (low, high) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), x| {
            (l.min(x), h.max(x))
        });
        positions.iter().copied().find(|x| (low..=high).contains(x))
    }
}
