//! Contact of a section with the seabed (`contact`, which defines the touchdown
//! point) and a stinger (`stinger`). On a continuous surface z >= f(x, t) each
//! node presses with the law's force density times its tributary length along
//! the gradient of the gap d = z - f(x). Rollers are points: each roller's top
//! meets the element passing over it (gap: the element's height there minus the
//! top; the law's force per roller, its penalty in N/m), so a roller supports the
//! pipe wherever it is, not only at nodes. Penalty-type laws act at the current
//! state; the energy-conserving law, under the energy-conserving integrator, acts
//! over a step by its discrete gradient; the augmented laws update their
//! Lagrangian parameter per contact point after each step.

mod points;

use super::model::Model;
use super::params::{Integrator, NodalContact, NonlinearParams};
use crate::contact::surface::Shape;
use crate::contact::{LambdaUpdate, Law};
use crate::contract::UnitError;
use crate::numerics::banded::SymmetricBand;
use points::{Point, for_each_point, for_each_point_of, roller_point, surface_slope};

/// A roller's load on the section at one state: its element, where along
/// it the roller meets it (0 to 1), and what it adds to the internal force
/// (the contact energy's gradient; the force on the pipe is its negative) at
/// the element's six DOFs (N, N m).
#[derive(Copy, Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RollerLoad {
    /// The element the roller meets.
    pub element: usize,
    /// Where along it (0 at its start node, 1 at its end).
    pub xi: f64,
    /// What the roller adds to the internal force at the element's DOFs
    /// (`3 element` to `3 element + 5`: x, z, rotation of each node; N, N m).
    pub force: [f64; 6],
}

impl RollerLoad {
    /// The force on the pipe (N, x and z).
    pub fn on_pipe(&self) -> [f64; 2] {
        [
            -(self.force[0] + self.force[3]),
            -(self.force[1] + self.force[4]),
        ]
    }

    /// What it adds to the internal force at DOF `dof` (N; 0 off its
    /// element).
    pub fn at(&self, dof: usize) -> f64 {
        (dof.checked_sub(3 * self.element))
            .and_then(|k| self.force.get(k))
            .map_or(0.0, |f| *f)
    }
}

/// What the contact did at one state.
#[derive(Copy, Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ContactSummary {
    /// Sum of the tributary lengths on the seabed (m).
    pub length: f64,
    /// Largest penetration of any surface (m).
    pub penetration: f64,
    /// Largest penetration relative to the node's tributary length.
    pub relative_penetration: f64,
    /// Sum of the contact energies w Xi(d) (J).
    pub energy: f64,
    /// The touchdown point as users define it: where the seabed gap crosses
    /// zero, interpolated between the nodes (`NodalContacts::seabed_crossing`),
    /// as arc length from the start (m) and as its x position (m); NaN
    /// without seabed contact.
    pub crossing: [f64; 2],
}

/// The contact surfaces of a section.
#[derive(Clone, Debug, Default)]
pub struct NodalContacts {
    /// Seabed first (when given), then the stinger.
    list: Vec<NodalContact>,
    /// Whether `list[0]` is the seabed (counts for touchdown).
    has_seabed: bool,
    /// Where each surface's Lagrangian parameters start in the state's list.
    offsets: Vec<usize>,
    /// Tributary length of each node (m).
    tributary: Vec<f64>,
    /// Energy-conserving laws act by their discrete gradient over a step.
    discrete: bool,
}

/// Stiffness factor for the tangent band.
pub type ContactTangent<'a> = Option<(&'a mut SymmetricBand, f64)>;

impl NodalContacts {
    /// From the parameters and the mesh.
    pub fn new(params: &NonlinearParams, model: &Model) -> NodalContacts {
        let list: Vec<NodalContact> = params
            .contact
            .iter()
            .chain(&params.stinger)
            .cloned()
            .collect();
        let mut tributary = vec![0.0; model.reference.len()];
        for (e, el) in model.elements.iter().enumerate() {
            tributary[e] += 0.5 * el.length;
            tributary[e + 1] += 0.5 * el.length;
        }
        let mut offsets = vec![0];
        for c in &list {
            let points = match &c.surface.shape {
                Shape::Rollers { positions, .. } => positions.len(),
                _ => tributary.len(),
            };
            offsets.push(offsets.last().unwrap_or(&0) + points);
        }
        let discrete = matches!(params.integrator, Integrator::EnergyConserving { .. })
            && list.iter().any(|c| is_energy_conserving(&c.method));
        NodalContacts {
            has_seabed: params.contact.is_some(),
            list,
            offsets,
            tributary,
            discrete,
        }
    }

