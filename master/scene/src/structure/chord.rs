//! The `beam` and `span` fidelities of a section: a `chord` unit, seed 004's
//! small-deflection FE beam or the span's transfer matrix, both with the
//! equilibrium's tension, about the straight line between the section's ends
//! in the structure's equilibrium. Its cuts are not the velocity and force of
//! the other fidelities: at its moving end it reads the neighbour's position
//! and rotation and returns force and moment; at its loaded end it reads the
//! neighbour's force and moment and hands back a displacement, which that
//! neighbour follows (`displacement` conditions on a `nonlinear` start). The
//! moving end is the section's start, the loaded end its end
//! (`mod.rs::orientation`); below it may be a static first section that takes
//! force (`statics::static_takes_force`).

use super::cuts::End;
use super::model::{CutNeeds, Place, SectionAt, SectionModel};
use super::nonlinear::section_parameters;
use super::sections::{Cut, Fidelity, Segment};
use super::spec::typed;
use super::statics::Equilibrium;
use super::unit::{Parameters, SectionUnit};
use super::written::Link;
use serde::Deserialize;
use slender_units::chord::{ChordModel, ChordParams, MovingEnd};
use slender_units::nonlinear::NonlinearParams;

/// A chord fidelity: its name, the keys of its table form and what a count
/// sets.
pub(super) struct Chord {
    name: &'static str,
    keys: &'static [&'static str],
    count: &'static str,
}

/// The `beam` fidelity: seed 004's FE beam with tension about the chord.
pub(super) const BEAM: Chord = Chord {
    name: "beam",
    keys: &BEAM_KEYS,
    count: "elements",
};

/// The `span` fidelity: the span's transfer matrix with tension about the
/// chord.
pub(super) const SPAN: Chord = Chord {
    name: "span",
    keys: &SPAN_KEYS,
    count: "order",
};

/// The keys of `{ kind = "beam", ... }`: the `chord` unit's beam settings.
const BEAM_KEYS: [&str; 5] = [
    "kind",
    "elements",
    "alpha",
    "damping_per_length",
    "drag_velocity",
];

/// The keys of `{ kind = "span", ... }`: the `chord` unit's span settings.
const SPAN_KEYS: [&str; 6] = [
    "kind",
    "order",
    "band",
    "alpha",
    "damping_per_length",
    "drag_velocity",
];

impl SectionModel for Chord {
    fn name(&self) -> &'static str {
        self.name
    }
    fn option_keys(&self) -> &'static [&'static str] {
        self.keys
    }
    fn count_key(&self) -> &'static str {
        self.count
    }
    fn is_chord(&self) -> bool {
        true
    }
    fn has_seabed(&self) -> bool {
        false
    }
    /// It moves at its start and is loaded at its end.
    fn cut_needs(&self, _: Place) -> CutNeeds {
        CutNeeds::MOVING_START_LOADED_END
    }
    fn unit(&self, at: &SectionAt) -> Result<SectionUnit, String> {
        let built = at.built;
        let statics = built.statics.as_ref();
        chord_unit(
            &built.name,
            &built.model,
            &built.segments,
            at.cuts,
            at.k,
            statics,
        )
    }
}

/// Points per section for the centre of its weight.
const WEIGHT_POINTS: usize = 200;
/// The transverse velocity amplitude (m/s) the section's drag is linearised at
/// when the scene gives neither `damping_per_length` nor `drag_velocity`.
const DEFAULT_DRAG_VELOCITY: f64 = 0.5;
/// The span fidelity's default numerical damping (theta = 1/2 + alpha): at the
/// trapezoidal rule's theta = 1/2 the fit's poles near the coupling step's
/// Nyquist frequency are undamped, and on the S-lay under a static touchdown
/// section a two-step oscillation of the cut forces grew until the stinger's
/// Newton failed (15.5 s); 0.02 runs it through and moves the errors of the
/// nonlinear-touchdown combination by less than 1 % of themselves.
const DEFAULT_SPAN_ALPHA: f64 = 0.02;

/// How far (max - min over the mean) the equilibrium's tension may vary along
/// a `span` section: the span's transfer matrix takes one tension. On the
/// hanging pipe's middle (a factor of 2, 0.67) the span coupled unstably at
/// every step tried; the S-lay's suspended span varies by a few per cent.
const SPAN_TENSION_VARIATION: f64 = 0.5;

