//! The static start of a cut structure: the whole structure's equilibrium, solved
//! once while the scene is written out, gives each section its start shape and
//! the displacement of its cut start, so every section's own static solve and the
//! master's initial iterations land on that equilibrium.

use super::unit::{Parameters, SectionUnit};
use super::written::Link;
use slender_units::beam::boundary::TimeFunction;
use slender_units::nonlinear::params::{DofCondition, End, EndKind, StartShape};
use slender_units::nonlinear::{NonlinearParams, NonlinearSection};
use slender_units::static_section::{Linearised, StaticSectionParams};
use slender_units::{Driver, Time, Unit};

/// The whole structure at rest in equilibrium.
pub(super) struct Equilibrium {
    section: Driver<NonlinearSection>,
    /// When it holds: the simulation's start.
    t0: Time,
}

/// Points per metre of the start shape handed to each section (at least 20).
const POINTS_PER_METRE: f64 = 2.0;

impl Equilibrium {
    /// Solves the model's statics at `t0` (the simulation's start: the ends'
    /// positions and the loads there); the error says why it cannot.
    pub(super) fn solve(model: &NonlinearParams, t0: Time) -> Result<Equilibrium, String> {
        let unit =
            NonlinearSection::new(model.clone()).map_err(|e| format!("`structure.model`: {e}"))?;
        if !unit.description().inputs.is_empty() {
            return Err("`structure.model.static_start`: the structure's statics are solved on their own, so its ends cannot take coupled inputs".into());
        }
        let mut section = Driver::new(unit);
        section.initialize(t0).map_err(|e| {
            format!("`structure.model.static_start`: the whole structure's statics: {e}")
        })?;
        Ok(Equilibrium { section, t0 })
    }

    /// Sets a section's static start (its parameters): the equilibrium shape
    /// over [from, to] as its start polyline, and its moving cut ends (each
    /// DOF coupled by `velocity`) where the equilibrium puts them.
    pub(super) fn start_section(&self, parameters: &mut NonlinearParams, (from, to): (f64, f64)) {
        let section = self.section.unit();
        let points = ((to - from) * POINTS_PER_METRE).ceil().max(20.0) as usize;
        parameters.static_start = true;
        parameters.start_shape = StartShape::Points;
        parameters.start_points = (0..=points)
            .map(|k| section.position_at(from + (to - from) * k as f64 / points as f64))
            .collect();
        let ends = &mut parameters.ends;
        for (end, at) in [(&mut ends.start, from), (&mut ends.end, to)] {
            let dofs = [&mut end.x, &mut end.z, &mut end.rotation];
            for (condition, d) in dofs.into_iter().zip(self.displacement_at(at)) {
                if *condition == Some(DofCondition::Velocity) {
                    *condition = Some(DofCondition::VelocityFrom(d));
                }
            }
        }
    }

    /// The force (N) the structure beyond arc length `s` exerts on the part
    /// before it in the equilibrium: the tension along the tangent (the shear of
    /// the bending is left out; it serves as a first guess of a cut's force).
    pub(super) fn force_at(&self, s: f64) -> [f64; 2] {
        let section = self.section.unit();
        let h = 1e-6 * section.model().arc.last().copied().unwrap_or(1.0);
        let (p0, p1) = (section.position_at(s - h), section.position_at(s + h));
        let chord = ((p1[0] - p0[0]).powi(2) + (p1[1] - p0[1]).powi(2)).sqrt();
        let tension = section.section_forces(s)[0];
        [
            tension * (p1[0] - p0[0]) / chord,
            tension * (p1[1] - p0[1]) / chord,
        ]
    }

    /// A section's loaded cut ends (`loaded`: start, end) take the equilibrium's
    /// force there as the first guess of their force inputs, so each section's
    /// static solve in the master's first initial iterate hangs as the whole
    /// structure does (the master iterates the moment and the rest).
    pub(super) fn first_guess_loads(
        &self,
        unit: &mut SectionUnit,
        (from, to): (f64, f64),
        loaded: (bool, bool),
    ) {
        if loaded.0 {
            // The force on a start is the part before's pull on the part after.
            let f = self.force_at(from);
            unit.first_guess_force("start", [-f[0], -f[1]]);
        }
        if loaded.1 {
            unit.first_guess_force("end", self.force_at(to));
        }
    }

    /// The equilibrium's nodes (x, z in m) with x moved by `shift` (m) times
    /// their arc fraction: the start shape of a nearby equilibrium's solve,
    /// its end moved by `shift` in x (the hang-off's next trial).
    pub(super) fn nodes_moved_by(&self, shift: f64) -> Vec<[f64; 2]> {
        let section = self.section.unit();
        let arc = &section.model().arc;
        let length = arc.last().copied().unwrap_or(1.0);
        (arc.iter())
            .map(|&s| {
                let [x, z] = section.position_at(s);
                [x + shift * s / length, z]
            })
            .collect()
    }

