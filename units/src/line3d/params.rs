//! Parameters of the 3D line unit (scene kind `line3d`), SI units, z up.
//!
//! The line runs from its `start` end (the anchor, or the lower cut of a
//! section) to its `end` end (the fairlead, or the upper cut); its start shape
//! is the static equilibrium between the two points. Every table is checked
//! once by [`Line3dParams::validate`]; a refusal names the key.

use crate::contract::{UnitError, require_finite, require_non_negative, require_positive};
use crate::sea::spectrum::Spectrum;
use crate::signal::sine::Sine;
use serde::{Deserialize, Serialize};

/// The 3D line's parameters.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Line3dParams {
    /// Unstretched length (m).
    pub length: f64,
    /// Number of equal elements (straight segments between nodes).
    pub elements: usize,
    /// EA (N).
    pub axial_stiffness: f64,
    /// EI (N m^2); 0 for a chain or a rope.
    #[serde(default)]
    pub bending_stiffness: f64,
    /// Torsion is not modelled (a line of isotropic section whose twist does
    /// not feed back into its shape); a value > 0 is refused with that reason.
    #[serde(default)]
    pub torsional_stiffness: f64,
    /// Internal axial damping BA (N s): tension rate = BA * strain rate.
    #[serde(default)]
    pub axial_damping: f64,
    /// Structural mass per unit length (kg/m).
    pub mass_per_length: f64,
    /// Weight in water per unit length (N/m, positive down).
    #[serde(default)]
    pub submerged_weight: f64,
    /// Hydrodynamic diameter (m); needed for drag, added mass and waves.
    #[serde(default)]
    pub diameter: f64,
    /// Morison drag coefficients normal and tangential to the line (the
    /// tangential one on the surface pi D, as MoorDyn and the planar unit).
    #[serde(default)]
    pub drag_normal: f64,
    /// Morison drag coefficient tangential to the line (on the surface pi D).
    #[serde(default)]
    pub drag_tangential: f64,
    /// Added-mass coefficients normal and tangential.
    #[serde(default)]
    pub added_mass_normal: f64,
    /// Added-mass coefficient tangential to the line.
    #[serde(default)]
    pub added_mass_tangential: f64,
    /// Water density (kg/m^3).
    #[serde(default = "default_water_density")]
    pub water_density: f64,
    /// Where the line starts (m) and how that end is held or loaded.
    pub start: EndSpec,
    /// Where the line ends (m) and how.
    pub end: EndSpec,
    /// The seabed, when the line can touch it.
    #[serde(default)]
    pub seabed: Option<Seabed>,
    /// Current speed and heading by depth.
    #[serde(default)]
    pub current: Vec<CurrentPoint>,
    /// Airy waves acting on the submerged nodes.
    #[serde(default)]
    pub waves: Option<Waves>,
    /// HHT-alpha numerical damping in [0, 1/3].
    #[serde(default = "default_alpha")]
    pub alpha: f64,
    /// Step the line linearised about its static state (see
    /// `line3d::linear`): one back-substitution a step, for small motion.
    #[serde(default)]
    pub linear: bool,
    /// Largest internal step (s); a coupling step is cut into equal steps no
    /// longer than this (0: one internal step per coupling step).
    #[serde(default)]
    pub max_step: f64,
    /// Newton's tolerance on the largest correction relative to max(1, |q|).
    #[serde(default = "default_tolerance")]
    pub tolerance: f64,
    /// Newton's iteration bound per step.
    #[serde(default = "default_iterations")]
    pub max_iterations: u32,
}