    /// Whether there are no surfaces.
    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// Whether a surface moves whose law acts by its discrete gradient
    /// (`discrete`) or by its force at the step's end (not `discrete`).
    pub fn moves_by(&self, discrete: bool) -> bool {
        self.list.iter().any(|c| moves_by(c, discrete))
    }

    /// The contact energy (J) at (q, t) of the moving surfaces whose law acts
    /// by its discrete gradient (`discrete`) or not: what changes at a fixed
    /// shape, for the energy balance.
    pub fn moving_energy(
        &self,
        model: &Model,
        (q, t, lambda): (&[f64], f64, &[f64]),
        discrete: bool,
    ) -> f64 {
        let mut energy = 0.0;
        for (c, contact) in self
            .list
            .iter()
            .enumerate()
            .filter(|(_, c)| moves_by(c, discrete))
        {
            let lambda = &lambda[self.offsets[c]..];
            for_each_point(contact, model, &self.tributary, (q, t), |p| {
                energy += p.weight * contact.method.evaluate(p.gap, lambda[p.index]).0;
            });
        }
        energy
    }

    /// Whether energy-conserving laws act by their discrete gradient.
    pub fn is_discrete(&self) -> bool {
        self.discrete
    }

    /// The Lagrangian parameters at the start, per surface and contact point.
    pub fn initial_lambda(&self) -> Vec<f64> {
        self.list
            .iter()
            .zip(self.offsets.windows(2))
            .flat_map(|(c, w)| std::iter::repeat_n(c.method.lambda0(), w[1] - w[0]))
            .collect()
    }

    /// Adds `scale` times the contact force at `q` (time t) to `out` and its
    /// tangent; with `skip_discrete`, the laws stepped by their discrete gradient
    /// are left out.
    pub fn add_force(
        &self,
        model: &Model,
        (q, t, lambda): (&[f64], f64, &[f64]),
        scale: f64,
        skip_discrete: bool,
        tangent: ContactTangent<'_>,
        out: &mut [f64],
    ) {
        let at = (q, t, lambda, None);
        self.add_force_of(model, at, scale, skip_discrete, tangent, out);
    }

    /// The contact force at `q` (time t) added to `out` as
    /// [`Self::add_force`] adds it, the laws stepped by their discrete
    /// gradient left out, from every roller and the nodal points of nodes
    /// `ends` alone: their DOFs' rows are the whole force's (a section's
    /// step end left for its correction).
    pub fn add_force_at_ends(
        &self,
        model: &Model,
        (q, t, lambda): (&[f64], f64, &[f64]),
        ends: [usize; 2],
        out: &mut [f64],
    ) {
        self.add_force_of(model, (q, t, lambda, Some(ends)), 1.0, true, None, out);
    }

    fn add_force_of(
        &self,
        model: &Model,
        (q, t, lambda, ends): (&[f64], f64, &[f64], Option<[usize; 2]>),
        scale: f64,
        skip_discrete: bool,
        mut tangent: ContactTangent<'_>,
        out: &mut [f64],
    ) {
        for (c, contact) in self.list.iter().enumerate() {
            if skip_discrete && self.discrete && is_energy_conserving(&contact.method) {
                continue;
            }
            let lambda = &lambda[self.offsets[c]..];
            for_each_point_of(contact, model, &self.tributary, (q, t), ends, |p| {
                let (_, g, k) = contact.method.evaluate(p.gap, lambda[p.index]);
                if g == 0.0 && k == 0.0 {
                    return;
                }
                p.add_force(scale * p.weight * g, out);
                if let Some((band, factor)) = tangent.as_mut() {
                    p.add_tangent(band, *factor * p.weight * k);
                }
            });
        }
    }

