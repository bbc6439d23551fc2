//! A chord section's motion along its chord: its loaded end carries a mass
//! (`axial_mass`, kg) on a spring (`axial_stiffness`, N/m) to the moving end,
//! stepped by Newmark's rule (gamma = 1/2 + alpha, beta = (1 + alpha)^2 / 4:
//! the trapezoidal rule at alpha = 0, unconditionally stable). Without a mass
//! the loaded end sits where the spring balances its force (quasi-static);
//! without a spring the section is a rigid link along the chord.
//!
//! The loaded end's displacement at a step's end is affine in that step's end
//! inputs (the moving end's slide and the loaded end's axial force), so the
//! unit's outputs follow its inputs at a communication point exactly and its
//! step Jacobian stays exact: d u / d F = beta h^2 / (M + beta h^2 k).

use crate::contract::{Time, UnitError};
use crate::contract::{require_finite_state, require_positive};
use serde::{Deserialize, Serialize};

/// Displacement (m), velocity (m/s) and acceleration (m/s^2) of the loaded
/// end along the chord, from the equilibrium.
#[derive(Copy, Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub(super) struct Motion {
    pub displacement: f64,
    pub velocity: f64,
    pub acceleration: f64,
}

/// The saved motion: at the start of the step last taken and at its end, and
/// that step's size (s; zero before the first step).
#[derive(Copy, Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub(super) struct AxialState {
    start: Motion,
    end: Motion,
    step: f64,
}

/// The axial model of a chord section.
#[derive(Copy, Clone, Debug)]
pub(super) struct Axial {
    stiffness: Option<f64>,
    mass: Option<f64>,
    beta: f64,
    gamma: f64,
    pub state: AxialState,
}

impl Axial {
    /// The model from the section's parameters; a mass needs a stiffness (a
    /// rigid link has no motion of its own along the chord).
    pub(super) fn new(
        stiffness: Option<f64>,
        mass: Option<f64>,
        alpha: f64,
    ) -> Result<Axial, UnitError> {
        if let Some(k) = stiffness {
            require_positive("axial_stiffness", k)?;
        }
        if let Some(m) = mass {
            require_positive("axial_mass", m)?;
            if stiffness.is_none() {
                return Err(UnitError::parameter(
                    "axial_mass",
                    format!("{m}"),
                    "needs `axial_stiffness`: without it the section is a rigid link along its chord",
                ));
            }
        }
        Ok(Axial {
            stiffness,
            mass,
            beta: 0.25 * (1.0 + alpha).powi(2),
            gamma: 0.5 + alpha,
            state: AxialState::default(),
        })
    }

    /// Whether the loaded end's displacement follows the axial force.
    pub(super) fn stretches(&self) -> bool {
        self.stiffness.is_some()
    }

    /// Whether the moving end's axial force lags the loaded end's (a mass
    /// between them): it then follows the moving end's slide too.
    pub(super) fn has_mass(&self) -> bool {
        self.mass.is_some()
    }

    /// At rest in the equilibrium.
    pub(super) fn initialize(&mut self) {
        self.state = AxialState::default();
    }

    /// Takes a step of `h` to the end inputs: the moving end's slide (m) and
    /// the change of the loaded end's axial force (N, outward).
    pub(super) fn do_step(&mut self, h: Time, slide: f64, force: f64) {
        let step = h.as_secs();
        let start = self.state.end;
        self.state = AxialState {
            start,
            end: self.advance(start, step, slide, force),
            step,
        };
    }

    /// The loaded end's displacement along the chord (m) and the change of
    /// the axial force (N) the section exerts on its moving end's neighbour,
    /// pulling it along the chord, with the current end inputs `slide` and
    /// `force` (as in `do_step`): the spring's force, or without a mass the
    /// loaded end's change passing through.
    pub(super) fn response(&self, slide: f64, force: f64) -> (f64, f64) {
        let s = &self.state;
        let displacement = match (self.mass, s.step > 0.0) {
            (Some(_), true) => self.advance(s.start, s.step, slide, force).displacement,
            _ => self.quasi_static(slide, force),
        };
        let pull = match (self.stiffness, self.mass) {
            (Some(k), Some(_)) => k * (displacement - slide),
            _ => force,
        };
        (displacement, pull)
    }

    /// Where the spring alone puts the loaded end (m).
    fn quasi_static(&self, slide: f64, force: f64) -> f64 {
        slide + self.stiffness.map_or(0.0, |k| force / k)
    }

    /// An error where the motion along the chord became non-finite.
    pub(super) fn require_finite(&self) -> Result<(), UnitError> {
        let m = &self.state.end;
        require_finite_state(
            "the chord's motion along itself (displacement, velocity, acceleration)",
            &[m.displacement, m.velocity, m.acceleration],
        )
    }

    /// Newmark's step from `start` over `h` (s).
    fn advance(&self, start: Motion, h: f64, slide: f64, force: f64) -> Motion {
        let (Some(k), Some(m)) = (self.stiffness, self.mass) else {
            return Motion {
                displacement: self.quasi_static(slide, force),
                ..Motion::default()
            };
        };
        let (beta, gamma) = (self.beta, self.gamma);
        let predicted =
            start.displacement + h * start.velocity + h * h * (0.5 - beta) * start.acceleration;
        let bh2 = beta * h * h;
        let displacement = (m * predicted + bh2 * (force + k * slide)) / (m + bh2 * k);
        let acceleration = (force - k * (displacement - slide)) / m;
        Motion {
            displacement,
            velocity: start.velocity
                + h * ((1.0 - gamma) * start.acceleration + gamma * acceleration),
            acceleration,
        }
    }
}