/// An end of the line: its position at the start and its condition.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct EndSpec {
    /// Position at t0 (m): x, y, z (z up).
    pub position: [f64; 3],
    /// How it is held or loaded (default fixed).
    #[serde(default)]
    pub condition: EndCondition,
    /// With `condition = "motion"`: sines added to the position per axis (m).
    #[serde(default)]
    pub motion: [Vec<Sine>; 3],
    /// Seconds over which the motion's sines grow from nothing (a half
    /// cosine), so a run does not start with a jump in velocity; 0: none.
    #[serde(default)]
    pub fade_in: f64,
    /// The time (s) the end lets go (a line that breaks at its fairlead):
    /// from the first step starting then, it is free and exerts no force.
    #[serde(default)]
    pub released_at: Option<f64>,
}

impl EndSpec {
    /// An end at `position` (m) held or moved as `condition` says, without
    /// a motion of its own (a section's cut end, a mooring line's anchor or
    /// fairlead).
    pub fn at(position: [f64; 3], condition: EndCondition) -> EndSpec {
        EndSpec {
            position,
            condition,
            motion: Default::default(),
            fade_in: 0.0,
            released_at: None,
        }
    }

    /// Whether the end has let go for a step starting at `t` (s).
    pub fn released(&self, t: f64) -> bool {
        self.released_at
            .is_some_and(|at| t >= at - 1e-9 * at.abs().max(1.0))
    }
}

/// How an end is held or loaded.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum EndCondition {
    /// Held at its position.
    #[default]
    Fixed,
    /// Moved by the sines of `motion`.
    Motion,
    /// Moved by coupled velocity inputs (`<side>_velocity_x|y|z`, m/s); the
    /// force it exerts on what moves it is an output.
    Velocity,
    /// Loaded by coupled force inputs (`<side>_force_x|y|z`, N, the force
    /// applied on the line); its motion is an output.
    Force,
}

/// The seabed: a plane through (0, 0, -depth) with slopes dz/dx and dz/dy,
/// or a bathymetry grid; normal contact by a penalty spring and damper per
/// unit length, and Coulomb friction regularised by a stick velocity.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Seabed {
    /// Depth of the seabed plane below z = 0 at x = y = 0 (m).
    #[serde(default)]
    pub depth: Option<f64>,
    /// dz/dx and dz/dy of the plane.
    #[serde(default)]
    pub slope: [f64; 2],
    /// The seabed's depth on a grid, bilinear, in place of the plane.
    #[serde(default)]
    pub bathymetry: Option<super::bathymetry::Bathymetry>,
    /// Normal stiffness per unit length of line (N/m per m of penetration).
    pub stiffness: f64,
    /// Normal damping per unit length of line (N s/m^2), while in contact.
    #[serde(default)]
    pub damping: f64,
    /// Coulomb coefficients along the line and across it.
    #[serde(default)]
    pub friction_axial: f64,
    /// Coulomb coefficient across the line.
    #[serde(default)]
    pub friction_lateral: f64,
    /// Friction is mu N tanh(v / stick_velocity) in each direction (m/s): a
    /// smooth form of MoorDyn's saturated damping; a line creeps at about
    /// stick_velocity F / (mu N) under a load F below the friction limit.
    #[serde(default = "default_stick_velocity")]
    pub stick_velocity: f64,
}

/// One row of the current table.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CurrentPoint {
    /// Depth below z = 0 (m, positive down).
    pub depth: f64,
    /// Speed (m/s).
    pub speed: f64,
    /// Direction the current flows towards, counter-clockwise from +x (deg).
    #[serde(default)]
    pub heading_deg: f64,
}

/// Airy waves: a sea state's components (or sines given), travelling towards
/// a heading, on water of a depth (infinite when absent).
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Waves {
    /// The elevation's spectrum (seeded components), or ...
    #[serde(default)]
    pub spectrum: Option<Spectrum>,
    /// ... its components as sines of the elevation at x = y = 0 (m).
    #[serde(default)]
    pub sines: Vec<Sine>,
    /// Direction the waves travel towards, counter-clockwise from +x (deg).
    #[serde(default)]
    pub heading_deg: f64,
    /// Water depth for the dispersion relation (m); 0: deep water.
    #[serde(default)]
    pub water_depth: f64,
    /// Seconds over which the waves grow from calm (a half cosine on their
    /// velocity and elevation), so a run does not start with the full wave
    /// force on a line at rest; 0: none.
    #[serde(default)]
    pub fade_in: f64,
}