/// Refuses a `span` on a section whose equilibrium tension varies more than
/// `SPAN_TENSION_VARIATION` (its ends and middle), naming the range.
fn uniform_enough(equilibrium: &Equilibrium, cut: &Cut, key: &str) -> Result<(), String> {
    if cut.fidelity != Fidelity::Span {
        return Ok(());
    }
    let at = [cut.from, 0.5 * (cut.from + cut.to), cut.to].map(|s| equilibrium.tension_at(s));
    let (low, high) = at
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &t| {
            (l.min(t), h.max(t))
        });
    let mean = at.iter().sum::<f64>() / 3.0;
    let variation = (high - low) / mean.abs();
    if variation > SPAN_TENSION_VARIATION || !variation.is_finite() {
        return Err(format!(
            "`{key}` = \"span\": the span's transfer matrix takes one tension, and this section's equilibrium tension runs from {low:.4e} to {high:.4e} N ({:.0} % of its mean; at most {:.0} %), where the span couples unstably with its neighbours (a hanging pipe's middle); choose \"beam\" (the tension at its middle) or \"nonlinear\"",
            100.0 * variation,
            100.0 * SPAN_TENSION_VARIATION
        ));
    }
    Ok(())
}

/// The section's stiffness along its chord (N/m) as its loaded end feels it:
/// the end's static stiffness with its start held in the structure's
/// equilibrium (`Equilibrium::end_stiffness`: sag, bending and seabed contact
/// included), inverted to the compliance under a force (the end free to turn
/// and to move across), whose component along the chord is one over this. On
/// the S-lay's sag bend (109.7 to 231.0 m of arc) 6.4e4 N/m where EA over the
/// arc length is 2.5e7: the sag, not the pipe's stretch, gives way.
fn axial_stiffness(
    (model, segments): (&NonlinearParams, &[Segment]),
    cut: &Cut,
    equilibrium: &Equilibrium,
) -> Result<f64, String> {
    let held = End {
        moving: true,
        pinned: false,
        by_displacement: false,
    };
    let mut section = section_parameters(model, segments, cut, (Some(held), Some(held)))?;
    equilibrium.start_section(&mut section, (cut.from, cut.to));
    // The end force is the section's pull on what holds it: its stiffness is
    // the negative of the force's derivative.
    let force_derivative = equilibrium.end_stiffness(&section, (cut.from, cut.to))?;
    let stiffness = force_derivative.map(|row| row.map(|k| -k));
    let (a, b) = (
        equilibrium.position_at(cut.from),
        equilibrium.position_at(cut.to),
    );
    let length = (b[0] - a[0]).hypot(b[1] - a[1]);
    let e = nalgebra::Vector3::new((b[0] - a[0]) / length, (b[1] - a[1]) / length, 0.0);
    let stiffness = nalgebra::Matrix3::from_fn(|i, j| stiffness[i][j]);
    let along = stiffness
        .lu()
        .solve(&e)
        .map_or(f64::NAN, |compliance| 1.0 / e.dot(&compliance));
    if along.is_finite() && along > 0.0 {
        Ok(along)
    } else {
        Err(format!(
            "the section's static stiffness along its chord is {along:.4e} N/m in the equilibrium (expected a positive stiffness: the section must hold its end against a pull)"
        ))
    }
}

