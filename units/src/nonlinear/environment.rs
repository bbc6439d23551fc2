//! Forces from the surroundings that depend on the motion: Morison drag on the
//! velocity relative to a current, and contact of the nodes with the seabed and
//! a stinger ([`super::contact`]). Each is skipped entirely when the scene does
//! not ask for it.

// Small dense element blocks read best indexed as in the formulas.
#![allow(clippy::needless_range_loop)]

use super::contact::NodalContacts;
use super::model::Model;
use super::params::{Current, NonlinearParams};
use crate::numerics::banded::SymmetricBand;

/// Drag of one element: 1/2 rho D l Cn and 1/2 rho pi D l Ct (kg/m).
#[derive(Copy, Clone, Debug)]
struct ElementDrag {
    normal: f64,
    tangential: f64,
}

/// The motion-dependent environment of a section.
#[derive(Clone, Debug)]
pub struct Environment {
    drag: Vec<ElementDrag>,
    current: Option<Current>,
    /// Contact of the nodes with the seabed and the stinger.
    pub contacts: NodalContacts,
}

/// How the force's derivatives enter a Newton matrix: (band, stiffness factor,
/// damping factor).
pub type Tangent<'a> = Option<(&'a mut SymmetricBand, f64, f64)>;

impl Environment {
    /// From the parameters and the mesh.
    pub fn new(params: &NonlinearParams, model: &Model) -> Environment {
        let drag: Vec<ElementDrag> = model
            .elements
            .iter()
            .zip(&model.segment_of)
            .map(|(e, &s)| {
                let s = &params.segments[s];
                let k = 0.5 * params.water_density * s.diameter * e.length;
                ElementDrag {
                    normal: k * s.drag_normal,
                    tangential: k * std::f64::consts::PI * s.drag_tangential,
                }
            })
            .collect();
        let any_drag = drag.iter().any(|d| d.normal > 0.0 || d.tangential > 0.0);
        Environment {
            drag: if any_drag { drag } else { Vec::new() },
            current: params.current.clone(),
            contacts: NodalContacts::new(params, model),
        }
    }

    /// Whether there is nothing to compute.
    pub fn is_empty(&self) -> bool {
        self.drag.is_empty() && self.contacts.is_empty()
    }

    /// Adds `scale` times the drag and contact force (as it enters the left-hand
    /// side) at (q, v, t) with the contacts' Lagrangian parameters `lambda` to
    /// `out`, and their tangents to the band. With `stepped`, the contact laws
    /// that act by their discrete gradient over a step are left out.
    #[allow(clippy::too_many_arguments)]
    pub fn add_force(
        &self,
        model: &Model,
        (q, v, t): (&[f64], &[f64], f64),
        lambda: &[f64],
        scale: f64,
        stepped: bool,
        mut tangent: Tangent<'_>,
        out: &mut [f64],
    ) {
        if !self.drag.is_empty() {
            let tangent = tangent.as_mut().map(|(b, _, d)| (&mut **b, *d));
            self.add_drag(model, (q, v), scale, tangent, (out, None));
        }
        if !self.contacts.is_empty() {
            let tangent = tangent.map(|(b, k, _)| (b, k));
            self.contacts
                .add_force(model, (q, t, lambda), scale, stepped, tangent, out);
        }
    }

    /// Adds `scale` times the drag force alone (as it enters the left-hand
    /// side) at (q, v).
    pub fn add_drag_force(
        &self,
        model: &Model,
        (q, v): (&[f64], &[f64]),
        scale: f64,
        out: &mut [f64],
    ) {
        if !self.drag.is_empty() {
            self.add_drag(model, (q, v), scale, None, (out, None));
        }
    }

    /// Whether any element has drag.
    pub fn has_drag(&self) -> bool {
        !self.drag.is_empty()
    }

    /// Adds the drag force at (q, v) to `out` and its velocity tangent
    /// (N s/m) to `tangent`: a linear section's drag linearised at a step's
    /// start.
    pub fn add_drag_with_tangent(
        &self,
        model: &Model,
        (q, v): (&[f64], &[f64]),
        tangent: &mut SymmetricBand,
        out: &mut [f64],
    ) {
        if !self.drag.is_empty() {
            self.add_drag(model, (q, v), 1.0, Some((tangent, 1.0)), (out, None));
        }
    }

    /// Adds the drag and contact force at the state (q, v, t) with the
    /// contacts' parameters `lambda` to `out` as [`Self::add_force`] does
    /// (the laws stepped by their discrete gradient left out, no tangent),
    /// and writes the drag alone to `drag` (N, N m per DOF): the energy
    /// balance's, without a second evaluation.
    pub fn add_force_keeping_drag(
        &self,
        model: &Model,
        (q, v, t): (&[f64], &[f64], f64),
        lambda: &[f64],
        out: &mut [f64],
        drag: &mut [f64],
    ) {
        drag.fill(0.0);
        if !self.drag.is_empty() {
            self.add_drag(model, (q, v), 1.0, None, (out, Some(drag)));
        }
        if !self.contacts.is_empty() {
            (self.contacts).add_force(model, (q, t, lambda), 1.0, true, None, out);
        }
    }

    /// Drag per element on the midpoint's relative velocity, half to each node,
    /// added to `out` (and to `also` when given); the damping tangent
    /// (velocity derivative) only.
    fn add_drag(
        &self,
        model: &Model,
        (q, v): (&[f64], &[f64]),
        scale: f64,
        mut tangent: Option<(&mut SymmetricBand, f64)>,
        (out, mut also): (&mut [f64], Option<&mut [f64]>),
    ) {
        for e in 0..self.drag.len() {
            let tangent = tangent.as_mut().map(|(b, f)| (&mut **b, *f));
            self.add_element_drag(model, e, (q, v), scale, tangent, (out, also.as_deref_mut()));
        }
    }

