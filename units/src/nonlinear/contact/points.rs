//! The contact points of a surface at a state: a node's gap over a
//! continuous surface, or a roller's on the element passing over it, with
//! the gradient and weight its force and tangent take.

use super::super::model::Model;
use super::super::params::NodalContact;
use crate::contact::surface::Shape;
use crate::numerics::banded::SymmetricBand;

/// One contact point: the gap (m), its gradient over up to four translational
/// DOFs, and its weight (tributary length for a node, 1 for a roller).
#[derive(Copy, Clone, Debug)]
pub(super) struct Point {
    pub(super) gap: f64,
    pub(super) dofs: [usize; 4],
    pub(super) grad: [f64; 4],
    pub(super) count: usize,
    pub(super) weight: f64,
    /// Node (or roller) index, for the Lagrangian parameter and the summary.
    pub(super) index: usize,
    /// Arc length (m) of the node, or of the roller's point on the section.
    pub(super) arc: f64,
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
            dofs: [3 * j, 3 * j + 1, 0, 0],
            grad: [-surface_slope(contact, x, t), 1.0, 0.0, 0.0],
            count: 2,
            weight: tributary[j],
            index: j,
            arc: model.arc[j],
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

/// The gap between element `e` (straight between its nodes) and roller `i`'s top
/// at x = xr, with its gradient over the element's end translations.
pub(super) fn roller_point(
    model: &Model,
    q: &[f64],
    e: usize,
    (i, xr, top): (usize, f64, f64),
) -> Point {
    let (a, b) = (e, e + 1);
    let (xa, za) = (node_x(model, q, a), model.reference[a][1] + q[3 * a + 1]);
    let (xb, zb) = (node_x(model, q, b), model.reference[b][1] + q[3 * b + 1]);
    let xi = (xr - xa) / (xb - xa);
    let slope = (zb - za) / (xb - xa);
    Point {
        gap: (1.0 - xi) * za + xi * zb - top,
        dofs: [3 * a, 3 * a + 1, 3 * b, 3 * b + 1],
        grad: [-slope * (1.0 - xi), 1.0 - xi, -slope * xi, xi],
        count: 4,
        weight: 1.0,
        index: i,
        arc: model.arc[a] + xi.clamp(0.0, 1.0) * model.elements[e].length,
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
