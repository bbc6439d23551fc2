//! Parameters of the rigid body unit (scene kind `body`), SI units, z up.
//!
//! The body's frame has its origin at the reference point (where the
//! hydrostatic restoring, the added mass, the damping and the mean load act:
//! for a floater, the centreline at the still water line) and its axes along
//! the global ones at rest. Every table is checked once by
//! [`BodyParams::validate`]; a refusal names the key.

use super::motion_table::MotionTable;
use super::waves::RaoTable;
use crate::contract::{UnitError, require_finite, require_non_negative, require_positive};
use crate::line3d::params::Waves;
use crate::signal::sine::Sine;
use serde::{Deserialize, Serialize};

/// A 6x6 matrix as rows (surge, sway, heave, roll, pitch, yaw).
pub type Matrix6Rows = [[f64; 6]; 6];

/// The rigid body's parameters.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct BodyParams {
    /// Structural mass (kg).
    pub mass: f64,
    /// Moments of inertia about the centre of gravity along the body's axes
    /// (kg m^2): Ixx, Iyy, Izz.
    pub inertia: [f64; 3],
    /// Products of inertia about the centre of gravity (kg m^2): Ixy, Ixz, Iyz.
    #[serde(default)]
    pub inertia_products: [f64; 3],
    /// The centre of gravity in the body's frame (m from the reference point).
    #[serde(default)]
    pub centre_of_gravity: [f64; 3],
    /// The reference point's position at rest, global (m).
    #[serde(default)]
    pub reference: [f64; 3],
    /// The initial displacement from rest (m, rad): surge, sway, heave, roll,
    /// pitch, yaw (a decay test's start).
    #[serde(default)]
    pub initial_offset: [f64; 6],
    /// The initial velocity of the reference point (m/s) and the angular
    /// velocity (rad/s), global axes.
    #[serde(default)]
    pub initial_velocity: [f64; 6],
    /// Displaced volume at rest (m^3): buoyancy rho g V upward at the
    /// reference point (its moments are in `hydrostatic_stiffness`, as
    /// OpenFAST's HydroDyn has them).
    #[serde(default)]
    pub displaced_volume: f64,
    /// Water density (kg/m^3).
    #[serde(default = "default_water_density")]
    pub water_density: f64,
    /// Gravity (m/s^2): the body's weight acts at its centre of gravity.
    #[serde(default = "default_gravity")]
    pub gravity: f64,
    /// Linear hydrostatic restoring about the reference point for the
    /// displacement from rest (N/m, N/rad, N m/m, N m/rad).
    #[serde(default)]
    pub hydrostatic_stiffness: Matrix6Rows,
    /// A further linear restoring (a yaw spring standing for a mooring's
    /// delta lines, a soft fender), same units.
    #[serde(default)]
    pub additional_stiffness: Matrix6Rows,
    /// Constant added mass about the reference point, global axes (kg, kg m,
    /// kg m^2).
    #[serde(default)]
    pub added_mass: Matrix6Rows,
    /// Linear damping on the reference point's velocity and the angular
    /// velocity (N s/m, N m s/rad, ...).
    #[serde(default)]
    pub damping_linear: Matrix6Rows,
    /// Quadratic damping: force = -B |u| u, the product taken per component
    /// (N s^2/m^2, N m s^2/rad^2).
    #[serde(default)]
    pub damping_quadratic: Matrix6Rows,
    /// A constant load at the reference point (N, N m), global axes: wind
    /// thrust, mean drift.
    #[serde(default)]
    pub mean_force: [f64; 6],
    /// The attachment points, each an output of its global motion and an
    /// input of the force it receives.
    #[serde(default)]
    pub fairleads: Vec<Fairlead>,
    /// Instead of the dynamics, a prescribed motion: per degree of freedom
    /// (surge, sway, heave in m; roll, pitch, yaw in rad) sines added to the
    /// initial offset.
    #[serde(default)]
    pub motion: Option<[Vec<Sine>; 6]>,
    /// Instead of the dynamics, a prescribed motion from a time table (a
    /// natural cubic spline per degree of freedom; added to `motion` and
    /// `initial_offset`); a run must stay within its times.
    #[serde(default)]
    pub motion_table: Option<MotionTable>,
    /// Seconds over which the prescribed sines grow from nothing.
    #[serde(default)]
    pub fade_in: f64,
    /// The sea (a 3D line's `waves` table: a spectrum or sines, a heading,
    /// a water depth, a fade-in), acting through `force_rao` or `motion_rao`.
    #[serde(default)]
    pub waves: Option<Waves>,
    /// First-order wave excitation: force and moment per metre of wave
    /// amplitude at the reference point.
    #[serde(default)]
    pub force_rao: Option<RaoTable>,
    /// Instead of the dynamics, the motion the waves give the body, per
    /// metre of wave amplitude (added to `motion` and `initial_offset`).
    #[serde(default)]
    pub motion_rao: Option<RaoTable>,
    /// Bound on the Newton iterations of a step.
    #[serde(default = "default_max_iterations")]
    pub max_iterations: u32,
}

/// A named attachment point.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Fairlead {
    /// Its name: the prefix of its ports (`<name>_position_x`, `<name>_force_x`).
    pub name: String,
    /// Where it is in the body's frame (m from the reference point).
    pub position: [f64; 3],
}

fn default_water_density() -> f64 {
    1025.0
}

fn default_gravity() -> f64 {
    9.80665
}

fn default_max_iterations() -> u32 {
    50
}

/// The degrees of freedom's names, in matrix order.
pub const DOFS: [&str; 6] = ["surge", "sway", "heave", "roll", "pitch", "yaw"];