    /// The angle (deg) between the vertical and the pipe's tangent line at
    /// the structure's end (0 hanging straight down or standing straight up).
    pub(super) fn end_angle_from_vertical(&self) -> f64 {
        let section = self.section.unit();
        let angle = section.tangent_angle_at_node(section.model().reference.len() - 1);
        angle.cos().abs().atan2(angle.sin().abs()).to_degrees()
    }

    /// The first and last arc lengths (m) in [from, to] where a node of the
    /// equilibrium lies on a flat seabed at `height` (m; pressed into it, as
    /// contact presses), None where none does.
    pub(super) fn on_seabed(&self, (from, to): (f64, f64), height: f64) -> Option<(f64, f64)> {
        let section = self.section.unit();
        let arcs = section.model().arc.iter().copied();
        let lying: Vec<f64> = arcs
            .filter(|&s| s >= from - 1e-9 && s <= to + 1e-9)
            .filter(|&s| section.position_at(s)[1] < height)
            .collect();
        Some((*lying.first()?, *lying.last()?))
    }

    /// Position (m) at arc length `s` in the equilibrium.
    pub(super) fn position_at(&self, s: f64) -> [f64; 2] {
        self.section.unit().position_at(s)
    }

    /// The `static_section` unit `name` of `section` (a `nonlinear` unit's
    /// parameters over [from, to] of arc length): the end force and moment and the start reaction
    /// of the section's own static solve with its end held where the equilibrium
    /// puts it, and their derivatives with the end's position by central
    /// differences (steps of 1e-5 of the section's length and 1e-5 rad); six
    /// more static solves. Where the section touches the seabed, also its
    /// touchdown point (where the gap crosses zero, continuous in the state)
    /// and its largest sag-bend moment: the static touchdown estimate. The
    /// error names `key`.
    pub(super) fn static_section(
        &self,
        key: &str,
        name: String,
        section: &NonlinearParams,
        (from, to): (f64, f64),
    ) -> Result<SectionUnit, String> {
        let (base, columns) = self
            .end_held_derivatives(section, (from, to))
            .map_err(|e| format!("`{key}` = \"static\": {e}"))?;
        let row = |i: usize| std::array::from_fn(|j| columns[j][i]);
        let touchdown = base[5].is_finite() && columns.iter().all(|c| c[5].is_finite());
        let quantity = |name: &str, unit: &str, i: usize| Linearised {
            name: name.into(),
            unit: unit.into(),
            value: base[i],
            gradient: row(i),
        };
        let parameters = StaticSectionParams {
            stiffness: std::array::from_fn(row),
            force: [base[0], base[1], base[2]],
            start_stiffness: [row(3), row(4)],
            start_force: [base[3], base[4]],
            force_input: false,
            quantities: match touchdown {
                true => vec![
                    quantity("touchdown", "m", 5),
                    quantity("sagbend_moment", "N.m", 6),
                ],
                false => Vec::new(),
            },
        };
        Ok(SectionUnit::new(
            name,
            Parameters::Static(Box::new(parameters)),
        ))
    }

    /// A section's static response with its end held where the equilibrium
    /// puts it (`end_held_response`), and its derivatives with the end's
    /// position (x, z, rotation: one column each) by central differences,
    /// steps of 1e-5 of the section's length and 1e-5 rad; seven static solves.
    fn end_held_derivatives(
        &self,
        section: &NonlinearParams,
        (from, to): (f64, f64),
    ) -> Result<([f64; RESPONSES], [[f64; RESPONSES]; 3]), String> {
        let at_rest = self.displacement_at(to);
        let length = to - from;
        let steps = [1e-5 * length, 1e-5 * length, 1e-5];
        let response = |d: [f64; 3]| end_held_response(section, d, self.t0);
        let base = response(at_rest)?;
        let mut columns = [[0.0; RESPONSES]; 3];
        for (j, column) in columns.iter_mut().enumerate() {
            let (mut plus, mut minus) = (at_rest, at_rest);
            plus[j] += steps[j];
            minus[j] -= steps[j];
            let (p, m) = (response(plus)?, response(minus)?);
            for i in 0..RESPONSES {
                column[i] = (p[i] - m[i]) / (2.0 * steps[j]);
            }
        }
        Ok((base, columns))
    }

