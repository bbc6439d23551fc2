//! The section's quantities along its length (the unit's fields): node
//! positions and the tension in every element, what an FMI 3.0 export offers
//! as array outputs.

use super::NonlinearSection;
use crate::contract::{Field, UnitError};

/// The fields, in [`NonlinearSection::field_list`] order.
const X: usize = 0;
const Z: usize = 1;
const TENSION: usize = 2;

impl NonlinearSection {
    /// Node x and z (m, per node from the first end) and the axial force of
    /// each element (N, tension positive).
    pub(super) fn field_list(&self) -> Vec<Field> {
        let nodes = self.model.reference.len();
        let field = Field::new;
        vec![
            field(
                "x",
                "m",
                "horizontal position of each node, first end first",
                nodes,
            ),
            field(
                "z",
                "m",
                "vertical position of each node (up), first end first",
                nodes,
            ),
            field(
                "tension",
                "N",
                "axial force of each element (tension positive), first end first",
                self.model.elements.len(),
            ),
        ]
    }

    /// The current values of field `index` into `out`.
    pub(super) fn write_field(&self, index: usize, out: &mut [f64]) -> Result<(), UnitError> {
        let q = &self.state.q;
        let expected = match index {
            X | Z => self.model.reference.len(),
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
            _ => {
                for (e, v) in out.iter_mut().enumerate() {
                    *v = self.model.local_forces(q, e).axial;
                }
            }
        }
        Ok(())
    }
}
