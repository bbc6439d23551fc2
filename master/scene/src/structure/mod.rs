//! `[structure]`: one planar slender structure described once and cut into
//! sections, each its own unit, written out as units and connections when the
//! scene is read (`crate::expansion` types them and appends them to the
//! scene's own; `slender expand` prints them as plain `[[units]]` and
//! `[[connections]]`, so nothing is hidden).
//!
//! The structure is a `nonlinear` section's parameters (`[structure.model]`:
//! segments from the start, ends, environment, integrator). `[[structure.sections]]`
//! cut it by arc length (`to`, m; the last runs to the end), each with a
//! `fidelity` (`sections`): the nonlinear unit at any mesh (`nonlinear`), seed
//! 000's cable (`cable`), or an external FMU with either's ports; a section may
//! be physical (artefacts on its cut signals). What crosses a cut is in `cuts`;
//! `reference` adds the whole structure as one unit (`<name>_reference`), the
//! monolithic twin; `top_load` loads the top from other units (`load`).
//!
//! A model of `kind = "line3d"` is a 3D line, written out by [`line3d`].
//!
//! With `static_start`, the whole structure's equilibrium is solved once here
//! (`statics`); each section starts its own static solve from that shape, each
//! moving cut end is placed where the equilibrium puts it (`velocity_from`) and
//! each loaded one takes the equilibrium's force as its first guess, so the
//! master's initial iterations find the same state.

mod cable;
mod chord;
mod cuts;
mod error;
mod hang_off;
mod layout;
mod line3d;
mod load;
mod model;
mod nonlinear;
mod reduced;
mod refusals;
mod sections;
mod spec;
mod static_fidelity;
mod statics;
mod unit;
mod written;

use cuts::{End, Side};
pub use error::StructureError;
pub use layout::{
    Layout, SectionLayout, SectionOutputs, layout, reference_name, takes_model_mesh, unit_name,
    write_choice, write_training,
};
pub(crate) use line3d::Line3dStructure;
pub use sections::FIDELITIES;
pub(crate) use sections::SectionFile;
use sections::{Cut, Fidelity, Segment};
use slender_units::Time;
use slender_units::nonlinear::NonlinearParams;
use slender_units::nonlinear::params::{DofCondition, EndKind};
use spec::Spec;
pub(crate) use spec::typed;
use toml::Value;
pub(crate) use unit::{Parameters, SectionUnit};
pub(crate) use written::{Link, Written};

/// Writes out the `[structure]` table `structure` as typed units and
/// connections, its statics solved at the simulation's start `t0`. The error
/// names the key.
pub(crate) fn expand(structure: &Value, t0: Time) -> Result<Written, StructureError> {
    let structure = structure
        .as_table()
        .ok_or("`structure`: expected a table")?;
    if line3d::is_3d(structure) {
        return Ok(line3d::expand(structure, t0)?);
    }
    let spec = Spec::parse(structure)?;
    let (built, cuts) = Built::new(spec, t0)?;
    let force_on_upper = orientation(&cuts, built.statics.is_some(), built.holding_static)?;
    let mut units = Vec::new();
    let mut connections = Vec::new();
    let mut advisories = Vec::new();
    for k in 0..cuts.len() {
        units.push(built.section(&cuts, k, &force_on_upper)?);
        advisories.extend(built.advise_on_touchdown(&cuts[k]));
        if cut_is_plain(&cuts, k, built.holding_static) {
            let (links, artefacts) = cuts::cut_connections(
                &built.side(&cuts[k]),
                &built.side(&cuts[k + 1]),
                force_on_upper[k],
            )?;
            connections.extend(links);
            units.extend(artefacts);
        }
    }
    if built.holding_static {
        connections.extend(built.holding_links(&cuts)?);
    }
    for (k, cut) in cuts
        .iter()
        .enumerate()
        .filter(|(_, c)| c.fidelity.is_chord())
    {
        if k > 0 && k + 1 < cuts.len() {
            let unit = |c: &Cut| built.side(c).unit;
            if !(k == 1 && built.holding_static) {
                connections.extend(chord::mover_links(&unit(cut), &unit(&cuts[k - 1])));
            }
            connections.extend(chord::loaded_links(&unit(cut), &unit(&cuts[k + 1])));
        }
    }
    if let (Some(load), Some(last)) = (&built.top_load, cuts.last()) {
        connections.extend(load.links(&built.side(last).unit, last.fidelity));
    }
    if let Some((unit, fidelity)) = built.reference()? {
        if let Some(load) = &built.top_load {
            connections.extend(load.links(&reference_name(&built.name), fidelity));
        }
        units.push(unit);
    }
    let mut written = Written {
        units,
        connections,
        advisories,
    };
    for cut in cuts
        .iter()
        .filter(|c| c.fmu.is_some() && c.fidelity.is_section_unit())
    {
        written.fmu_input_names(&built.side(cut).unit);
    }
    Ok(written)
}