/// The `chord` unit of section `k`, its start moving with the section below.
pub(super) fn chord_unit(
    structure: &str,
    model: &NonlinearParams,
    segments: &[Segment],
    cuts: &[Cut],
    k: usize,
    equilibrium: Option<&Equilibrium>,
) -> Result<SectionUnit, String> {
    let cut = &cuts[k];
    let key = format!("structure.sections.{}.fidelity", cut.name);
    let word = cut.fidelity.name();
    let equilibrium = equilibrium.ok_or(format!(
        "`{key}` = \"{word}\": a {word} section moves about its chord in the structure's equilibrium, so the structure needs `structure.model.static_start = true`"
    ))?;
    neighbours_fit(cuts, k, &key)?;
    uniform_enough(equilibrium, cut, &key)?;
    let options: ChordOptions = typed(&key, &cut.options.clone().unwrap_or_default())?;
    let drag_velocity = options.drag_velocity(&key)?;
    let (weight, weight_at) = weight_of(segments, cut, equilibrium);
    let [ei, mass, drag, structural] = properties(model, segments, cut, &key)?;
    let stiffness = axial_stiffness((model, segments), cut, equilibrium)
        .map_err(|e| format!("`{key}` = \"{word}\": {e}"))?;
    // The section's own inertia along the pipe: the loaded end's half of it
    // (the moving end's half is left out: its acceleration would come from
    // differencing its neighbour's positions). The mass of the static shapes
    // the end drags along (the sag's motion across the pipe, 8 times the
    // section's mass on the S-lay) was tried: it doubled the sag-bend error.
    let axial_mass = 0.5 * structural * (cut.to - cut.from);
    let span = cut.fidelity == Fidelity::Span;
    let p = ChordParams {
        model: if span {
            ChordModel::Span
        } else {
            ChordModel::Beam
        },
        moving: MovingEnd::Start,
        start: equilibrium.position_at(cut.from),
        end: equilibrium.position_at(cut.to),
        weight,
        weight_at,
        loaded_end_displacement: equilibrium.displacement_at(cut.to),
        flexural_rigidity: ei,
        mass_per_length: mass,
        damping_per_length: options.damping_per_length.unwrap_or(drag * drag_velocity),
        tension: equilibrium.tension_at(0.5 * (cut.from + cut.to)),
        axial_stiffness: Some(stiffness),
        axial_mass: (axial_mass > 0.0).then_some(axial_mass),
        elements: match span {
            true => ChordParams::DEFAULT_ELEMENTS,
            false => cut.elements.unwrap_or(ChordParams::DEFAULT_ELEMENTS),
        },
        alpha: (options.alpha).unwrap_or(if span { DEFAULT_SPAN_ALPHA } else { 0.0 }),
        order: options.order.unwrap_or(ChordParams::DEFAULT_ORDER),
        band: options.band.unwrap_or(ChordParams::DEFAULT_BAND),
    };
    // First guesses: the equilibrium's force at the loaded end and position at
    // the moving one, so the neighbours' first static solves hang as the whole.
    let force = equilibrium.force_at(cut.to);
    let position = equilibrium.position_at(cut.from);
    let name = super::unit_name(structure, &cut.name);
    let mut unit = SectionUnit::new(name, Parameters::Chord(Box::new(p)));
    for (axis, i) in [("x", 0), ("z", 1)] {
        unit.inputs.insert(format!("end_force_{axis}"), force[i]);
        unit.inputs
            .insert(format!("start_position_{axis}"), position[i]);
    }
    Ok(unit)
}

/// A chord fidelity's own keys as the scene writes them (`{ kind = "span",
/// order = 16, alpha = 0.05 }`; `kind` and `elements` are read by the
/// sections), checked by serde at the section's key.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ChordOptions {
    /// Numerical damping of the chord unit's integrator.
    alpha: Option<f64>,
    /// Linear damping per length (N s/m^2) in place of the drag's.
    damping_per_length: Option<f64>,
    /// The velocity amplitude (m/s) the drag is linearised at.
    drag_velocity: Option<f64>,
    /// The span fit's order.
    order: Option<usize>,
    /// The span fit's band (rad/s).
    band: Option<f64>,
}

impl ChordOptions {
    /// `drag_velocity` (m/s), or the default.
    fn drag_velocity(&self, key: &str) -> Result<f64, String> {
        match self.drag_velocity {
            None => Ok(DEFAULT_DRAG_VELOCITY),
            Some(v) if v >= 0.0 && v.is_finite() => Ok(v),
            Some(v) => Err(format!(
                "`{key}.drag_velocity` = {v}: expected a velocity amplitude >= 0 (m/s)"
            )),
        }
    }
}

/// A chord section lies between two numerical sections that follow its
/// displacement or carry its force: `nonlinear` ones, or a static first section
/// below it.
fn neighbours_fit(cuts: &[Cut], k: usize, key: &str) -> Result<(), String> {
    let word = cuts[k].fidelity.name();
    if k == 0 || k + 1 == cuts.len() {
        return Err(format!(
            "`{key}` = \"{word}\": a {word} section moves about its chord between two neighbours, so it cannot be the structure's first or last section"
        ));
    }
    for (n, neighbour) in [(k - 1, &cuts[k - 1]), (k + 1, &cuts[k + 1])] {
        let fits = neighbour.physical.is_none()
            && neighbour.fmu.is_none()
            && (neighbour.fidelity.is_section_unit()
                || (n == 0 && neighbour.fidelity == Fidelity::Static));
        if !fits {
            return Err(format!(
                "`{key}` = \"{word}\": its neighbour `{}` is {}; a {word} section couples by position and force to numerical `nonlinear` sections (or a static first section below it)",
                neighbour.name,
                if neighbour.physical.is_some() {
                    "physical"
                } else if neighbour.fmu.is_some() {
                    "an FMU"
                } else {
                    neighbour.fidelity.name()
                }
            ));
        }
    }
    Ok(())
}

