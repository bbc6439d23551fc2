//! The cable's quantities along its length (the unit's fields): node
//! positions and the tension in every element, linearised about the static
//! state as the unit's end tensions are, for FMI 3.0 array outputs.

use super::{Cable, elements};
use crate::contract::{Field, UnitError};

impl Cable {
    /// Node x and z (m, bottom first) and each element's tension (N).
    pub(super) fn field_list(&self) -> Vec<Field> {
        let elements = self.element_count();
        vec![
            Field::per_node(
                "x",
                "m",
                "horizontal position of each node, bottom first",
                elements + 1,
            ),
            Field::per_node(
                "z",
                "m",
                "vertical position of each node (up), bottom first",
                elements + 1,
            ),
            Field::per_element(
                "tension",
                "N",
                "tension of each element, bottom first",
                elements,
            ),
        ]
    }

    /// Node `j`'s displacement from its static position (m).
    fn displacement(&self, j: usize) -> [f64; 2] {
        let s = &self.state;
        if j == 0 {
            s.qb
        } else {
            [s.q[2 * (j - 1)], s.q[2 * (j - 1) + 1]]
        }
    }

    /// The current values of field `index` into `out`.
    pub(super) fn write_field(&self, index: usize, out: &mut [f64]) -> Result<(), UnitError> {
        let dynamics = self.dynamics.as_ref().ok_or_else(|| {
            UnitError::State("a cable's fields are known after initialisation".into())
        })?;
        let x = &dynamics.statics.positions;
        let expected = if index == 2 { x.len() - 1 } else { x.len() };
        if index > 2 || out.len() != expected {
            return Err(UnitError::Numerical(format!(
                "field {index}: {} values asked for",
                out.len()
            )));
        }
        let ea = self.props.axial_stiffness / self.props.length;
        for (j, v) in out.iter_mut().enumerate() {
            *v = match index {
                0 | 1 => x[j][index] + self.displacement(j)[index],
                _ => {
                    let (e, _, t) = elements::element_state(&self.props, x[j], x[j + 1]);
                    let (a, b) = (self.displacement(j), self.displacement(j + 1));
                    let d = [b[0] - a[0], b[1] - a[1]];
                    t + ea * (e[0] * d[0] + e[1] * d[1])
                }
            };
        }
        Ok(())
    }
}
