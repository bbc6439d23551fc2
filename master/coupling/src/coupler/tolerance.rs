//! Each connection's convergence tolerance, and where it comes from. A port with
//! a unit of measure takes the absolute tolerance of its kind; a port without
//! one (a generic port, as FMUs from other tools declare them) cannot be judged
//! by an absolute number: 1e-9 is round-off for a 1.9 MN force. Its default is
//! therefore relative, `tolerances.generic_relative` times the largest value the
//! connection has carried so far, and `tolerances.generic` a floor near zero.
//! The tolerance changes only between steps, so an accelerator's scaling stays
//! fixed within a step.

use crate::adapter::UnitAdapter;
use crate::settings::Tolerances;
use crate::system::Connection;
use slender_contract::PortKind;

/// Per connection: the tolerance's source and the scale of a relative one.
pub(crate) struct ConnectionTolerances {
    /// The absolute tolerance (a connection's own, its kind's, or the floor).
    absolute: Vec<f64>,
    /// The relative factor (0 where the tolerance is absolute).
    relative: Vec<f64>,
    /// The largest magnitude each connection has carried (relative ones only).
    scale: Vec<f64>,
    /// Whether any connection is relative (else nothing to update).
    any_relative: bool,
}

impl ConnectionTolerances {
    /// The tolerances of `connections` under `tolerances`, and their values now.
    pub(crate) fn new(connections: &[Connection], tolerances: &Tolerances) -> (Self, Vec<f64>) {
        let absolute: Vec<f64> = connections
            .iter()
            .map(|c| c.link.tolerance.unwrap_or(tolerances.of(c.kind)))
            .collect();
        let relative: Vec<f64> = connections
            .iter()
            .map(|c| match (c.link.tolerance, c.kind) {
                (None, PortKind::Generic) => tolerances.generic_relative,
                _ => 0.0,
            })
            .collect();
        let any_relative = relative.iter().any(|&r| r > 0.0);
        let now = absolute.clone();
        let scale = vec![0.0; connections.len()];
        let tolerances = ConnectionTolerances {
            absolute,
            relative,
            scale,
            any_relative,
        };
        (tolerances, now)
    }

    /// Raises the relative tolerances to the values accepted so far
    /// (`accepted`), in `tolerance` and in the destination units' copies.
    pub(crate) fn follow(
        &mut self,
        accepted: &[f64],
        connections: &[Connection],
        tolerance: &mut [f64],
        units: &mut [UnitAdapter],
    ) {
        if !self.any_relative {
            return;
        }
        for (c, connection) in connections.iter().enumerate() {
            if self.relative[c] == 0.0 || !accepted[c].is_finite() {
                continue;
            }
            self.scale[c] = self.scale[c].max(accepted[c].abs());
            tolerance[c] = self.absolute[c].max(self.relative[c] * self.scale[c]);
            units[connection.to.unit].input_tolerance[connection.to.port] = tolerance[c];
        }
    }

    /// The scene key that sets connection `c`'s tolerance, for messages.
    pub(crate) fn key(&self, c: usize, connection: &Connection) -> String {
        if connection.link.tolerance.is_some() {
            "the connection's own `tolerance`".into()
        } else if self.relative[c] > 0.0 {
            format!(
                "[master] tolerances.generic_relative = {:e} times the largest value carried ({:.3e}), at least tolerances.generic = {:e}; the ports have no unit of measure",
                self.relative[c], self.scale[c], self.absolute[c]
            )
        } else {
            format!("[master] tolerances.{}", connection.kind.name())
        }
    }
}