fn default_water_density() -> f64 {
    1025.0
}

fn default_alpha() -> f64 {
    0.3
}

fn default_tolerance() -> f64 {
    1e-10
}

fn default_iterations() -> u32 {
    50
}

fn default_stick_velocity() -> f64 {
    0.01
}

impl Line3dParams {
    /// Checks every value; the error names the key.
    pub fn validate(&self) -> Result<(), UnitError> {
        require_positive("length", self.length)?;
        if !(2..=100_000).contains(&self.elements) {
            return Err(UnitError::parameter(
                "elements",
                self.elements,
                "2 to 100 000 elements",
            ));
        }
        require_positive("axial_stiffness", self.axial_stiffness)?;
        require_positive("mass_per_length", self.mass_per_length)?;
        if self.torsional_stiffness != 0.0 {
            return Err(UnitError::parameter(
                "torsional_stiffness",
                self.torsional_stiffness,
                "0: torsion is not modelled by `line3d` (isotropic lines whose twist does not change their shape: mooring lines and risers)",
            ));
        }
        for (key, value) in [
            ("bending_stiffness", self.bending_stiffness),
            ("axial_damping", self.axial_damping),
            ("submerged_weight", self.submerged_weight),
            ("diameter", self.diameter),
            ("drag_normal", self.drag_normal),
            ("drag_tangential", self.drag_tangential),
            ("added_mass_normal", self.added_mass_normal),
            ("added_mass_tangential", self.added_mass_tangential),
            ("max_step", self.max_step),
        ] {
            require_non_negative(key, value)?;
        }
        require_positive("water_density", self.water_density)?;
        self.validate_solver()?;
        self.validate_hydrodynamics()?;
        for (side, end) in [("start", &self.start), ("end", &self.end)] {
            end.validate(side)?;
            if self.linear && end.released_at.is_some() {
                return Err(UnitError::parameter(
                    &format!("{side}.released_at"),
                    "given",
                    "no release on a linear line (linearised about its held ends); use the nonlinear line",
                ));
            }
        }
        let span = distance(self.start.position, self.end.position);
        if span > self.length * (1.0 + 0.5) {
            return Err(UnitError::parameter(
                "end.position",
                format!("{:?}", self.end.position),
                "a point the line reaches: its distance from start.position at most 1.5 x the length",
            ));
        }
        if let Some(seabed) = &self.seabed {
            seabed.validate()?;
        }
        for (i, c) in self.current.iter().enumerate() {
            require_non_negative(&format!("current[{i}].depth"), c.depth)?;
            require_non_negative(&format!("current[{i}].speed"), c.speed)?;
            require_finite(&format!("current[{i}].heading_deg"), c.heading_deg)?;
            if i > 0 && c.depth <= self.current[i - 1].depth {
                return Err(UnitError::parameter(
                    &format!("current[{i}].depth"),
                    c.depth,
                    "depths increasing down the table",
                ));
            }
        }
        if let Some(waves) = &self.waves {
            waves.validate()?;
        }
        Ok(())
    }

    fn validate_solver(&self) -> Result<(), UnitError> {
        if !(0.0..=1.0 / 3.0).contains(&self.alpha) {
            return Err(UnitError::parameter("alpha", self.alpha, "in [0, 1/3]"));
        }
        if !(self.tolerance > 0.0 && self.tolerance < 1e-2) {
            return Err(UnitError::parameter(
                "tolerance",
                self.tolerance,
                "in (0, 1e-2)",
            ));
        }
        if self.max_iterations == 0 || self.max_iterations > 1000 {
            return Err(UnitError::parameter(
                "max_iterations",
                self.max_iterations,
                "1 to 1000",
            ));
        }
        Ok(())
    }

