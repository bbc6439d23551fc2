//! Parameters of the beam unit (scene kind `beam`).

use super::boundary::Boundary;
use crate::contact::Law;
use crate::contact::surface::Surface;
use crate::contract::{UnitError, require_in_range, require_non_negative, require_positive};
use serde::Deserialize;

/// Where the contact terms are integrated on each element.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ContactIntegration {
    /// Two Gauss-Legendre points per element.
    #[default]
    Gauss,
    /// The element's end nodes (trapezoidal rule).
    Trapezoid,
}

/// Contact of the beam with a surface.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactParams {
    /// The contact law (penalty, augmented Lagrangian or barrier).
    pub method: Law,
    /// The surface the beam touches.
    pub surface: Surface,
    /// Where the contact terms are integrated on each element.
    #[serde(default)]
    pub integration: ContactIntegration,
    /// Damping on contact c_c (N s/m per m), active where the gap <= gap_band.
    #[serde(default)]
    pub damping: f64,
    /// eps_g (m).
    #[serde(default)]
    pub gap_band: f64,
}

/// Named initial shapes.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum InitialShape {
    /// Seed 004 eq. 4.41: the static shape of a pipe held at x = 0 with deflection
    /// `deflection` > 0 and angle `angle` < 0, lying on y = 0 from x = -3 y0 / y0'.
    ContactReference {
        /// Deflection at x = 0 (m), > 0.
        deflection: f64,
        /// Angle at x = 0 (rad), < 0.
        angle: f64,
    },
}

impl InitialShape {
    /// Deflection and slope at x.
    pub fn at(&self, x: f64) -> (f64, f64) {
        match *self {
            InitialShape::ContactReference {
                deflection: y0,
                angle: t0,
            } => {
                if x < -3.0 * y0 / t0 {
                    let c3 = t0.powi(3) / (27.0 * y0 * y0);
                    let c2 = t0 * t0 / (3.0 * y0);
                    (
                        c3 * x.powi(3) + c2 * x * x + t0 * x + y0,
                        3.0 * c3 * x * x + 2.0 * c2 * x + t0,
                    )
                } else {
                    (0.0, 0.0)
                }
            }
        }
    }
}

/// Beam parameters (SI units).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BeamParams {
    /// Length L (m).
    pub length: f64,
    /// Equal elements over the length (ignored when `element_lengths` is given).
    #[serde(default = "default_elements")]
    pub elements: usize,
    /// Element lengths (m), summing to `length`, for unequal meshes.
    #[serde(default)]
    pub element_lengths: Option<Vec<f64>>,
    /// EI (N m^2).
    pub flexural_rigidity: f64,
    /// mu (kg/m).
    pub mass_per_length: f64,
    /// Constant axial tension T (N; negative in compression): adds -T y'' to the
    /// equation, so `shear` at an end is the transverse force EI y''' - T y'.
    #[serde(default)]
    pub tension: f64,
    /// c_d (N s/m^2): distributed viscous damping c_d y' (seed 004 eq. 2.11).
    #[serde(default)]
    pub damping_per_length: f64,
    /// Rayleigh damping C += rayleigh_mass M + rayleigh_stiffness K.
    #[serde(default)]
    pub rayleigh_mass: f64,
    /// Rayleigh damping proportional to stiffness (s): C = a M + b K, this is b.
    #[serde(default)]
    pub rayleigh_stiffness: f64,
    /// Distributed load w(x) = sum_i c_i x^i (N/m), constant in time.
    #[serde(default)]
    pub distributed_load: Vec<f64>,
    /// Initial deflection y0(x) = sum_i c_i x^i (m).
    #[serde(default)]
    pub initial_deflection: Vec<f64>,
    /// Initial velocity v0(x) = sum_i c_i x^i (m/s).
    #[serde(default)]
    pub initial_velocity: Vec<f64>,
    /// Positions x (m) whose deflection is output as `deflection_1`, `deflection_2`,
    /// ... (a profile of the pipe over time).
    #[serde(default)]
    pub stations: Vec<f64>,
    /// A named initial shape at rest, instead of `initial_deflection`.
    #[serde(default)]
    pub initial_shape: Option<InitialShape>,
    /// Start from the static equilibrium instead of `initial_deflection`.
    #[serde(default)]
    pub static_start: bool,
    /// The conditions at the two ends.
    pub boundary: Boundary,
    /// Contact with a surface, when the beam can touch one.
    #[serde(default)]
    pub contact: Option<ContactParams>,
    /// HHT-alpha in [0, 1/3] (0: trapezoidal rule, no numerical damping).
    #[serde(default)]
    pub alpha: f64,
    /// Newton stops when the largest correction is below this times
    /// max(1, largest |DOF|) (relative step tolerance).
    #[serde(default = "default_newton_tolerance")]
    pub newton_tolerance: f64,
    /// Newton iteration cap per step.
    #[serde(default = "default_newton_cap")]
    pub newton_max_iterations: u32,
    /// Static solver: first penalty p0 and growth psi per iteration (p0 psi^(n-1),
    /// capped at the method's penalty); default: the method's penalty from the start.
    #[serde(default)]
    pub static_penalty_start: Option<f64>,
    /// Growth of the static solver's penalty per iteration (see `static_penalty_start`).
    #[serde(default = "one")]
    pub static_penalty_growth: f64,
}