/// EI (N m^2), the transversely moving mass per length (kg/m, with the added
/// mass Ca rho pi D^2 / 4) and the normal drag's linear damping per unit of
/// velocity amplitude (8 / (3 pi) rho / 2 Cd D, N s/m^2 per m/s: the harmonic
/// equivalent linearisation) and the structural mass per length (kg/m,
/// moving along the pipe) of the segments the section spans; one value each,
/// or an error.
fn properties(
    model: &NonlinearParams,
    segments: &[Segment],
    cut: &Cut,
    key: &str,
) -> Result<[f64; 4], String> {
    let density = model.water_density;
    let mut found: Option<[f64; 4]> = None;
    for s in segments
        .iter()
        .filter(|s| s.overlap(cut.from, cut.to) > 0.0)
    {
        let t = &s.properties;
        let ei = t.bending_stiffness;
        let diameter = t.diameter;
        let added = t.added_mass_normal * density * std::f64::consts::PI * diameter.powi(2) / 4.0;
        let structural = t.mass_per_length;
        let mass = structural + added;
        let drag = 8.0 / (3.0 * std::f64::consts::PI) * 0.5 * density * t.drag_normal * diameter;
        match found {
            Some(f)
                if (f[0] - ei).abs() > 1e-9 * f[0].abs() || (f[1] - mass).abs() > 1e-9 * f[1] =>
            {
                return Err(format!(
                    "`{key}`: the section spans segments of different bending stiffness or mass; a chord section takes one of each, so cut at the segments' joint"
                ));
            }
            _ => found = Some([ei, mass, drag, structural]),
        }
    }
    found.ok_or(format!("`{key}`: the section is empty"))
}

/// The section's submerged weight (N) and where it acts in the equilibrium (m).
fn weight_of(segments: &[Segment], cut: &Cut, equilibrium: &Equilibrium) -> (f64, [f64; 2]) {
    let per_length = |s: f64| {
        segments
            .iter()
            .find(|g| s >= g.from && s <= g.from + g.length)
            .map_or(0.0, |g| g.properties.submerged_weight)
    };
    let ds = (cut.to - cut.from) / WEIGHT_POINTS as f64;
    let (mut weight, mut moment) = (0.0, [0.0; 2]);
    for i in 0..WEIGHT_POINTS {
        let s = cut.from + (i as f64 + 0.5) * ds;
        let w = per_length(s) * ds;
        let p = equilibrium.position_at(s);
        weight += w;
        moment = [moment[0] + w * p[0], moment[1] + w * p[1]];
    }
    if weight.abs() > 0.0 {
        (weight, [moment[0] / weight, moment[1] / weight])
    } else {
        let (a, b) = (
            equilibrium.position_at(cut.from),
            equilibrium.position_at(cut.to),
        );
        (0.0, [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])])
    }
}

/// The links at a chord section's moving start: the position and rotation of
/// `below`'s end in, the force and moment on it out.
pub(super) fn mover_links(chord: &str, below: &str) -> Vec<Link> {
    let mut links = Vec::new();
    for (q, r) in [
        ("position_x", "force_x"),
        ("position_z", "force_z"),
        ("rotation", "moment"),
    ] {
        links.push(Link::new(
            format!("{below}.end_{q}"),
            format!("{chord}.start_{q}"),
        ));
        links.push(Link::new(
            format!("{chord}.start_{r}"),
            format!("{below}.end_{r}"),
        ));
    }
    links
}

/// The links at a chord section's loaded end: the force and moment of
/// `above`'s start in, the displacement it follows out.
pub(super) fn loaded_links(chord: &str, above: &str) -> Vec<Link> {
    let mut links = Vec::new();
    for (q, r) in [
        ("force_x", "displacement_x"),
        ("force_z", "displacement_z"),
        ("moment", "rotation"),
    ] {
        links.push(Link::new(
            format!("{above}.start_{q}"),
            format!("{chord}.end_{q}"),
        ));
        links.push(Link::new(
            format!("{chord}.end_{r}"),
            format!("{above}.start_{r}"),
        ));
    }
    links
}
