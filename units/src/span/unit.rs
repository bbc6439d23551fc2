//! The span unit (scene kind `span`): the suspended span's response from the
//! rotation at its upper end (U2) to the deflection at its lower end (U5), with
//! y(0) = 0 and a free lower end (U1 = U7 = U8 = 0), as an order-N rational
//! approximation realised in state space and stepped exactly (matrix exponential;
//! input ramped or held over the step).

use super::rational::{RationalX, function_pade_u2_u5, taylor_u2_u5, term_pade_u2_u5};
use super::realization::{StateSpace, Stepper};
use super::transfer::Span;
use crate::contract::Time;
use crate::contract::{Capabilities, StepReport, Unit, UnitDescription, UnitError};
use crate::contract::{Inputs, Port, PortKind, StateVector};
use nalgebra::DVector;
use serde::Deserialize;

/// Which rational approximation.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Approximation {
    /// Taylor series of the exact transfer function.
    Taylor,
    /// Pade approximants of each term.
    TermPade,
    /// Pade approximant of the whole function.
    #[default]
    FunctionPade,
    /// Vector fitting of the exact transfer function over `band` (beyond the source).
    Fit,
}

/// Parameters of the span unit.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpanParams {
    /// EI (N m^2).
    pub flexural_rigidity: f64,
    /// mu (kg/m).
    pub mass_per_length: f64,
    /// c_d (N s/m^2), default 0.
    #[serde(default)]
    pub damping_per_length: f64,
    /// L (m).
    pub length: f64,
    /// Constant axial tension T (N), default 0; with tension only `fit` applies
    /// (the Taylor and Pade forms are those of the tension-free span).
    #[serde(default)]
    pub tension: f64,
    /// How the exact transfer function is approximated.
    #[serde(default)]
    pub approximation: Approximation,
    /// Order in s (even, 2..=24), default 8.
    #[serde(default = "eight")]
    pub order: usize,
    /// Band of interest (rad/s) for repairing an approximation with unstable poles;
    /// default 2 pi 10 (10 Hz, seed 004 sec. 5.2).
    #[serde(default = "ten_hz")]
    pub band: f64,
}

fn ten_hz() -> f64 {
    2.0 * std::f64::consts::PI * 10.0
}

fn eight() -> usize {
    8
}

impl SpanParams {
    /// The span's properties.
    pub fn span(&self) -> Span {
        Span {
            flexural_rigidity: self.flexural_rigidity,
            mass_per_length: self.mass_per_length,
            damping_per_length: self.damping_per_length,
            length: self.length,
            tension: self.tension,
        }
    }

    /// The rational approximation asked for.
    pub fn approximation(&self) -> Result<RationalX, UnitError> {
        match self.approximation {
            Approximation::Taylor => taylor_u2_u5(self.order),
            Approximation::TermPade => term_pade_u2_u5(self.order),
            Approximation::FunctionPade => function_pade_u2_u5(self.order),
            Approximation::Fit => Err(UnitError::Unsupported(
                "a vector fit has no rational form in x".into(),
            )),
        }
    }
}

crate::state_struct! {
    /// Everything that changes while stepping: the state-space vector.
    #[derive(Debug, serde::Serialize, serde::Deserialize)]
    struct SpanState {
        x: StateVector,
    }
}

/// The span unit.
pub struct SpanUnit {
    description: UnitDescription,
    system: StateSpace,
    state: SpanState,
    /// The exact step and the step length (s) it is for (None before the first step).
    stepper: Option<(f64, Stepper)>,
}

impl SpanUnit {
    /// Builds the unit; fails for bad properties or an order it cannot form.
    pub fn new(params: SpanParams) -> Result<SpanUnit, UnitError> {
        let span = params.span();
        span.validate()?;
        if span.tension != 0.0 && params.approximation != Approximation::Fit {
            return Err(UnitError::parameter(
                "approximation",
                format!("{:?}", params.approximation),
                "`fit` with a tension (the other forms are the tension-free span's)",
            ));
        }
        let system = match params.approximation {
            Approximation::Fit => super::fit::fit(&span, params.order, params.band)?,
            _ => StateSpace::realize(&params.approximation()?, &span, params.band)?,
        };
        let n = system.order();
        let feedthrough: &[usize] = if system.d != 0.0 { &[0] } else { &[] };
        Ok(SpanUnit {
            description: UnitDescription {
                kind: "span".into(),
                inputs: vec![Port::input("upper_rotation", PortKind::Rotation)],
                outputs: vec![
                    Port::output("lower_deflection", PortKind::Displacement)
                        .with_feedthrough(feedthrough),
                ],
                capabilities: Capabilities::default(),
            },
            state: SpanState {
                x: StateVector(DVector::zeros(n)),
            },
            stepper: None,
            system,
        })
    }

    /// The realised system (poles, repairs).
    pub fn system(&self) -> &StateSpace {
        &self.system
    }
}

impl Unit for SpanUnit {
    fn description(&self) -> &UnitDescription {
        &self.description
    }

    fn initialize(&mut self, _t0: Time, inputs: Inputs<'_>) -> Result<(), UnitError> {
        // Steady state for the initial input: x = -A^-1 B u0.
        let u0 = inputs.at(0, 0.0);
        let rhs = &self.system.b * (-u0);
        self.state.x = StateVector(self.system.a.clone().lu().solve(&rhs).ok_or_else(|| {
            UnitError::Numerical("the span's static gain is undefined (a pole at s = 0)".into())
        })?);
        Ok(())
    }

    fn do_step(&mut self, _t: Time, h: Time, inputs: Inputs<'_>) -> Result<StepReport, UnitError> {
        let h = h.as_secs();
        let (u0, u1) = (inputs.at(0, 0.0), inputs.at(0, 1.0));
        let stepper = match &mut self.stepper {
            Some((step, stepper)) if *step == h => stepper,
            slot => &mut slot.insert((h, self.system.stepper(h))).1,
        };
        stepper.advance(&mut self.state.x, u0, u1);
        // A non-finite entry makes the sum non-finite: one pass, no branch per entry.
        if !self.state.x.iter().sum::<f64>().is_finite() {
            return Err(UnitError::Numerical(
                "the span's state became non-finite".into(),
            ));
        }
        Ok(StepReport::default())
    }

    fn outputs(&self, inputs: Inputs<'_>, out: &mut [f64]) {
        out[0] = self.system.c.dot(&self.state.x) + self.system.d * inputs.end()[0];
    }

    slender_contract::state_in_field!(state: SpanState);
}