    /// The static stiffness of a section's end (N/m, N, N m: rows the end's
    /// force x, z and moment, columns its displacement x, z and rotation)
    /// about the equilibrium, its start held there: what a chord section's
    /// neighbour feels when it moves the section's end slowly. Sag and seabed
    /// contact make it far softer along the chord than EA over the length.
    pub(super) fn end_stiffness(
        &self,
        section: &NonlinearParams,
        (from, to): (f64, f64),
    ) -> Result<[[f64; 3]; 3], String> {
        let (_, columns) = self.end_held_derivatives(section, (from, to))?;
        Ok(std::array::from_fn(|i| {
            std::array::from_fn(|j| columns[j][i])
        }))
    }

    /// The axial force (N, tension positive) at arc length `s`.
    pub(super) fn tension_at(&self, s: f64) -> f64 {
        self.section.unit().section_forces(s)[0]
    }

    /// Displacement (x, z from the stress-free position, m; rotation, rad) at arc
    /// length `s`, linear between the nodes.
    pub(super) fn displacement_at(&self, s: f64) -> [f64; 3] {
        let section = self.section.unit();
        let model = section.model();
        let (e, xi) = model.locate(s);
        let q = section.displacements();
        std::array::from_fn(|k| (1.0 - xi) * q[3 * e + k] + xi * q[3 * e + 3 + k])
    }
}

/// Whether a static first section takes the force at its end and holds the
/// section above where its compliance puts it (rather than following that
/// section's velocity and returning force): when the structure's end carries
/// a force in x or z (a tensioner, a top load), the sections above cannot all
/// be held at their ends, so the static section holds them (`Built::new` also
/// makes it hold under a chord section, for the same reason).
pub(super) fn static_takes_force(model: &NonlinearParams, top_load: bool) -> bool {
    let end = &model.ends.end;
    let forced = |dof: &Option<DofCondition>| matches!(dof, Some(DofCondition::Force(_)));
    top_load || forced(&end.x) || forced(&end.z)
}

/// The links of the cut above a static first section that takes force
/// (`static_unit`): the force and moment of the section above's start in, its
/// displacement out (`offsets`: the equilibrium's values the neighbour's ports
/// count from; `ports`: the neighbour's x, z and rotation port names).
pub(super) fn holding_links(
    static_unit: &str,
    above: &str,
    ports: [&str; 3],
    offsets: [f64; 3],
) -> Vec<Link> {
    let mut links = Vec::new();
    let outputs = ["end_displacement_x", "end_displacement_z", "end_rotation"];
    let loads = ["force_x", "force_z", "moment"];
    for k in 0..3 {
        links.push(
            Link::new(
                format!("{static_unit}.{}", outputs[k]),
                format!("{above}.{}", ports[k]),
            )
            .with_offset(offsets[k]),
        );
        links.push(Link::new(
            format!("{above}.start_{}", loads[k]),
            format!("{static_unit}.end_{}", loads[k]),
        ));
    }
    links
}

/// What `end_held_response` returns.
const RESPONSES: usize = 7;

/// End force x, z, end moment, start reaction x, z, the touchdown point (where
/// the seabed gap crosses zero; NaN without contact) and the largest sag-bend
/// moment of a `nonlinear` section's static solve with its end displaced by `d`
/// (x, z, rotation) from the stress-free position.
fn end_held_response(
    section: &NonlinearParams,
    d: [f64; 3],
    t0: Time,
) -> Result<[f64; RESPONSES], String> {
    let mut params = section.clone();
    let held = |d: f64| Some(DofCondition::Displacement(TimeFunction::Constant(d)));
    params.ends.end = End {
        kind: EndKind::Free,
        x: held(d[0]),
        z: held(d[1]),
        rotation: held(d[2]),
    };
    params.static_start = true;
    let unit = NonlinearSection::new(params).map_err(|e| e.to_string())?;
    let names: Vec<String> = unit
        .description()
        .outputs
        .iter()
        .map(|p| p.name.clone())
        .collect();
    let mut section = Driver::new(unit);
    section
        .initialize(t0)
        .map_err(|e| format!("the section's static solve with its end held: {e}"))?;
    let mut out = vec![0.0; names.len()];
    section.outputs(&mut out).map_err(|e| e.to_string())?;
    let pick = |name: &str| {
        names
            .iter()
            .position(|n| n == name)
            .map(|i| out[i])
            .ok_or(format!("the section has no output `{name}`"))
    };
    Ok([
        pick("end_force_x")?,
        pick("end_force_z")?,
        pick("end_moment")?,
        pick("start_force_x")?,
        pick("start_force_z")?,
        section.unit().seabed_crossing().unwrap_or(f64::NAN),
        pick("sagbend_moment")?,
    ])
}