fn default_elements() -> usize {
    25
}

fn default_newton_tolerance() -> f64 {
    1e-10
}

fn default_newton_cap() -> u32 {
    30
}

fn one() -> f64 {
    1.0
}

impl BeamParams {
    /// A beam of `elements` equal elements with every optional parameter at its
    /// default: no damping, load, initial motion, contact or stations; alpha = 0.
    pub fn new(
        length: f64,
        elements: usize,
        flexural_rigidity: f64,
        mass_per_length: f64,
        boundary: Boundary,
    ) -> BeamParams {
        BeamParams {
            length,
            elements,
            element_lengths: None,
            flexural_rigidity,
            mass_per_length,
            tension: 0.0,
            damping_per_length: 0.0,
            rayleigh_mass: 0.0,
            rayleigh_stiffness: 0.0,
            distributed_load: Vec::new(),
            initial_deflection: Vec::new(),
            initial_velocity: Vec::new(),
            stations: Vec::new(),
            initial_shape: None,
            static_start: false,
            boundary,
            contact: None,
            alpha: 0.0,
            newton_tolerance: default_newton_tolerance(),
            newton_max_iterations: default_newton_cap(),
            static_penalty_start: None,
            static_penalty_growth: 1.0,
        }
    }

    /// The element lengths (m).
    pub fn lengths(&self) -> Vec<f64> {
        match &self.element_lengths {
            Some(l) => l.clone(),
            None => vec![self.length / self.elements as f64; self.elements],
        }
    }

    /// Checks every parameter, naming the first bad one.
    pub fn validate(&self) -> Result<(), UnitError> {
        self.validate_mesh()?;
        self.validate_properties()?;
        self.validate_solver()?;
        self.boundary.validate()?;
        if let Some(c) = &self.contact {
            c.method.validate()?;
            c.surface.validate()?;
            require_non_negative("contact.damping", c.damping)?;
            require_non_negative("contact.gap_band", c.gap_band)?;
        }
        Ok(())
    }

    /// Length and elements in range; element lengths that sum to the length.
    fn validate_mesh(&self) -> Result<(), UnitError> {
        // Physical ranges with margin (a thin cable to a large riser): beyond them
        // the matrices lose every digit and the diagnosis would be wrong.
        require_in_range("length", self.length, 1e-3, 1e5, "m")?;
        if self.elements == 0 || self.elements > 100_000 {
            return Err(UnitError::parameter(
                "elements",
                self.elements,
                "expected 1..=100000",
            ));
        }
        if let Some(l) = &self.element_lengths {
            if l.is_empty() || l.iter().any(|v| !(v.is_finite() && *v > 0.0)) {
                return Err(UnitError::parameter(
                    "element_lengths",
                    format!("{l:?}"),
                    "expected positive lengths",
                ));
            }
            let sum: f64 = l.iter().sum();
            if (sum - self.length).abs() > 1e-9 * self.length {
                return Err(UnitError::parameter(
                    "element_lengths",
                    sum,
                    &format!("expected lengths summing to length = {}", self.length),
                ));
            }
        }
        Ok(())
    }