/// Per cut, whether the upper section's end is the loaded side (it carries the
/// force; the lower start moves with its velocity). At each cut one side moves
/// with the other's velocity and the other carries the force: by default the
/// upper section's end moves and the lower start is loaded (the more robust
/// coupling in the tests); with a static start the other way round, so that in
/// the master's first initial iterate every section hangs from what holds it
/// and its own static solve is well posed. Some fidelities fix the way round: a
/// cable's top takes force and its bottom velocity; a reduced section about its stress-free state takes
/// force at both its cuts; a static first section either follows the section
/// above and every section above is held at its end (all cuts the first way
/// round), or, when the structure's end carries a force or a chord section is
/// above it (`holding_static`),
/// takes force and holds the section above; a chord section moves at its start
/// and is loaded at its end.
fn orientation(
    cuts: &[Cut],
    static_start: bool,
    holding_static: bool,
) -> Result<Vec<bool>, String> {
    let mut fixed: Vec<Option<(bool, &Cut)>> = vec![None; cuts.len().saturating_sub(1)];
    let last = cuts.len() - 1;
    for (k, cut) in cuts.iter().enumerate() {
        let place = model::Place {
            k,
            static_start,
            holding_static,
        };
        let needs = cut.fidelity.model().cut_needs(place);
        if let Some(way) = needs.all {
            for c in 0..last {
                require(&mut fixed, c, way, cut)?;
            }
        }
        if let (Some(way), true) = (needs.below, k > 0) {
            require(&mut fixed, k - 1, way, cut)?;
        }
        if let (Some(way), true) = (needs.above, k < last) {
            require(&mut fixed, k, way, cut)?;
        }
    }
    Ok(fixed
        .into_iter()
        .map(|f| f.map_or(static_start, |(way, _)| way))
        .collect())
}