    /// The drag of the elements `elements` alone and the contact force at the
    /// end nodes (and of every roller) at (q, v, t), added to `out` as
    /// [`Self::add_force_keeping_drag`] adds them (same order of sums): their
    /// rows at the end nodes of a section whose `elements` are its end
    /// elements are the whole force's.
    pub fn add_end_force(
        &self,
        model: &Model,
        (q, v, t): (&[f64], &[f64], f64),
        lambda: &[f64],
        elements: &[usize],
        out: &mut [f64],
    ) {
        for &e in elements.iter().filter(|&&e| e < self.drag.len()) {
            self.add_element_drag(model, e, (q, v), 1.0, None, (out, None));
        }
        if !self.contacts.is_empty() {
            let ends = [0, model.reference.len() - 1];
            (self.contacts).add_force_at_ends(model, (q, t, lambda), ends, out);
        }
    }

    /// The drag's damping tangent (N s/m) of the elements `elements` alone at
    /// (q, v), added to `band`: the entries a step's interface sensitivity
    /// reads at its end nodes come from their elements only, so the rest of
    /// the section need not be evaluated again.
    pub fn add_drag_damping_of(
        &self,
        model: &Model,
        (q, v): (&[f64], &[f64]),
        elements: &[usize],
        band: &mut SymmetricBand,
        scratch: &mut [f64],
    ) {
        for &e in elements.iter().filter(|&&e| e < self.drag.len()) {
            self.add_element_drag(model, e, (q, v), 1.0, Some((band, 1.0)), (scratch, None));
        }
    }

    /// Element `e`'s part of [`Self::add_drag`].
    fn add_element_drag(
        &self,
        model: &Model,
        e: usize,
        (q, v): (&[f64], &[f64]),
        scale: f64,
        tangent: Option<(&mut SymmetricBand, f64)>,
        (out, mut also): (&mut [f64], Option<&mut [f64]>),
    ) {
        let b = 3 * e;
        let (i, j) = (b, b + 3);
        let local = |x: &[f64]| [x[i], x[i + 1], x[i + 2], x[j], x[j + 1], x[j + 2]];
        let (f, k) = self.element_drag(model, e, (&local(q), &local(v)), tangent.is_some());
        for node in [i, j] {
            out[node] += scale * 0.5 * f[0];
            out[node + 1] += scale * 0.5 * f[1];
            if let Some(also) = also.as_deref_mut() {
                also[node] += scale * 0.5 * f[0];
                also[node + 1] += scale * 0.5 * f[1];
            }
        }
        if let Some((band, factor)) = tangent {
            // Each node's velocity enters vr with 1/2, each node takes half the force.
            for a in [i, j] {
                for bn in [i, j] {
                    for r in 0..2 {
                        for c in 0..2 {
                            if a + r >= bn + c {
                                band.add(a + r, bn + c, factor * 0.25 * k[r][c]);
                            }
                        }
                    }
                }
            }
        }
    }

    /// The drag of element `e` (N, both nodes' x and z together) at its end
    /// nodes' displacements and velocities `q`, `v` (x, z, rotation of each),
    /// and with `tangent` its derivative by the relative velocity (N s/m;
    /// zero without). Zero where the section has no drag.
    pub fn element_drag(
        &self,
        model: &Model,
        e: usize,
        (q, v): (&[f64; 6], &[f64; 6]),
        tangent: bool,
    ) -> ([f64; 2], [[f64; 2]; 2]) {
        let Some(d) = self.drag.get(e) else {
            return ([0.0; 2], [[0.0; 2]; 2]);
        };
        let (i, j) = (0, 3);
        let el = &model.elements[e];
        let dx = el.length * el.cos0 + q[j] - q[i];
        let dz = el.length * el.sin0 + q[j + 1] - q[i + 1];
        let ln = (dx * dx + dz * dz).sqrt().max(1e-12);
        let tv = [dx / ln, dz / ln];
        let zmid = 0.5 * (model.reference[e][1] + model.reference[e + 1][1] + q[i + 1] + q[j + 1]);
        let u = self.current.as_ref().map_or(0.0, |c| c.at(zmid));
        let vr = [0.5 * (v[i] + v[j]) - u, 0.5 * (v[i + 1] + v[j + 1])];
        let vt = vr[0] * tv[0] + vr[1] * tv[1];
        let vn = [vr[0] - vt * tv[0], vr[1] - vt * tv[1]];
        let an = (vn[0] * vn[0] + vn[1] * vn[1]).sqrt();
        let f = [
            d.normal * an * vn[0] + d.tangential * vt.abs() * vt * tv[0],
            d.normal * an * vn[1] + d.tangential * vt.abs() * vt * tv[1],
        ];
        let mut k = [[0.0; 2]; 2];
        if tangent {
            // d f / d vr = Cn (|vn| P + vn vn^T / |vn|) + 2 Ct |vt| t t^T.
            for r in 0..2 {
                for c in 0..2 {
                    let p = if r == c { 1.0 } else { 0.0 } - tv[r] * tv[c];
                    let outer = if an > 0.0 { vn[r] * vn[c] / an } else { 0.0 };
                    k[r][c] =
                        d.normal * (an * p + outer) + 2.0 * d.tangential * vt.abs() * tv[r] * tv[c];
                }
            }
        }
        (f, k)
    }
}