    /// Each pressing roller's load at `q` (time t) into `out` (cleared
    /// first): what the moment recovery takes as a point load
    /// (`moments.rs`).
    pub fn roller_loads(
        &self,
        model: &Model,
        at: (&[f64], f64, &[f64]),
        out: &mut Vec<RollerLoad>,
    ) {
        out.clear();
        self.for_each_roller(model, at, |p, g| {
            if let (Some((element, xi)), true) = (p.on, g != 0.0) {
                let f = p.weight * g;
                out.push(RollerLoad {
                    element,
                    xi,
                    force: std::array::from_fn(|k| f * p.grad[k]),
                });
            }
        });
    }

    /// Whether any roller presses on the section at `q` (time t): a force
    /// that no fixed sample of nodes holds (see [`Self::node_force`]).
    pub fn rollers_press(&self, model: &Model, at: (&[f64], f64, &[f64])) -> bool {
        let mut pressed = false;
        self.for_each_roller(model, at, |_, g| pressed |= g != 0.0);
        pressed
    }

    /// Calls `visit` with every roller's point at `q` (time t) and its law's
    /// force per unit weight (N; 0 where it does not press).
    fn for_each_roller(
        &self,
        model: &Model,
        (q, t, lambda): (&[f64], f64, &[f64]),
        mut visit: impl FnMut(&Point, f64),
    ) {
        for (c, contact) in self.list.iter().enumerate() {
            if !matches!(contact.surface.shape, Shape::Rollers { .. }) {
                continue;
            }
            let lambda = &lambda[self.offsets[c]..];
            for_each_point(contact, model, &self.tributary, (q, t), |p| {
                visit(&p, contact.method.evaluate(p.gap, lambda[p.index]).1);
            });
        }
    }

    /// The force (N, on the node's x and z) of the continuous surfaces on node
    /// `j` at its displacement `d` (m: x, z) at time `t` with the contacts'
    /// Lagrangian parameters `lambda`, and its stiffness (N/m): the node's
    /// share of [`Self::add_force`], for a force summed over sampled nodes.
    /// Rollers are left out (they meet whichever element passes over them).
    pub fn node_force(
        &self,
        model: &Model,
        j: usize,
        (d, t): ([f64; 2], f64),
        lambda: &[f64],
    ) -> ([f64; 2], [[f64; 2]; 2]) {
        let (mut f, mut k) = ([0.0; 2], [[0.0; 2]; 2]);
        for (c, contact) in self.list.iter().enumerate() {
            if let Shape::Rollers { .. } = &contact.surface.shape {
                continue;
            }
            let r = model.reference[j];
            let x = r[0] + d[0];
            let Some((height, _)) = contact.surface.at(x, t) else {
                continue;
            };
            let grad = [-surface_slope(contact, x, t), 1.0];
            let gap = r[1] + d[1] - height;
            let (_, g, stiffness) = contact.method.evaluate(gap, lambda[self.offsets[c] + j]);
            let w = self.tributary[j];
            for a in 0..2 {
                f[a] += w * g * grad[a];
                for b in 0..2 {
                    k[a][b] += w * stiffness * grad[a] * grad[b];
                }
            }
        }
        (f, k)
    }

