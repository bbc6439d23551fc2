//! Beams of the seed 004 tests: conditions, the cantilever, the static contact
//! reference problem (eq. 4.41) and its reference distance.

use slender_units::Driver;
use slender_units::beam::boundary::{Boundary, Condition, Quantity, TimeFunction};
use slender_units::beam::{Beam, BeamParams, ContactIntegration, ContactParams};
use slender_units::contact::Law;
use slender_units::contact::surface::{Motion, Shape, Surface};

/// A condition with a constant value.
pub(crate) fn cond(quantity: Quantity, value: f64) -> Condition {
    Condition {
        quantity,
        value: TimeFunction::Constant(value),
    }
}

/// A 10 m beam (EI 1e4, mu 10) with a tight Newton tolerance.
pub(crate) fn params(elements: usize, boundary: Boundary) -> BeamParams {
    let mut p = BeamParams::new(10.0, elements, 1e4, 10.0, boundary);
    p.newton_tolerance = 1e-10;
    p
}

/// Clamped at the left, free at the right.
pub(crate) fn cantilever() -> Boundary {
    Boundary {
        left: [
            cond(Quantity::Deflection, 0.0),
            cond(Quantity::Rotation, 0.0),
        ],
        right: [cond(Quantity::Moment, 0.0), cond(Quantity::Shear, 0.0)],
    }
}

/// The static contact reference problem (seed 004 eq. 4.41) with `method`.
pub(crate) fn contact_params(elements: usize, method: Law) -> BeamParams {
    let mut p = params(
        elements,
        Boundary {
            left: [
                cond(Quantity::Deflection, 1.0),
                cond(Quantity::Rotation, -0.5),
            ],
            right: [cond(Quantity::Moment, 0.0), cond(Quantity::Shear, 0.0)],
        },
    );
    // The surface y >= 0 holds the beam from below; a small uniform load keeps the
    // free part on it without changing the shape before touchdown much.
    p.contact = Some(ContactParams {
        method,
        surface: Surface {
            shape: Shape::Flat { height: 0.0 },
            motion: Motion::None,
        },
        integration: ContactIntegration::Gauss,
        damping: 0.0,
        gap_band: 0.0,
    });
    p.static_start = true;
    p.newton_tolerance = 1e-9;
    p
}

/// The contact reference problem as a driven unit.
pub(crate) fn contact_problem(elements: usize, method: Law) -> Driver<Beam> {
    Driver::new(Beam::new(contact_params(elements, method)).unwrap())
}

/// Reference distance (eq. 4.42) to y_ref and the largest penetration.
pub(crate) fn reference_distance(beam: &Beam) -> (f64, f64) {
    let yref = |x: f64| {
        if x < 6.0 {
            -0.5f64.powi(3) * x.powi(3) / 27.0 + 0.25 * x * x / 3.0 - 0.5 * x + 1.0
        } else {
            0.0
        }
    };
    let n = 2000;
    let (mut sum, mut pen) = (0.0, 0.0f64);
    for i in 0..n {
        let x = (i as f64 + 0.5) * 10.0 / n as f64;
        let y = beam.deflection_at(x);
        sum += (y - yref(x)).powi(2) * 10.0 / n as f64;
        pen = pen.max(-y);
    }
    (sum.sqrt(), pen)
}
