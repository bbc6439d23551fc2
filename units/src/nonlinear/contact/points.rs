//! The contact points of a surface at a state: a node's gap over a
//! continuous surface, or a roller's on the element passing over it, with
//! the gradient and weight its force and tangent take.

use super::super::element::Formulation;
use super::super::model::Model;
use super::super::params::NodalContact;
use crate::contact::surface::Shape;
use crate::numerics::banded::SymmetricBand;

/// One contact point: the gap (m), its gradient over up to six DOFs (a
/// node's x and z; a roller's element's end translations and rotations), and
/// its weight (tributary length for a node, 1 for a roller).
#[derive(Copy, Clone, Debug)]
pub(crate) struct Point {
    pub(super) gap: f64,
    pub(super) dofs: [usize; 6],
    pub(super) grad: [f64; 6],
    pub(super) count: usize,
    pub(super) weight: f64,
    /// Node (or roller) index, for the Lagrangian parameter and the summary.
    pub(super) index: usize,
    /// Arc length (m) of the node, or of the roller's point on the section.
    pub(super) arc: f64,
    /// A roller's element and where along it the roller meets it (0 to 1);
    /// none for a node.
    pub(crate) on: Option<(usize, f64)>,
}

impl Point {
    pub(super) fn along(&self, dq: impl Fn(usize) -> f64) -> f64 {
        (0..self.count)
            .map(|k| self.grad[k] * dq(self.dofs[k]))
            .sum()
    }

    pub(super) fn add_force(&self, f: f64, out: &mut [f64]) {
        for k in 0..self.count {
            out[self.dofs[k]] += f * self.grad[k];
        }
    }

    pub(super) fn add_tangent(&self, band: &mut SymmetricBand, k: f64) {
        for a in 0..self.count {
            for b in 0..self.count {
                let (i, j) = (self.dofs[a], self.dofs[b]);
                if i >= j {
                    band.add(i, j, k * self.grad[a] * self.grad[b]);
                }
            }
        }
    }
}

/// The contact points of surface `contact` at `q` (time t): rollers in order,
/// nodes in order of decreasing arc length.
pub(super) fn for_each_point(
    contact: &NodalContact,
    model: &Model,
    tributary: &[f64],
    (q, t): (&[f64], f64),
    visit: impl FnMut(Point),
) {
    for_each_point_of(contact, model, tributary, (q, t), None, visit);
}

/// [`for_each_point`], with `ends` the nodal points of those two nodes alone
/// (every roller still).
pub(super) fn for_each_point_of(
    contact: &NodalContact,
    model: &Model,
    tributary: &[f64],
    (q, t): (&[f64], f64),
    ends: Option<[usize; 2]>,
    mut visit: impl FnMut(Point),
) {
    if let Shape::Rollers { .. } = &contact.surface.shape {
        // Where each roller is at t (a pitching vessel carries it sideways).
        for (i, (xr, top)) in contact.surface.rollers(t).enumerate() {
            if let Some(e) = roller_element(model, q, xr, top) {
                visit(roller_point(model, q, e, (i, xr, top)));
            }
        }
        return;
    }
    let visited = |j: usize| ends.is_none_or(|[a, b]| j == a || j == b);
    for j in (0..model.reference.len()).rev().filter(|&j| visited(j)) {
        let r = model.reference[j];
        let x = r[0] + q[3 * j];
        let Some((f, _)) = contact.surface.at(x, t) else {
            continue;
        };
        visit(Point {
            gap: r[1] + q[3 * j + 1] - f,
            dofs: [3 * j, 3 * j + 1, 0, 0, 0, 0],
            grad: [-surface_slope(contact, x, t), 1.0, 0.0, 0.0, 0.0, 0.0],
            count: 2,
            weight: tributary[j],
            index: j,
            arc: model.arc[j],
            on: None,
        });
    }
}

/// The element passing over a roller at x = `xr` nearest its top (none when no
/// element spans xr).
fn roller_element(model: &Model, q: &[f64], xr: f64, top: f64) -> Option<usize> {
    let mut best: Option<(usize, f64)> = None;
    for e in 0..model.elements.len() {
        let (xa, xb) = (node_x(model, q, e), node_x(model, q, e + 1));
        if (xr - xa) * (xr - xb) > 0.0 || xa == xb {
            continue;
        }
        let gap = roller_point(model, q, e, (0, xr, top)).gap.abs();
        if best.is_none_or(|(_, g)| gap < g) {
            best = Some((e, gap));
        }
    }
    best.map(|(e, _)| e)
}

fn node_x(model: &Model, q: &[f64], j: usize) -> f64 {
    model.reference[j][0] + q[3 * j]
}

/// The gap between element `e` and roller `i`'s top at x = `xr`, with its
/// gradient over the element's end translations and rotations. The element
/// between its nodes is its chord bent by its end rotations relative to the
/// chord (the co-rotational element's cubic, `w = l (N2 t1 + N4 t2)` along its
/// normal), so a roller's force reaches the nodes as the cubic element's
/// consistent load (forces and moments, `N1..N4`): the moment over a roller
/// then no longer depends on where it falls between two nodes. The gap is
/// vertical at the roller: the chord's height there plus `w / cos(beta)`.
pub(super) fn roller_point(
    model: &Model,
    q: &[f64],
    e: usize,
    (i, xr, top): (usize, f64, f64),
) -> Point {
    let (a, b) = (e, e + 1);
    let (xa, za) = (node_x(model, q, a), model.reference[a][1] + q[3 * a + 1]);
    let (xb, zb) = (node_x(model, q, b), model.reference[b][1] + q[3 * b + 1]);
    let (dx, dz) = (xb - xa, zb - za);
    let xi = (xr - xa) / dx;
    let slope = dz / dx;
    let linear = [-slope * (1.0 - xi), 1.0 - xi, -slope * xi, xi];
    // Seed 002's element has no co-rotational frame: its chord alone.
    let bend = match model.formulation {
        Formulation::Corotational => Bend::at(model, q, (e, xi), (dx, dz)),
        Formulation::Seed002 => Bend::NONE,
    };
    let grad = [
        linear[0] + bend.by_translation[0],
        linear[1] + bend.by_translation[1],
        bend.by_rotation[0],
        linear[2] + bend.by_translation[2],
        linear[3] + bend.by_translation[3],
        bend.by_rotation[1],
    ];
    Point {
        gap: (1.0 - xi) * za + xi * zb + bend.height - top,
        dofs: [3 * a, 3 * a + 1, 3 * a + 2, 3 * b, 3 * b + 1, 3 * b + 2],
        grad,
        count: 6,
        weight: 1.0,
        index: i,
        arc: model.arc[a] + xi.clamp(0.0, 1.0) * model.elements[e].length,
        on: Some((e, xi)),
    }
}