    /// Adds `scale` times twice the discrete gradient over the step from `q0` to
    /// `q1` of the energy-conserving laws' energy: per point
    /// w (Xi(d1) - Xi(d0)) / (g . dq) g with g the mean of the gap's gradients at
    /// q0 and q1, so the force's work over the step is exactly the energy change
    /// (the mean gap force where the point slides along the surface). A roller is
    /// measured on the element over it at q1.
    pub fn add_discrete_gradient(
        &self,
        model: &Model,
        (q0, q1, t): (&[f64], &[f64], f64),
        scale: f64,
        mut tangent: ContactTangent<'_>,
        out: &mut [f64],
    ) {
        if !self.discrete {
            return;
        }
        for contact in self.list.iter().filter(|c| is_energy_conserving(&c.method)) {
            for_each_point(contact, model, &self.tributary, (q1, t), |p1| {
                let Some(p0) = start_point(contact, model, (q0, t), &p1) else {
                    return;
                };
                if p0.gap > 0.0 && p1.gap > 0.0 {
                    return;
                }
                let mut mean = p1;
                for k in 0..p1.count {
                    mean.grad[k] = 0.5 * (p0.grad[k] + p1.grad[k]);
                }
                let along = mean.along(|d| q1[d] - q0[d]);
                let (xi0, g0, k0) = contact.method.evaluate(p0.gap, 0.0);
                let (xi1, g1, k1) = contact.method.evaluate(p1.gap, 0.0);
                // The secant and its derivative in the end gap (the exact one, so
                // Newton converges where a point enters or leaves contact).
                let (secant, slope) = if along.abs() > 1e-12 * (1.0 + p0.gap.abs() + p1.gap.abs()) {
                    let secant = (xi1 - xi0) / along;
                    // Between 0 and the law's largest slope (a convex energy), which
                    // also bounds round-off where the point hardly moves.
                    (secant, ((g1 - secant) / along).clamp(0.0, k0.max(k1)))
                } else {
                    (0.5 * (g0 + g1), 0.5 * k1)
                };
                mean.add_force(2.0 * scale * p1.weight * secant, out);
                if let Some((band, factor)) = tangent.as_mut() {
                    p1.add_tangent(band, *factor * p1.weight * 2.0 * slope);
                }
            });
        }
    }

    /// After a step: the Lagrangian update of the augmented laws that update per
    /// time step.
    pub fn update_lambda(&self, model: &Model, (q, t): (&[f64], f64), lambda: &mut [f64]) {
        for (c, contact) in self.list.iter().enumerate() {
            if contact.method.lambda_update() != Some(LambdaUpdate::TimeStep) {
                continue;
            }
            let lambda = &mut lambda[self.offsets[c]..];
            for_each_point(contact, model, &self.tributary, (q, t), |p| {
                let l = &mut lambda[p.index];
                *l = contact.method.updated_lambda(p.gap, *l);
            });
        }
    }

    /// The arc length (m) where the seabed's gap crosses zero above the highest
    /// node in contact, linear in the gaps of that node and the next one up: a
    /// touchdown point that moves continuously with `q` (the `touchdown` output
    /// is the node's). None without seabed contact.
    pub fn seabed_crossing(&self, model: &Model, (q, t): (&[f64], f64)) -> Option<f64> {
        let seabed = self.list.first().filter(|_| self.has_seabed)?;
        let mut crossing = Crossing::default();
        for_each_point(seabed, model, &self.tributary, (q, t), |p| {
            crossing.see(p.gap, p.arc)
        });
        crossing.arc
    }

    /// Touchdown point, seabed contact length, penetration and energy at `q`.
    /// Whether any point rests on a surface other than the seabed (a
    /// stinger's rollers) at (q, t).
    pub fn on_stinger(&self, model: &Model, (q, t): (&[f64], f64)) -> bool {
        let mut touched = false;
        for (c, contact) in self.list.iter().enumerate() {
            if !(c == 0 && self.has_seabed) {
                for_each_point(contact, model, &self.tributary, (q, t), |p| {
                    touched |= p.gap <= 0.0;
                });
            }
        }
        touched
    }

    /// The contact's summary at (q, t, lambda): nodes in contact, reactions and the touchdown.
    pub fn summary(&self, model: &Model, (q, t, lambda): (&[f64], f64, &[f64])) -> ContactSummary {
        let mut s = ContactSummary {
            crossing: [f64::NAN; 2],
            ..ContactSummary::default()
        };
        let mut crossing = Crossing::default();
        for (c, contact) in self.list.iter().enumerate() {
            let seabed = c == 0 && self.has_seabed;
            let lambda = &lambda[self.offsets[c]..];
            let depth_limit = match contact.surface.shape {
                Shape::Rollers { radius, .. } => Some(radius),
                _ => None,
            };
            for_each_point(contact, model, &self.tributary, (q, t), |p| {
                s.energy += p.weight * contact.method.evaluate(p.gap, lambda[p.index]).0;
                if seabed {
                    crossing.see(p.gap, p.arc);
                }
                if p.gap > 0.0 {
                    return;
                }
                if seabed {
                    s.length += p.weight;
                }
                s.penetration = s.penetration.max(-p.gap);
                let limit = depth_limit.unwrap_or(p.weight);
                s.relative_penetration = s.relative_penetration.max(-p.gap / limit);
            });
        }
        if let Some(arc) = crossing.arc {
            s.crossing = [arc, model.position_at(q, arc)[0]];
        }
        s
    }
}