/// Fixes cut `cut` the way `by` needs it (`upper_loaded`), or says which two
/// sections disagree.
fn require<'a>(
    fixed: &mut [Option<(bool, &'a Cut)>],
    cut: usize,
    upper_loaded: bool,
    by: &'a Cut,
) -> Result<(), String> {
    match fixed[cut] {
        Some((way, other)) if way != upper_loaded => {
            let neighbours = other.to == by.from || by.to == other.from;
            let between = if neighbours {
                "the cut between them"
            } else {
                "a cut"
            };
            let advice = if neighbours {
                "put a nonlinear section between them"
            } else {
                "choose another fidelity for one of them"
            };
            Err(format!(
                "`structure.sections.{}.fidelity` = \"{}\" and `structure.sections.{}.fidelity` = \"{}\" need {between} coupled opposite ways (a cable is loaded at its top and moves at its bottom, a reduced section is loaded at both its cuts, a static first section under a held top hangs every section above from their ends); {advice}",
                other.name,
                other.fidelity.name(),
                by.name,
                by.fidelity.name(),
            ))
        }
        _ => {
            fixed[cut] = Some((upper_loaded, by));
            Ok(())
        }
    }
}

/// What every section is built from.
struct Built {
    name: String,
    /// The model as the units take it (a top load as a coupled input).
    model: NonlinearParams,
    segments: Vec<Segment>,
    /// The structure's stress-free length (m).
    length: f64,
    statics: Option<statics::Equilibrium>,
    water: Option<cable::Water>,
    top_load: Option<load::TopLoad>,
    /// The first section is static and takes force (`statics::static_takes_force`).
    holding_static: bool,
    /// The monolithic twin's fidelity, if any.
    reference: Option<Fidelity>,
}

impl Built {
    /// The model as the units take it, with the top placed by its hang-off
    /// angle, and the equilibrium of a static start at `t0`; and the sections.
    fn new(mut spec: Spec, t0: Time) -> Result<(Built, Vec<Cut>), String> {
        let placed = match spec.hang_off {
            Some(angle) => Some(hang_off::place(&mut spec.model, angle, t0)?.1),
            None => None,
        };
        let statics_model = match &spec.top_load {
            Some(load) => load.held_at_rest(&spec.model),
            None => spec.model.clone(),
        };
        if let Some(load) = &spec.top_load {
            load.take_input(&mut spec.model);
        }
        let statics = match (spec.static_start, placed) {
            (_, Some(equilibrium)) => Some(equilibrium),
            (true, None) => Some(statics::Equilibrium::solve(&statics_model, t0)?),
            (false, None) => None,
        };
        // A chord section is loaded at its end and moves at its start, so the
        // section below it cannot hang from it: the static section holds.
        let chord = spec.sections.iter().any(|c| c.fidelity.is_chord());
        let holding_static = spec.sections[0].fidelity == Fidelity::Static
            && (chord || statics::static_takes_force(&statics_model, spec.top_load.is_some()));
        let built = Built {
            holding_static,
            water: spec.water,
            name: spec.name,
            model: spec.model,
            segments: spec.segments,
            length: spec.length,
            statics,
            top_load: spec.top_load,
            reference: spec.reference,
        };
        Ok((built, spec.sections))
    }

    /// Section `k`'s unit.
    fn section(
        &self,
        cuts: &[Cut],
        k: usize,
        force_on_upper: &[bool],
    ) -> Result<SectionUnit, String> {
        let cut = &cuts[k];
        self.refuse_without_seabed(cut)?;
        cut.fidelity.model().refuse(self, cut)?;
        // Per end at a cut: whether this section is the moving (velocity) side,
        // and whether the cut is pinned (a side without bending).
        let start = (k > 0).then(|| End {
            moving: force_on_upper[k - 1],
            pinned: !cuts[k - 1].fidelity.bends() || !cut.fidelity.bends(),
            by_displacement: cuts[k - 1].fidelity.is_chord() || (k == 1 && self.holding_static),
        });
        let end = (k + 1 < cuts.len()).then(|| End {
            moving: !force_on_upper[k],
            pinned: !cuts[k + 1].fidelity.bends() || !cut.fidelity.bends(),
            by_displacement: cuts[k + 1].fidelity.is_chord(),
        });
        let at = model::SectionAt {
            built: self,
            cuts,
            k,
            ends: (start, end),
        };
        let mut unit = cut.fidelity.model().unit(&at)?;
        if let (Some(load), true) = (&self.top_load, k + 1 == cuts.len()) {
            load.first_guess(&mut unit, cut.fidelity);
        }
        if let Some(fmu) = &cut.fmu {
            // The FMU takes the unit's place: same name, ports, first guesses.
            unit.parameters = Parameters::Fmu(fmu.clone());
            unit.effects = None;
        }
        unit.substeps = cut.substeps;
        Ok(unit)
    }

    /// The links between a static first section that takes force and the
    /// section above, which follows its displacement: a `nonlinear` section
    /// by the displacement of its start's DOFs, a chord section by position.
    fn holding_links(&self, cuts: &[Cut]) -> Result<Vec<Link>, String> {
        let above = cuts.get(1).filter(|c| {
            c.physical.is_none()
                && c.fmu.is_none()
                && (c.fidelity.is_section_unit() || c.fidelity.is_chord())
        });
        let (Some(above), Some(equilibrium)) = (above, &self.statics) else {
            return Err(format!(
                "`structure.sections.{}.fidelity` = \"static\": the structure's end carries a force or a chord section is above, so the static first section holds the section above by its displacement; that section must be numerical and `nonlinear`, `beam` or `span`",
                cuts[0].name
            ));
        };
        let at = cuts[0].to;
        let rest = equilibrium.displacement_at(at);
        let (ports, offsets) = if above.fidelity.is_chord() {
            let p = equilibrium.position_at(at);
            (
                ["start_position_x", "start_position_z", "start_rotation"],
                [p[0], p[1], rest[2]],
            )
        } else {
            (
                [
                    "start_displacement_x",
                    "start_displacement_z",
                    "start_rotation",
                ],
                rest,
            )
        };
        Ok(statics::holding_links(
            &self.side(&cuts[0]).unit,
            &self.side(above).unit,
            ports,
            offsets,
        ))
    }

    /// How a cut sees a section.
    fn side<'a>(&self, cut: &'a Cut) -> Side<'a> {
        Side {
            section: &cut.name,
            unit: unit_name(&self.name, &cut.name),
            fidelity: cut.fidelity,
            physical: cut.physical.as_ref(),
        }
    }

    /// The monolithic twin `<name>_reference` (`reference = true` or
    /// "nonlinear": the model as one unit; "cable": the whole structure as one
    /// cable) and its fidelity; None without one.
    fn reference(&self) -> Result<Option<(SectionUnit, Fidelity)>, String> {
        let Some(fidelity) = self.reference else {
            return Ok(None);
        };
        let mut unit = if fidelity == Fidelity::Cable {
            let whole = [Cut {
                name: "reference".into(),
                from: 0.0,
                to: self.length,
                fidelity,
                elements: None,
                substeps: None,
                physical: None,
                fmu: None,
                options: None,
            }];
            cable_fits(&self.model, &whole, 0, self.top_load.is_some())?;
            cable::cable_unit(
                &self.name,
                &self.model,
                &self.segments,
                &whole[0],
                self.water,
                self.model.start,
            )?
        } else {
            SectionUnit::nonlinear(reference_name(&self.name), self.model.clone())
        };
        if let Some(load) = &self.top_load {
            load.first_guess(&mut unit, fidelity);
        }
        Ok(Some((unit, fidelity)))
    }
}