    /// EI, mu and the damping in physical ranges; finite load and initial shapes.
    fn validate_properties(&self) -> Result<(), UnitError> {
        check_section(
            self.flexural_rigidity,
            self.mass_per_length,
            self.damping_per_length,
        )?;
        require_non_negative("rayleigh_mass", self.rayleigh_mass)?;
        require_non_negative("rayleigh_stiffness", self.rayleigh_stiffness)?;
        require_in_range("tension", self.tension, -1e10, 1e10, "N")?;
        for (name, poly) in [
            ("distributed_load", &self.distributed_load),
            ("initial_deflection", &self.initial_deflection),
            ("initial_velocity", &self.initial_velocity),
        ] {
            if poly.iter().any(|c| !c.is_finite()) {
                return Err(UnitError::parameter(
                    name,
                    format!("{poly:?}"),
                    "expected finite coefficients",
                ));
            }
        }
        Ok(())
    }

    /// HHT-alpha, stations, Newton and the static penalty continuation.
    fn validate_solver(&self) -> Result<(), UnitError> {
        if !(0.0..=1.0 / 3.0 + 1e-12).contains(&self.alpha) {
            return Err(UnitError::parameter(
                "alpha",
                self.alpha,
                "expected a value in [0, 1/3]",
            ));
        }
        if let Some(x) = self
            .stations
            .iter()
            .find(|x| !(x.is_finite() && **x >= 0.0 && **x <= self.length))
        {
            return Err(UnitError::parameter(
                "stations",
                x,
                &format!("expected positions in [0, {}]", self.length),
            ));
        }
        require_positive("newton_tolerance", self.newton_tolerance)?;
        if self.newton_max_iterations == 0 {
            return Err(UnitError::parameter(
                "newton_max_iterations",
                0,
                "expected at least 1",
            ));
        }
        if let Some(InitialShape::ContactReference { deflection, angle }) = self.initial_shape {
            if !(deflection > 0.0 && angle < 0.0 && deflection.is_finite() && angle.is_finite()) {
                return Err(UnitError::parameter(
                    "initial_shape",
                    format!("deflection {deflection}, angle {angle}"),
                    "the contact reference shape needs deflection > 0 and angle < 0",
                ));
            }
        }
        if let Some(p0) = self.static_penalty_start {
            require_positive("static_penalty_start", p0)?;
        }
        if self.static_penalty_growth.is_nan() || self.static_penalty_growth < 1.0 {
            return Err(UnitError::parameter(
                "static_penalty_growth",
                self.static_penalty_growth,
                "expected psi >= 1",
            ));
        }
        Ok(())
    }
}

/// sum_i c_i x^i and its derivative, by Horner's rule.
pub fn polynomial(c: &[f64], x: f64) -> (f64, f64) {
    let value = c.iter().rev().fold(0.0, |acc, ci| acc * x + ci);
    let slope = c
        .iter()
        .enumerate()
        .skip(1)
        .rev()
        .fold(0.0, |acc, (i, ci)| acc * x + i as f64 * ci);
    (value, slope)
}

/// Checks the properties of an Euler-Bernoulli section (beam or span) against
/// ranges that cover every slender marine structure, a thin cable to a large riser,
/// with margin: EI 1e-3..1e13 N m^2, mu 1e-3..1e7 kg/m, c_d 0..1e7 N s/m^2. Beyond
/// them the matrices and the transfer matrix lose every digit or overflow.
pub fn check_section(
    flexural_rigidity: f64,
    mass_per_length: f64,
    damping_per_length: f64,
) -> Result<(), UnitError> {
    require_in_range("flexural_rigidity", flexural_rigidity, 1e-3, 1e13, "N m^2")?;
    require_in_range("mass_per_length", mass_per_length, 1e-3, 1e7, "kg/m")?;
    require_in_range(
        "damping_per_length",
        damping_per_length,
        0.0,
        1e7,
        "N s/m^2",
    )
}