/// Where the seabed's gap first crosses zero along its points in their order:
/// linear between the last point above the seabed and the first on it.
#[derive(Default)]
struct Crossing {
    above: Option<(f64, f64)>,
    arc: Option<f64>,
}

impl Crossing {
    /// Takes the next point's gap (m) and arc length (m).
    fn see(&mut self, gap: f64, arc: f64) {
        if self.arc.is_some() {
            return;
        }
        if gap <= 0.0 {
            self.arc = Some(match self.above {
                Some((g, a)) => arc + (a - arc) * (-gap) / (g - gap),
                None => arc,
            });
        } else {
            self.above = Some((gap, arc));
        }
    }
}

/// The point matching `p1` at the step's start `q0`: the same node, or the same
/// roller on the same element.
fn start_point(
    contact: &NodalContact,
    model: &Model,
    (q0, t): (&[f64], f64),
    p1: &Point,
) -> Option<Point> {
    if let Some((e, _)) = p1.on {
        let (xr, top) = contact.surface.roller(p1.index, t)?;
        Some(roller_point(model, q0, e, (p1.index, xr, top)))
    } else {
        let j = p1.index;
        let r = model.reference[j];
        let x = r[0] + q0[3 * j];
        let (f, _) = contact.surface.at(x, t)?;
        Some(Point {
            gap: r[1] + q0[3 * j + 1] - f,
            grad: [-surface_slope(contact, x, t), 1.0, 0.0, 0.0, 0.0, 0.0],
            ..*p1
        })
    }
}

/// The most a point may penetrate a surface, relative to a node's tributary
/// length or a roller's radius: deeper, the contact no longer represents the
/// pipe resting on the surface.
pub const MAX_RELATIVE_PENETRATION: f64 = 1.0;

/// Checks a contact summary after a step.
pub fn check_penetration(s: &ContactSummary, t: f64) -> Result<(), UnitError> {
    if s.relative_penetration > MAX_RELATIVE_PENETRATION {
        return Err(UnitError::Numerical(format!(
            "nonlinear section: at t = {t} s the section is {:.4} m deep in a contact surface, more than a node's tributary length or a roller's radius (the contact cannot represent it: raise the penalty or refine the mesh)",
            s.penetration
        )));
    }
    Ok(())
}

/// Checks the contact settings against the integrator.
pub fn validate(params: &NonlinearParams) -> Result<(), UnitError> {
    for (key, c) in [("contact", &params.contact), ("stinger", &params.stinger)] {
        let Some(c) = c else { continue };
        c.method.validate()?;
        c.surface.validate()?;
        if c.method.lambda_update() == Some(LambdaUpdate::NewtonIteration) {
            return Err(UnitError::parameter(
                &format!("{key}.method.update"),
                "newton_iteration",
                "time_step (the nodes update their Lagrangian parameter after each step)",
            ));
        }
        let energy_integrator = matches!(params.integrator, Integrator::EnergyConserving { .. });
        if is_energy_conserving(&c.method) && !energy_integrator {
            return Err(UnitError::parameter(
                &format!("{key}.method.kind"),
                "energy_conserving",
                "integrator.kind = \"energy_conserving\" with this law (else use `penalty`)",
            ));
        }
    }
    Ok(())
}

/// Whether `contact`'s surface moves and its law acts by its discrete
/// gradient (`discrete`) or by its force at the step's end (not `discrete`).
fn moves_by(contact: &NodalContact, discrete: bool) -> bool {
    contact.moves() && is_energy_conserving(&contact.method) == discrete
}

fn is_energy_conserving(law: &Law) -> bool {
    matches!(law, Law::EnergyConserving { .. })
}
