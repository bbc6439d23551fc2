//! The `cable` fidelity of a structure's section: seed 000's cable unit (bar
//! elements, linear about its static state, exact Morison drag) over the
//! section's arc-length range, in the cable's own frame (z up from the seabed).
//!
//! The cable has no bending stiffness, so its cuts are pinned: force and velocity
//! cross them, rotation and moment do not (the neighbouring section's end turns
//! freely). The section takes its static state from the force at its top (a
//! `full` line), so it needs the structure's static start to place its anchor
//! where the equilibrium puts the section's start.

use super::cable_fits;
use super::model::{CutNeeds, Place, SectionAt, SectionModel};
use super::sections::{Cut, Segment};
use super::unit::{Parameters, SectionUnit};
use slender_units::cable::current::CurrentProfile;
use slender_units::cable::params::{DEFAULT_DRAG_TOLERANCE, DEFAULT_STATIC_TOLERANCE};
use slender_units::cable::{CableParams, Section as CableSection};
use slender_units::nonlinear::NonlinearParams;
use slender_units::nonlinear::params::{Current, Segment as ModelSegment};

/// The `cable` fidelity.
pub(super) struct Cable;

impl SectionModel for Cable {
    fn name(&self) -> &'static str {
        "cable"
    }
    fn bends(&self) -> bool {
        false
    }
    fn has_seabed(&self) -> bool {
        false
    }
    fn end_names(&self) -> [&'static str; 2] {
        ["bottom", "top"]
    }
    /// Its top takes force, its bottom velocity.
    fn cut_needs(&self, _: Place) -> CutNeeds {
        CutNeeds::MOVING_START_LOADED_END
    }
    fn unit(&self, at: &SectionAt) -> Result<SectionUnit, String> {
        let (built, cuts, k, cut) = (at.built, at.cuts, at.k, at.cut());
        cable_fits(&built.model, cuts, k, built.top_load.is_some())?;
        let anchor = built.statics.as_ref().map(|e| e.position_at(cut.from)).ok_or(format!(
            "`structure.sections.{}.fidelity` = \"cable\": a cable section takes its static state from its top force, so the structure needs `structure.model.static_start = true` to place it",
            cut.name
        ))?;
        let mut unit = cable_unit(
            &built.name,
            &built.model,
            &built.segments,
            cut,
            built.water,
            anchor,
        )?;
        // Its static state needs the force at its top in the master's first
        // initial iterate: the equilibrium's, as the first guess.
        if let (Some(e), true) = (&built.statics, k + 1 < cuts.len()) {
            unit.first_guess_force("top", e.force_at(cut.to));
        }
        Ok(unit)
    }
}

/// Where the structure's frame puts the water: the seabed height (m, in the
/// structure's frame) and the water depth (m).
#[derive(Copy, Clone, Debug)]
pub(super) struct Water {
    pub seabed: f64,
    pub depth: f64,
}

impl Water {
    /// `structure.seabed` (default 0) and `structure.water_depth` (needed by a
    /// cable section only: `None` when absent), both m.
    pub(super) fn of(seabed: Option<f64>, depth: Option<f64>) -> Result<Option<Water>, String> {
        for (key, value) in [("seabed", seabed), ("water_depth", depth)] {
            if value.is_some_and(|v| !v.is_finite()) {
                return Err(format!("`structure.{key}`: expected a number (m)"));
            }
        }
        let seabed = seabed.unwrap_or(0.0);
        match depth {
            Some(depth) if depth > 0.0 => Ok(Some(Water { seabed, depth })),
            Some(depth) => Err(format!(
                "`structure.water_depth` = {depth}: expected a depth > 0 m"
            )),
            None => Ok(None),
        }
    }
}

/// A cable section carries no supports or distributed loads: refused rather
/// than dropped where the model has them in its range.
fn carries_nothing_along(
    key: &str,
    model: &NonlinearParams,
    segments: &[Segment],
    cut: &Cut,
) -> Result<(), String> {
    let length = segments.iter().map(|s| s.length).sum();
    let along = super::nonlinear::along(model, cut, length)?;
    let carried = [
        ("supports", along.supports.is_empty()),
        ("loads", along.loads.is_empty()),
    ];
    if let Some((what, _)) = carried.into_iter().find(|(_, none)| !none) {
        return Err(format!(
            "`{key}.fidelity` = \"cable\": the cable carries no `structure.model.{what}`; give this range another fidelity or move the cut"
        ));
    }
    Ok(())
}

