//! The section's quantities along its length (the unit's fields): node
//! positions, the tension in every element and the bending moment at every
//! node, what an FMI 3.0 export offers as array outputs and envelopes read.

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
