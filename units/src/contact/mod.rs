//! Contact of a body with a surface y >= f(x): the gap d = y - f, and the contact
//! laws of seed 004 ch. 3 as penalty functionals Xi(d) with their derivatives,
//! plus an energy-conserving penalty.
//!
//! A law gives, for a gap d and a Lagrangian parameter lambda, the energy density
//! Xi(d), the force density g = dXi/dd (negative: it pushes the body up) and its
//! slope dg/dd. The barrier's lambda is positive here: it is minus the source's.

pub mod surface;

use crate::contract::{UnitError, require_positive};
use serde::{Deserialize, Serialize};

/// When the Lagrangian parameter of the augmented methods is updated.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum LambdaUpdate {
    /// Scheme 1: after every Newton iteration.
    NewtonIteration,
    /// Scheme 2: after every time step.
    #[default]
    TimeStep,
}

/// A contact law (scene table `contact.method`).
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Law {
    /// Xi = p d^2 / 2 for d <= 0 (a spring in the surface).
    Penalty {
        /// Penalty p (N/m per m of contact, or N/m at a node).
        penalty: f64,
    },
    /// Xi = (lambda + p d)^2 / (2p) for lambda + p d <= 0 (eq. 3.4).
    AugmentedLagrangian {
        /// Penalty p (N/m per m of contact, or N/m at a node).
        penalty: f64,
        /// Starting Lagrangian parameter lambda (force per length, like g).
        #[serde(default)]
        lambda0: f64,
        /// Relaxation of the update in [0, 1]: lambda+ = eta lambda- + (1 - eta) g (eq. 3.12).
        #[serde(default)]
        eta: f64,
        /// When lambda is updated.
        #[serde(default)]
        update: LambdaUpdate,
    },
    /// Shifted logarithmic barrier with quadratic extension (eq. 3.8).
    AugmentedBarrier {
        /// Penalty p (N/m per m of contact, or N/m at a node).
        penalty: f64,
        /// Starting Lagrangian parameter lambda (> 0 here: minus the source's).
        #[serde(default = "one")]
        lambda0: f64,
        /// The barrier's shift s (>= 1, eq. 3.8).
        #[serde(default = "one")]
        s: f64,
        /// Where the logarithm gives way to the quadratic extension, in (0, 1).
        #[serde(default = "half")]
        beta: f64,
        /// Relaxation of the update in [0, 1]: lambda+ = eta lambda- + (1 - eta) g (eq. 3.12).
        #[serde(default)]
        eta: f64,
        /// When lambda is updated.
        #[serde(default)]
        update: LambdaUpdate,
    },
    /// Penalty whose force over a step is the discrete gradient
    /// (Xi(d1) - Xi(d0)) / (d1 - d0): with the trapezoidal rule (alpha = 0) the
    /// contact neither adds nor removes energy (after Armero and Petocz 1998).
    EnergyConserving {
        /// Penalty p (N/m per m of contact, or N/m at a node).
        penalty: f64,
    },
}

fn one() -> f64 {
    1.0
}

fn half() -> f64 {
    0.5
}

impl Law {
    /// Checks the parameters.
    pub fn validate(&self) -> Result<(), UnitError> {
        match *self {
            Law::Penalty { penalty } | Law::EnergyConserving { penalty } => {
                require_positive("contact.penalty", penalty)
            }
            Law::AugmentedLagrangian {
                penalty,
                lambda0,
                eta,
                ..
            } => {
                require_positive("contact.penalty", penalty)?;
                if lambda0.is_nan() || lambda0 > 0.0 {
                    return Err(UnitError::parameter(
                        "contact.lambda0",
                        lambda0,
                        "expected <= 0 for the augmented Lagrangian",
                    ));
                }
                check_eta(eta)
            }
            Law::AugmentedBarrier {
                penalty,
                lambda0,
                s,
                beta,
                eta,
                ..
            } => {
                require_positive("contact.penalty", penalty)?;
                require_positive("contact.lambda0", lambda0)?;
                if s.is_nan() || s < 1.0 {
                    return Err(UnitError::parameter("contact.s", s, "expected s >= 1"));
                }
                if !(beta > 0.0 && beta < 1.0) {
                    return Err(UnitError::parameter(
                        "contact.beta",
                        beta,
                        "expected a value in (0, 1)",
                    ));
                }
                check_eta(eta)
            }
        }
    }

    /// The starting Lagrangian parameter.
    pub fn lambda0(&self) -> f64 {
        match *self {
            Law::AugmentedLagrangian { lambda0, .. } | Law::AugmentedBarrier { lambda0, .. } => {
                lambda0
            }
            _ => 0.0,
        }
    }

