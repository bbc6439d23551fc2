//! Building a reduced unit's model: what a section must not have, the basis
//! (modes, attachment vectors, derivatives) and its stepper.

use super::basis::{
    Derivative, Normalisation, attachment_vectors, dependent_columns, derivative_columns,
    highest_frequency, linear_modes,
};
use super::polynomial::CubicSection;
use super::system::ReducedSection;
use super::taylor::TaylorSection;
use super::unit::{Derivatives, Stepping};
use crate::contract::UnitError;
use crate::integrators::central_difference::CentralDifference;
use crate::integrators::hht::{HhtAlpha, SecondOrderSystem};
use crate::nonlinear::NonlinearParams;
use nalgebra::{DMatrix, DVector};

/// A linear basis's stepper.
pub(super) enum Stepper {
    Explicit(CentralDifference),
    Implicit(Box<Implicit>),
}

/// The trapezoidal rule's integrator and the step start it needs.
pub(super) struct Implicit {
    pub hht: HhtAlpha,
    /// The projected load at the step's start.
    pub f0: DVector<f64>,
    /// The nonlinear force at the step's start.
    pub g0: Vec<f64>,
}

/// The reduced model: a linear basis with its stepper, or a Taylor basis.
pub(super) enum Model {
    Linear(ReducedSection, Stepper),
    Taylor(TaylorSection),
}

/// Seed 002's SVD tolerance for dependent derivatives (unit-norm columns).
const DEPENDENCE_TOLERANCE: f64 = 3e-6;

/// Refuses a section with effects the reduced model does not carry (it has
/// mass, stiffness and the section's loads only), rather than dropping them.
pub(super) fn refuse_what_is_not_reduced(section: &NonlinearParams) -> Result<(), UnitError> {
    let refuse = |key: &str, value: &dyn ToString| {
        Err(UnitError::parameter(
            &format!("section.{key}"),
            value.to_string(),
            "expected none: a reduced section carries mass, stiffness and loads, not damping, drag, current, contact or a static start",
        ))
    };
    if section.rayleigh_mass != 0.0 || section.rayleigh_stiffness != 0.0 {
        return refuse(
            "rayleigh_mass/rayleigh_stiffness",
            &format!("{}/{}", section.rayleigh_mass, section.rayleigh_stiffness),
        );
    }
    for (i, s) in section.segments.iter().enumerate() {
        if s.diameter > 0.0 && (s.drag_normal != 0.0 || s.drag_tangential != 0.0) {
            return refuse(&format!("segments[{i}].drag_normal"), &s.drag_normal);
        }
    }
    if section.current.is_some() {
        return refuse("current", &"a current");
    }
    if section.contact.is_some() || section.stinger.is_some() {
        return refuse("contact/stinger", &"contact");
    }
    if section.static_start {
        return refuse("static_start", &true);
    }
    Ok(())
}

/// The reduced model of `cubic` on `count` modes (and the attachment vectors of
/// the free DOFs `loaded`) and its critical step (s).
pub(super) fn build_model(
    cubic: &CubicSection,
    (count, derivatives): (usize, Derivatives),
    loaded: &[usize],
    stepping: Stepping,
) -> Result<(Model, f64), UnitError> {
    if stepping == Stepping::Trapezoidal && derivatives == Derivatives::Taylor {
        return Err(UnitError::parameter(
            "integrator",
            "trapezoidal",
            "expected \"central_difference\" with derivatives = \"taylor\" (its stable step is the modes' own; the trapezoidal rule is for a linear basis)",
        ));
    }
    let modes = linear_modes(cubic, count, Normalisation::Mass)?;
    let phi = DMatrix::from_columns(&modes.shapes);
    let statics = attachment_vectors(cubic, loaded, &modes.shapes)?;
    Ok(match derivatives {
        Derivatives::Taylor => {
            let mds = derivative_columns(cubic, &modes, Derivative::Novel, count)?;
            let taylor = TaylorSection::with_static_columns(
                cubic,
                &phi,
                &DMatrix::from_columns(&mds),
                &columns_of(cubic.size(), &statics),
            )?;
            // Linearised at rest only the linear columns remain: 2 / omega_N,
            // the last mode's unless attachment vectors stiffen the span.
            let omega = match statics.is_empty() {
                true => modes.omegas.last().copied().unwrap_or(0.0),
                false => {
                    let linear: Vec<_> = modes.shapes.iter().chain(&statics).cloned().collect();
                    highest_frequency(cubic, &columns_of(cubic.size(), &linear))?
                }
            };
            let critical = if omega > 0.0 {
                2.0 / omega
            } else {
                f64::INFINITY
            };
            (Model::Taylor(taylor), critical)
        }
        kind => {
            let mut columns = modes.shapes.clone();
            columns.extend(statics);
            if kind == Derivatives::Linear {
                let kept = columns.len();
                columns.extend(derivative_columns(cubic, &modes, Derivative::Novel, count)?);
                // A derivative in the span of the others (an attachment vector
                // can hold one) would make the reduced mass singular.
                let dependent = dependent_columns(&columns, DEPENDENCE_TOLERANCE, kept)?;
                let mut k = 0;
                columns.retain(|_| {
                    k += 1;
                    dependent.binary_search(&(k - 1)).is_err()
                });
            }
            let system = ReducedSection::new(cubic, DMatrix::from_columns(&columns));
            match stepping {
                Stepping::CentralDifference => {
                    let critical = CentralDifference::critical_step(&system.matrices(), 400)?;
                    let stepper = Stepper::Explicit(CentralDifference::new());
                    (Model::Linear(system, stepper), critical)
                }
                Stepping::Trapezoidal => {
                    let n = system.size();
                    let mut hht = HhtAlpha::new(0.0, n, n.saturating_sub(1));
                    // Its Newton matrix gives the step Jacobian.
                    hht.keep_newton_matrix();
                    let stepper = Stepper::Implicit(Box::new(Implicit {
                        hht,
                        f0: DVector::zeros(n),
                        g0: vec![0.0; n],
                    }));
                    (Model::Linear(system, stepper), f64::INFINITY)
                }
            }
        }
    })
}

/// The vectors as the columns of a `rows` x n matrix (n may be 0).
fn columns_of(rows: usize, vectors: &[DVector<f64>]) -> DMatrix<f64> {
    DMatrix::from_fn(rows, vectors.len(), |i, j| vectors[j][i])
}
