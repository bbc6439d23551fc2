//! The section's quantities along its length (the unit's fields): node
//! positions, the tension in every element and the bending moment at every
//! node, what an FMI 3.0 export offers as array outputs and envelopes read;
//! and the section forces at any arc length (the stations' outputs).

use super::NonlinearSection;
use crate::contract::{Field, UnitError};

/// The fields, in [`NonlinearSection::field_list`] order.
const X: usize = 0;
const Z: usize = 1;
const TENSION: usize = 2;
const MOMENT: usize = 3;

impl NonlinearSection {
    /// Node x and z (m, per node from the first end), the axial force of
    /// each element (N, tension positive) and the bending moment at each node
    /// (N m).
    pub(super) fn field_list(&self) -> Vec<Field> {
        let nodes = self.model.reference.len();
        vec![
            Field::per_node(
                "x",
                "m",
                "horizontal position of each node, first end first",
                nodes,
            ),
            Field::per_node(
                "z",
                "m",
                "vertical position of each node (up), first end first",
                nodes,
            ),
            Field::per_element(
                "tension",
                "N",
                "axial force of each element (tension positive), first end first",
                self.model.elements.len(),
            ),
            Field::per_node(
                "moment",
                "N.m",
                "bending moment at each node, the mean of its elements' ends (positive turning the tangent counter-clockwise along the arc), first end first",
                nodes,
            ),
        ]
    }

    /// The current values of field `index` into `out`.
    pub(super) fn write_field(&self, index: usize, out: &mut [f64]) -> Result<(), UnitError> {
        let q = &self.state.q;
        let expected = match index {
            X | Z | MOMENT => self.model.reference.len(),
            TENSION => self.model.elements.len(),
            _ => {
                return Err(UnitError::Unsupported(format!(
                    "field {index} of a section"
                )));
            }
        };
        if out.len() != expected {
            return Err(UnitError::Numerical(format!(
                "field {index}: {} values asked for, the section has {expected}",
                out.len()
            )));
        }
        match index {
            X | Z => {
                for (node, (v, r)) in out.iter_mut().zip(&self.model.reference).enumerate() {
                    *v = r[index] + q[3 * node + index];
                }
            }
            TENSION => {
                for (e, v) in out.iter_mut().enumerate() {
                    *v = self.model.local_forces(q, e).axial;
                }
            }
            _ => self.write_moments(out),
        }
        Ok(())
    }

    /// Each node's bending moment (N m) into `out`, as
    /// `moments.rs` gives it (the extremes read the same).
    fn write_moments(&self, out: &mut [f64]) {
        self.for_each_node_moment(false, |_| {}, |j, m, _| out[j] = m);
    }
}

impl NonlinearSection {
    /// Tension (N), bending moment (N m) and curvature (1/m) at arc length `s`,
    /// the moment interpolated linearly between the element's recovered end
    /// moments (see `moments.rs`).
    pub fn section_forces(&self, s: f64) -> [f64; 3] {
        let (e, xi) = self.model.locate(s);
        let local = self.model.local_forces(&self.state.q, e);
        let ends = self.model.recovered_moments(e, &local, self);
        let moment = (1.0 - xi) * -ends[0] + xi * ends[1];
        [local.axial, moment, moment / self.model.elements[e].ei]
    }

    /// The magnitude (N) of the internal force at arc length `s`: the element's
    /// axial force and its shear (m0 + m1) / l, frame-free, so any section's end
    /// force can be compared with it. At a node between two elements, the mean
    /// of theirs: what a cut at that node transmits, each side carrying half of
    /// its element's weight and inertia there.
    pub fn internal_force(&self, s: f64) -> f64 {
        let magnitude = |e: usize| {
            let local = self.model.local_forces(&self.state.q, e);
            let shear = (local.moments[0] + local.moments[1]) / local.chord;
            local.axial.hypot(shear)
        };
        let (e, xi) = self.model.locate(s);
        // At a node to round-off of the arc lengths.
        if xi < 1e-9 && e > 0 {
            0.5 * (magnitude(e - 1) + magnitude(e))
        } else if xi > 1.0 - 1e-9 && e + 1 < self.model.elements.len() {
            0.5 * (magnitude(e) + magnitude(e + 1))
        } else {
            magnitude(e)
        }
    }
}
