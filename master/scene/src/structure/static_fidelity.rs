//! The `static` fidelity: the structure's first section (a laid pipe from its
//! held start) as its linearised static response at its end in the
//! equilibrium (`static_section` unit), following the section above or, when
//! the structure's end carries a force, taking force and holding the section
//! above by its displacement; it reports the static touchdown estimate.

use super::Built;
use super::cuts::End;
use super::layout::SectionOutputs;
use super::model::{CutNeeds, Place, SectionAt, SectionModel, outputs_of};
use super::nonlinear::section_parameters;
use super::sections::Cut;
use super::unit::{Parameters, SectionUnit};

/// The `static` fidelity.
pub(super) struct Static;

impl SectionModel for Static {
    fn name(&self) -> &'static str {
        "static"
    }
    /// A first section that takes force holds the section above (its end
    /// loaded); otherwise every section above hangs from what holds it, every
    /// cut the moving way round.
    fn cut_needs(&self, place: Place) -> CutNeeds {
        match place {
            Place {
                k: 0,
                holding_static: true,
                ..
            } => CutNeeds {
                above: Some(true),
                ..CutNeeds::default()
            },
            Place { k: 0, .. } => CutNeeds {
                all: Some(false),
                ..CutNeeds::default()
            },
            _ => CutNeeds::default(),
        }
    }
    fn outputs(&self, _: bool, seabed: bool, stinger: bool, _: bool) -> SectionOutputs {
        outputs_of(
            ["start", "end"],
            false,
            Some("touchdown"),
            false,
            (seabed, stinger),
        )
    }
    fn unit(&self, at: &SectionAt) -> Result<SectionUnit, String> {
        at.built.static_unit(at.cuts, at.k, at.ends)
    }
}

impl Built {
    /// The `static` fidelity's unit of the first section: its static response
    /// from the equilibrium, taking force where it holds the sections above.
    pub(super) fn static_unit(
        &self,
        cuts: &[Cut],
        k: usize,
        (start, end): (Option<End>, Option<End>),
    ) -> Result<SectionUnit, String> {
        let cut = &cuts[k];
        let key = format!("structure.sections.{}.fidelity", cut.name);
        let equilibrium = match (&self.statics, k, cuts.len()) {
            (Some(e), 0, 2..) => e,
            _ => {
                return Err(format!(
                    "`{key}` = \"static\": a static section is the structure's first section (a laid pipe from its held start), one of several, and is found from the equilibrium of `structure.model.static_start = true`"
                ));
            }
        };
        let mut section = section_parameters(&self.model, &self.segments, cut, (start, end))?;
        equilibrium.start_section(&mut section, (cut.from, cut.to));
        let name = super::unit_name(&self.name, &cut.name);
        let mut unit = equilibrium.static_section(&key, name, &section, (cut.from, cut.to))?;
        if self.holding_static
            && let Parameters::Static(p) = &mut unit.parameters
        {
            p.force_input = true;
        }
        Ok(unit)
    }
}