    fn validate_hydrodynamics(&self) -> Result<(), UnitError> {
        let hydro = self.drag_normal
            + self.drag_tangential
            + self.added_mass_normal
            + self.added_mass_tangential;
        if (hydro > 0.0 || self.waves.is_some()) && self.diameter <= 0.0 {
            return Err(UnitError::parameter(
                "diameter",
                self.diameter,
                "a diameter > 0 where drag, added-mass coefficients or waves are given",
            ));
        }
        Ok(())
    }
}

impl EndSpec {
    fn validate(&self, side: &str) -> Result<(), UnitError> {
        for (axis, &p) in ["x", "y", "z"].iter().zip(&self.position) {
            require_finite(&format!("{side}.position.{axis}"), p)?;
        }
        require_non_negative(&format!("{side}.fade_in"), self.fade_in)?;
        if let Some(at) = self.released_at {
            require_finite(&format!("{side}.released_at"), at)?;
            if self.condition == EndCondition::Force {
                return Err(UnitError::parameter(
                    &format!("{side}.released_at"),
                    at,
                    "a held or moved end (a loaded end is free already)",
                ));
            }
        }
        let has_motion = self.motion.iter().any(|m| !m.is_empty());
        if has_motion != (self.condition == EndCondition::Motion) {
            return Err(UnitError::parameter(
                &format!("{side}.motion"),
                if has_motion { "given" } else { "absent" },
                "sines exactly when condition = \"motion\"",
            ));
        }
        for (axis, sines) in ["x", "y", "z"].iter().zip(&self.motion) {
            for (i, s) in sines.iter().enumerate() {
                s.check(&format!("{side}.motion.{axis}[{i}]"))?;
            }
        }
        Ok(())
    }
}

impl Seabed {
    fn validate(&self) -> Result<(), UnitError> {
        match (&self.depth, &self.bathymetry) {
            (Some(depth), None) => require_finite("seabed.depth", *depth)?,
            (None, Some(grid)) if self.slope == [0.0, 0.0] => grid.validate()?,
            _ => {
                return Err(UnitError::parameter(
                    "seabed",
                    "depth, slope and bathymetry",
                    "`depth` (with `slope`: a plane) or `bathymetry` (a grid), one of them",
                ));
            }
        }
        for (k, s) in ["seabed.slope.x", "seabed.slope.y"].iter().zip(self.slope) {
            require_finite(k, s)?;
        }
        require_positive("seabed.stiffness", self.stiffness)?;
        for (key, value) in [
            ("seabed.damping", self.damping),
            ("seabed.friction_axial", self.friction_axial),
            ("seabed.friction_lateral", self.friction_lateral),
        ] {
            require_non_negative(key, value)?;
        }
        require_positive("seabed.stick_velocity", self.stick_velocity)
    }
}

impl Waves {
    /// Refuses a sea with neither or both of a spectrum and sines, or a
    /// bad component, naming the key.
    pub fn validate(&self) -> Result<(), UnitError> {
        if self.spectrum.is_some() != self.sines.is_empty() {
            return Err(UnitError::parameter(
                "waves",
                "spectrum and sines",
                "either `spectrum` or `sines`",
            ));
        }
        if let Some(Err((k, value, expected))) = self.spectrum.as_ref().map(Spectrum::validate) {
            return Err(UnitError::parameter(
                &format!("waves.spectrum.{k}"),
                value,
                expected,
            ));
        }
        for (i, s) in self.sines.iter().enumerate() {
            s.check(&format!("waves.sines[{i}]"))?;
            require_positive(
                &format!("waves.sines[{i}].angular_frequency"),
                s.angular_frequency,
            )?;
        }
        require_finite("waves.heading_deg", self.heading_deg)?;
        require_non_negative("waves.fade_in", self.fade_in)?;
        require_non_negative("waves.water_depth", self.water_depth)
    }
}

/// |a - b| (m).
pub(crate) fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}