impl BodyParams {
    /// Refuses what the body cannot use, naming the key.
    pub fn validate(&self) -> Result<(), UnitError> {
        require_positive("mass", self.mass)?;
        for (axis, &i) in ["x", "y", "z"].iter().zip(&self.inertia) {
            require_positive(&format!("inertia.{axis}"), i)?;
        }
        let vectors = [
            ("inertia_products", &self.inertia_products[..]),
            ("centre_of_gravity", &self.centre_of_gravity[..]),
            ("reference", &self.reference[..]),
            ("initial_offset", &self.initial_offset[..]),
            ("initial_velocity", &self.initial_velocity[..]),
            ("mean_force", &self.mean_force[..]),
        ];
        for (key, values) in vectors {
            for (i, &v) in values.iter().enumerate() {
                require_finite(&format!("{key}[{i}]"), v)?;
            }
        }
        require_non_negative("displaced_volume", self.displaced_volume)?;
        require_positive("water_density", self.water_density)?;
        require_non_negative("gravity", self.gravity)?;
        require_non_negative("fade_in", self.fade_in)?;
        self.validate_inertia()?;
        self.validate_matrices()?;
        self.validate_fairleads()?;
        if self.initial_offset[4].abs() >= 1.4 {
            return Err(UnitError::parameter(
                "initial_offset[4]",
                self.initial_offset[4],
                "a pitch below 1.4 rad (80 degrees): the roll-pitch-yaw angles the restoring acts on are singular at 90 degrees",
            ));
        }
        if self.max_iterations == 0 {
            return Err(UnitError::parameter("max_iterations", 0, "at least 1"));
        }
        self.validate_waves()?;
        if let Some(table) = &self.motion_table {
            table.validate("motion_table")?;
        }
        if let Some(motion) = &self.motion {
            for (dof, sines) in DOFS.iter().zip(motion) {
                for (i, s) in sines.iter().enumerate() {
                    s.check(&format!("motion.{dof}[{i}]"))?;
                }
            }
        }
        Ok(())
    }

    /// The inertia tensor about the centre of gravity must be positive
    /// definite (its principal moments obey the triangle inequality).
    fn validate_inertia(&self) -> Result<(), UnitError> {
        let tensor = super::dynamics::inertia_tensor(self);
        match nalgebra::Cholesky::new(tensor) {
            Some(_) => Ok(()),
            None => Err(UnitError::parameter(
                "inertia_products",
                format!("{:?}", self.inertia_products),
                "products of inertia that leave the inertia tensor positive definite",
            )),
        }
    }

    fn validate_matrices(&self) -> Result<(), UnitError> {
        let matrices = [
            ("hydrostatic_stiffness", &self.hydrostatic_stiffness),
            ("additional_stiffness", &self.additional_stiffness),
            ("added_mass", &self.added_mass),
            ("damping_linear", &self.damping_linear),
            ("damping_quadratic", &self.damping_quadratic),
        ];
        for (key, m) in matrices {
            for (i, row) in m.iter().enumerate() {
                for (j, &v) in row.iter().enumerate() {
                    require_finite(&format!("{key}[{i}][{j}]"), v)?;
                }
            }
        }
        for (i, row) in self.added_mass.iter().enumerate() {
            for (j, &v) in row.iter().enumerate() {
                if (v - self.added_mass[j][i]).abs() > 1e-9 * v.abs().max(1.0) {
                    return Err(UnitError::parameter(
                        &format!("added_mass[{i}][{j}]"),
                        v,
                        &format!(
                            "a symmetric matrix (added_mass[{j}][{i}] = {})",
                            self.added_mass[j][i]
                        ),
                    ));
                }
            }
            require_non_negative(&format!("added_mass[{i}][{i}]"), row[i])?;
        }
        Ok(())
    }

    fn validate_waves(&self) -> Result<(), UnitError> {
        let tables = [
            ("force_rao", &self.force_rao),
            ("motion_rao", &self.motion_rao),
        ];
        for (key, table) in tables {
            let Some(table) = table else { continue };
            table.validate(key)?;
            let Some(waves) = &self.waves else {
                return Err(UnitError::parameter(
                    key,
                    "given",
                    "a `waves` table (the sea it answers to)",
                ));
            };
            table.check_heading(key, waves.heading_deg)?;
        }
        if self.force_rao.is_some() && self.motion_rao.is_some() {
            return Err(UnitError::parameter(
                "force_rao",
                "given with motion_rao",
                "one of them: a motion RAO prescribes the motion, which the excitation would not move",
            ));
        }
        if let Some(waves) = &self.waves {
            waves.validate()?;
            if self.force_rao.is_none() && self.motion_rao.is_none() {
                return Err(UnitError::parameter(
                    "waves",
                    "given",
                    "a `force_rao` or a `motion_rao` through which the waves act on the body",
                ));
            }
        }
        Ok(())
    }

    fn validate_fairleads(&self) -> Result<(), UnitError> {
        for (k, f) in self.fairleads.iter().enumerate() {
            let valid = !f.name.is_empty()
                && f.name
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_');
            if !valid {
                return Err(UnitError::parameter(
                    &format!("fairleads[{k}].name"),
                    &f.name,
                    "a name of letters, digits and underscores (it prefixes the fairlead's ports)",
                ));
            }
            if self.fairleads[..k].iter().any(|g| g.name == f.name) {
                return Err(UnitError::parameter(
                    &format!("fairleads[{k}].name"),
                    &f.name,
                    "a name no other fairlead has",
                ));
            }
            for (axis, &p) in ["x", "y", "z"].iter().zip(&f.position) {
                require_finite(&format!("fairleads[{k}].position.{axis}"), p)?;
            }
        }
        Ok(())
    }
}