/// The height (m) the element's bending adds over its chord at `xi`, and its
/// derivatives by the end translations (xa, za, xb, zb) and rotations.
struct Bend {
    height: f64,
    by_translation: [f64; 4],
    by_rotation: [f64; 2],
}

impl Bend {
    const NONE: Bend = Bend {
        height: 0.0,
        by_translation: [0.0; 4],
        by_rotation: [0.0; 2],
    };

    /// At `xi` along element `e`, whose chord is `(dx, dz)` (m).
    fn at(model: &Model, q: &[f64], (e, xi): (usize, f64), (dx, dz): (f64, f64)) -> Bend {
        let (a, b) = (e, e + 1);
        let chord = (dx * dx + dz * dz).sqrt();
        let (cos, tan) = (dx / chord, dz / dx);
        // The end rotations relative to the chord (rad).
        let [t1, t2] = model.elements[e].local_rotations(q[3 * a + 2], q[3 * b + 2], dz.atan2(dx));
        // Hermite's rotation shape functions and their derivatives in xi.
        let (n2, n4) = (xi * (1.0 - xi) * (1.0 - xi), -xi * xi * (1.0 - xi));
        let (dn2, dn4) = ((1.0 - xi) * (1.0 - 3.0 * xi), xi * (3.0 * xi - 2.0));
        let w = chord * (n2 * t1 + n4 * t2);
        // d(w / cos) by the chord's angle (t1 and t2 fall as it rises), by xi
        // and by the chord's length.
        let by_angle = (-chord * (n2 + n4) + w * tan) / cos;
        let by_xi = chord * (dn2 * t1 + dn4 * t2) / cos;
        let by_length = w / chord / cos;
        let r2 = chord * chord;
        // The chord's angle, xi and length by xa, za, xb, zb.
        let angle = [dz / r2, -dx / r2, -dz / r2, dx / r2];
        let along = [-(1.0 - xi) / dx, 0.0, -xi / dx, 0.0];
        let length = [-dx / chord, -dz / chord, dx / chord, dz / chord];
        Bend {
            height: w / cos,
            by_translation: std::array::from_fn(|k| {
                by_angle * angle[k] + by_xi * along[k] + by_length * length[k]
            }),
            by_rotation: [chord * n2 / cos, chord * n4 / cos],
        }
    }
}

/// df/dx by central differences over 1 mm (0 where the surface ends).
pub(super) fn surface_slope(contact: &NodalContact, x: f64, t: f64) -> f64 {
    let h = 1e-3;
    match (contact.surface.at(x + h, t), contact.surface.at(x - h, t)) {
        (Some((a, _)), Some((b, _))) => (a - b) / (2.0 * h),
        _ => 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::roller_point;
    use crate::nonlinear::NonlinearParams;
    use crate::nonlinear::model::Model;

    /// A roller's gap gradient is the gap's derivative (central differences)
    /// over the element's six DOFs, the rotations among them: the force it
    /// gives is the contact energy's gradient.
    #[test]
    fn a_rollers_gap_gradient_is_its_derivative() {
        let params: NonlinearParams = toml::from_str(
            r#"
            segments = [{ length = 10.0, angle_deg = 10.0, elements = 4, axial_stiffness = 1e9,
                          bending_stiffness = 1e7, mass_per_length = 100, submerged_weight = 400 }]
            "#,
        )
        .expect("parameters");
        let model = Model::new(&params);
        let mut q = vec![0.0; 15];
        for (k, v) in q.iter_mut().enumerate() {
            *v = 0.01 * ((k as f64) * 1.7).sin();
        }
        let e = 1;
        let xr = 0.5 * (model.reference[1][0] + model.reference[2][0]) + 0.3;
        let p = roller_point(&model, &q, e, (0, xr, -1.0));
        assert_eq!(p.on.map(|(e, _)| e), Some(1));
        for k in 0..6 {
            let dof = p.dofs[k];
            let h = 1e-6;
            let mut moved = q.clone();
            moved[dof] += h;
            let up = roller_point(&model, &moved, e, (0, xr, -1.0)).gap;
            moved[dof] -= 2.0 * h;
            let down = roller_point(&model, &moved, e, (0, xr, -1.0)).gap;
            let numeric = (up - down) / (2.0 * h);
            assert!(
                (numeric - p.grad[k]).abs() < 1e-7 * (1.0 + numeric.abs()),
                "DOF {dof}: {} against {numeric}",
                p.grad[k]
            );
        }
        // The rotations move it: the element's cubic between its nodes.
        assert!(
            p.grad[2].abs() > 0.1 && p.grad[5].abs() > 0.1,
            "{:?}",
            p.grad
        );
    }
}