/// The `cable` unit of one section, anchored (its bottom node) at `anchor`
/// (structure frame, m).
pub(super) fn cable_unit(
    name: &str,
    model: &NonlinearParams,
    segments: &[Segment],
    cut: &Cut,
    water: Option<Water>,
    anchor: [f64; 2],
) -> Result<SectionUnit, String> {
    let key = format!("structure.sections.{}", cut.name);
    let water = water.ok_or(format!(
        "`{key}.fidelity` = \"cable\": the cable needs `structure.water_depth` (m; and `structure.seabed`, the seabed's z in the structure's frame, default 0)"
    ))?;
    carries_nothing_along(&key, model, segments, cut)?;
    let inside: Vec<&Segment> = segments_in(segments, cut.from, cut.to);
    let first = one_cross_section(&key, &inside)?;
    let diameter = first.diameter;
    if diameter <= 0.0 {
        return Err(format!(
            "`{key}.fidelity` = \"cable\": the cable takes EA as E pi D^2 / 4, so its segments need `diameter` > 0 m"
        ));
    }
    let elements = cut.elements.unwrap_or_else(|| {
        let share: f64 = inside
            .iter()
            .map(|s| s.elements * s.overlap(cut.from, cut.to) / s.length)
            .sum();
        share.round().max(1.0) as usize
    });
    let current = (model.current.as_ref()).map(|c| cable_current(c, water.seabed));
    let p = CableParams {
        length: cut.to - cut.from,
        elements,
        diameter,
        mass_per_length: first.mass_per_length,
        youngs_modulus: first.axial_stiffness / (std::f64::consts::PI * diameter * diameter / 4.0),
        submerged_weight: first.submerged_weight,
        added_mass_normal: first.added_mass_normal,
        added_mass_tangential: first.added_mass_tangential,
        drag_normal: first.drag_normal,
        drag_tangential: first.drag_tangential,
        rayleigh_mass: model.rayleigh_mass,
        rayleigh_stiffness: model.rayleigh_stiffness,
        water_density: model.water_density,
        water_depth: water.depth,
        current: current.unwrap_or_default(),
        anchor: [anchor[0], anchor[1] - water.seabed],
        static_top_force: None,
        section: CableSection::Full,
        static_tolerance: DEFAULT_STATIC_TOLERANCE,
        drag_tolerance: DEFAULT_DRAG_TOLERANCE,
    };
    let effects = effects(&p, model.current.is_some());
    let name = super::unit_name(name, &cut.name);
    Ok(SectionUnit::new(name, Parameters::Cable(Box::new(p))).with_effects(effects))
}

/// A segment's section properties that must be equal along a cable
/// section (the cable unit has one cross-section), by name.
fn uniform_properties(s: &Segment) -> [(&'static str, f64); 9] {
    let p = &s.properties;
    [
        ("axial_stiffness", p.axial_stiffness),
        ("mass_per_length", p.mass_per_length),
        ("submerged_weight", p.submerged_weight),
        ("diameter", p.diameter),
        ("drag_normal", p.drag_normal),
        ("drag_tangential", p.drag_tangential),
        ("added_mass_normal", p.added_mass_normal),
        ("added_mass_tangential", p.added_mass_tangential),
        ("bending_stiffness", p.bending_stiffness),
    ]
}

/// The cross-section of a cable section: its segments must agree on it.
fn one_cross_section<'a>(key: &str, inside: &[&'a Segment]) -> Result<&'a ModelSegment, String> {
    let first = *inside
        .first()
        .ok_or(format!("`{key}`: the section is empty"))?;
    for s in &inside[1..] {
        let pairs = uniform_properties(s)
            .into_iter()
            .zip(uniform_properties(first));
        if let Some(((k, _), _)) = pairs.into_iter().find(|((_, a), (_, b))| a != b) {
            return Err(format!(
                "`{key}.fidelity` = \"cable\": the section's segments differ in `{k}`; the cable unit has one cross-section"
            ));
        }
    }
    Ok(&first.properties)
}

/// The segments overlapping [from, to].
fn segments_in(segments: &[Segment], from: f64, to: f64) -> Vec<&Segment> {
    segments
        .iter()
        .filter(|s| s.overlap(from, to) > 1e-12 * s.length)
        .collect()
}

/// The structure's current table (z in its frame) as the cable's (z above the
/// seabed).
fn cable_current(current: &Current, seabed: f64) -> CurrentProfile {
    CurrentProfile::Table {
        z: current.z.iter().map(|z| z - seabed).collect(),
        speed: current.velocity.clone(),
    }
}

/// The cable effects the section's properties call for; geometric stiffness
/// always (a cable has no transverse stiffness without it).
fn effects(p: &CableParams, current: bool) -> Vec<&'static str> {
    let mut effects = vec!["geometric_stiffness"];
    if p.submerged_weight != 0.0 {
        effects.push("weight");
    }
    if p.added_mass_normal != 0.0 || p.added_mass_tangential != 0.0 {
        effects.push("added_mass");
    }
    let drag = p.drag_normal != 0.0 || p.drag_tangential != 0.0;
    if drag {
        effects.push("drag");
    }
    if drag && current {
        effects.push("current");
    }
    if p.rayleigh_mass != 0.0 || p.rayleigh_stiffness != 0.0 {
        effects.push("structural_damping");
    }
    effects
}