    /// When lambda is updated; `None` for laws without one.
    pub fn lambda_update(&self) -> Option<LambdaUpdate> {
        match *self {
            Law::AugmentedLagrangian { update, .. } | Law::AugmentedBarrier { update, .. } => {
                Some(update)
            }
            _ => None,
        }
    }

    /// (Xi, g = dXi/dd, dg/dd) at gap d with parameter lambda.
    pub fn evaluate(&self, d: f64, lambda: f64) -> (f64, f64, f64) {
        match *self {
            Law::Penalty { penalty: p } | Law::EnergyConserving { penalty: p } => {
                if d <= 0.0 {
                    (0.5 * p * d * d, p * d, p)
                } else {
                    (0.0, 0.0, 0.0)
                }
            }
            Law::AugmentedLagrangian { penalty: p, .. } => {
                let z = lambda + p * d;
                if z <= 0.0 {
                    (z * z / (2.0 * p), z, p)
                } else {
                    (0.0, 0.0, 0.0)
                }
            }
            Law::AugmentedBarrier {
                penalty: p,
                s,
                beta,
                ..
            } => {
                let l = lambda;
                if d >= -beta * s / p {
                    let z = s + p * d;
                    // Xi = -(l / p) log(z): g = -l / z pushes the body away (eq. 3.8 with
                    // the sign that makes the barrier repel; lambda > 0).
                    (-(l / p) * z.ln(), -l / z, l * p / (z * z))
                } else {
                    // Quadratic continuation matching value, slope and curvature sign.
                    let z0 = s * (1.0 - beta);
                    let g0 = -l / z0;
                    let k0 = l * p / (z0 * z0);
                    let dd = d + beta * s / p;
                    let xi0 = -(l / p) * z0.ln();
                    (xi0 + g0 * dd + 0.5 * k0 * dd * dd, g0 + k0 * dd, k0)
                }
            }
        }
    }

    /// The Lagrangian update lambda+ = eta lambda- + (1 - eta) g(d; lambda-) (eq. 3.12).
    pub fn updated_lambda(&self, d: f64, lambda: f64) -> f64 {
        match *self {
            Law::AugmentedLagrangian { eta, .. } => {
                let (_, g, _) = self.evaluate(d, lambda);
                eta * lambda + (1.0 - eta) * g
            }
            Law::AugmentedBarrier { eta, .. } => {
                // lambda+ = lambda / (s + p d) (eq. 3.11; lambda > 0 here is minus the
                // source's lambda), kept positive.
                let (_, g, _) = self.evaluate(d, lambda);
                (eta * lambda + (1.0 - eta) * (-g)).max(1e-12)
            }
            _ => lambda,
        }
    }
}

fn check_eta(eta: f64) -> Result<(), UnitError> {
    if (0.0..=1.0).contains(&eta) {
        Ok(())
    } else {
        Err(UnitError::parameter(
            "contact.eta",
            eta,
            "expected a value in [0, 1]",
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fd_check(law: &Law, lambda: f64) {
        for d in [-0.3, -0.05, -0.001, 0.02, 0.4] {
            let h = 1e-7;
            let (x0, g0, k0) = law.evaluate(d, lambda);
            let (x1, g1, _) = law.evaluate(d + h, lambda);
            assert!(
                ((x1 - x0) / h - g0).abs() < 1e-4 * (1.0 + g0.abs()),
                "{law:?} g at {d}"
            );
            assert!(
                ((g1 - g0) / h - k0).abs() < 1e-3 * (1.0 + k0.abs()),
                "{law:?} k at {d}"
            );
        }
    }

    #[test]
    fn each_law_is_consistent_with_its_derivatives() {
        fd_check(&Law::Penalty { penalty: 100.0 }, 0.0);
        fd_check(
            &Law::AugmentedLagrangian {
                penalty: 100.0,
                lambda0: -1.0,
                eta: 0.0,
                update: LambdaUpdate::TimeStep,
            },
            -1.0,
        );
        fd_check(
            &Law::AugmentedBarrier {
                penalty: 10.0,
                lambda0: 1.0,
                s: 1.0,
                beta: 0.5,
                eta: 0.0,
                update: LambdaUpdate::TimeStep,
            },
            1.0,
        );
    }

    #[test]
    fn the_penalty_pushes_a_penetrating_body_up_and_leaves_a_free_one_alone() {
        let law = Law::Penalty { penalty: 1e4 };
        assert!(law.evaluate(-0.01, 0.0).1 < 0.0);
        assert_eq!(law.evaluate(0.01, 0.0), (0.0, 0.0, 0.0));
    }
}