/// Whether section `k` can be a cable: its top takes a coupled force, so it
/// cannot end the structure, and its bottom a coupled velocity, so at the
/// structure's start it must be anchored (x and z held).
fn cable_fits(
    model: &NonlinearParams,
    cuts: &[Cut],
    k: usize,
    top_load: bool,
) -> Result<(), String> {
    let key = format!("structure.sections.{}.fidelity", cuts[k].name);
    if k + 1 == cuts.len() && !top_load {
        return Err(format!(
            "`{key}` = \"cable\": the cable's top takes a coupled force, so a cable can be the structure's last section only under `structure.top_load`; otherwise give the end to a nonlinear section"
        ));
    }
    if k == 0 {
        let start = &model.ends.start;
        let held = |dof: &Option<DofCondition>| *dof == Some(DofCondition::Held);
        let anchored = matches!(start.kind, EndKind::Fixed | EndKind::Pinned)
            || (held(&start.x) && held(&start.z));
        if !anchored {
            return Err(format!(
                "`{key}` = \"cable\": a cable at the structure's start needs an anchor there (`structure.model.ends.start`: kind \"pinned\" or \"fixed\")"
            ));
        }
    }
    Ok(())
}

/// Whether cut `k` (between sections k and k + 1) takes the plain velocity and
/// force links: there is a section above it and neither side is a chord
/// section (whose links `chord::chord_links` writes).
fn cut_is_plain(cuts: &[Cut], k: usize, holding_static: bool) -> bool {
    let beside_chord =
        k + 1 < cuts.len() && (cuts[k].fidelity.is_chord() || cuts[k + 1].fidelity.is_chord());
    let held_below = k == 0 && holding_static;
    k + 1 < cuts.len() && !beside_chord && !held_below
}
