//! Parameters of the cable unit (scene kind `cable`), its switchable effects and the
//! section of the line it models.

use super::current::CurrentProfile;
use crate::contract::{
    UnitError, require_finite, require_in_range, require_non_negative, require_positive,
};
use serde::{Deserialize, Serialize};

/// Properties of the whole line and of the water (SI units).
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CableParams {
    /// Unstretched length of the whole line (m).
    pub length: f64,
    /// Bar elements over the whole line (a section keeps its share).
    pub elements: usize,
    /// Hydrodynamic diameter (m), for drag, added mass and, with the Young's
    /// modulus, the axial stiffness EA = E pi D^2 / 4.
    pub diameter: f64,
    /// Structural mass per unit length (kg/m).
    pub mass_per_length: f64,
    /// Young's modulus (Pa).
    pub youngs_modulus: f64,
    /// Submerged weight per unit length (N/m); used with the `weight` effect.
    #[serde(default)]
    pub submerged_weight: f64,
    /// Added-mass coefficient normal to the line (`added_mass` effect).
    #[serde(default)]
    pub added_mass_normal: f64,
    /// Added-mass coefficient along the line.
    #[serde(default)]
    pub added_mass_tangential: f64,
    /// Drag coefficient normal to the line (`drag` effect), on the diameter.
    #[serde(default)]
    pub drag_normal: f64,
    /// Drag coefficient along the line, on the circumference pi D.
    #[serde(default)]
    pub drag_tangential: f64,
    /// Rayleigh damping C = rayleigh_mass M + rayleigh_stiffness K
    /// (`structural_damping` effect): alpha1 (1/s).
    #[serde(default)]
    pub rayleigh_mass: f64,
    /// alpha2 (s).
    #[serde(default)]
    pub rayleigh_stiffness: f64,
    /// Sea water density (kg/m^3), default 1025.
    #[serde(default = "seawater")]
    pub water_density: f64,
    /// Water depth (m): the seabed is z = 0, the free surface z = water_depth.
    pub water_depth: f64,
    /// Current along +x (`current` effect).
    #[serde(default)]
    pub current: CurrentProfile,
    /// Anchor position [x, z] (m), default [0, 0].
    #[serde(default)]
    pub anchor: [f64; 2],
    /// Static top force [fx, fz] (N) of the whole line, used to find where a section
    /// ends; a `full` line takes its static top force from its inputs instead.
    #[serde(default)]
    pub static_top_force: Option<[f64; 2]>,
    /// Which part of the line this unit models.
    #[serde(default)]
    pub section: Section,
    /// Newton tolerance of the static equilibrium, relative to the top force.
    #[serde(default = "static_tolerance")]
    pub static_tolerance: f64,
    /// Tolerance on the velocity change of the drag iterations inside a step (m/s),
    /// default 1e-9: three decades below seed 000's coupling tolerance.
    #[serde(default = "drag_tolerance")]
    pub drag_tolerance: f64,
}

fn seawater() -> f64 {
    1025.0
}

/// The static solve's default tolerance (`static_tolerance`).
pub const DEFAULT_STATIC_TOLERANCE: f64 = 1e-10;

/// The drag iterations' default tolerance (`drag_tolerance`).
pub const DEFAULT_DRAG_TOLERANCE: f64 = 1e-9;

fn static_tolerance() -> f64 {
    DEFAULT_STATIC_TOLERANCE
}

fn drag_tolerance() -> f64 {
    DEFAULT_DRAG_TOLERANCE
}

/// The part of the line a unit models, split at the node nearest to the height
/// `truncation_ratio * water_depth` above the seabed.
#[derive(Copy, Clone, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(tag = "part", rename_all = "snake_case", deny_unknown_fields)]
pub enum Section {
    /// The whole line, anchor to top.
    #[default]
    Full,
    /// From the anchor to the truncation point (the numerical substructure).
    Lower {
        /// Where the cut is, as a fraction of the line's length from the anchor, in (0, 1).
        truncation_ratio: f64,
    },
    /// From the truncation point to the top (the physical substructure).
    Upper {
        /// Where the cut is, as a fraction of the line's length from the anchor, in (0, 1).
        truncation_ratio: f64,
    },
}

/// The physical effects a scene can switch on; none is computed when off.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub struct Effects {
    /// Submerged weight (static load).
    pub weight: bool,
    /// Added mass of the surrounding water.
    pub added_mass: bool,
    /// Morison drag on the velocity relative to the water.
    pub drag: bool,
    /// Current profile (needs `drag` to act).
    pub current: bool,
    /// Geometric (tension) stiffness in the dynamics; the static solution always
    /// has it, a cable has no transverse stiffness otherwise.
    pub geometric_stiffness: bool,
    /// Rayleigh structural damping.
    pub structural_damping: bool,
}

impl Effects {
    /// Names as written in scenes.
    pub const NAMES: [&'static str; 6] = [
        "weight",
        "added_mass",
        "drag",
        "current",
        "geometric_stiffness",
        "structural_damping",
    ];

    /// From scene names; unknown names are an error.
    pub fn from_names(names: &[String]) -> Result<Effects, UnitError> {
        let mut e = Effects::default();
        for n in names {
            match n.as_str() {
                "weight" => e.weight = true,
                "added_mass" => e.added_mass = true,
                "drag" => e.drag = true,
                "current" => e.current = true,
                "geometric_stiffness" => e.geometric_stiffness = true,
                "structural_damping" => e.structural_damping = true,
                other => {
                    return Err(UnitError::parameter(
                        "effects",
                        other,
                        "expected weight, added_mass, drag, current, geometric_stiffness or structural_damping",
                    ));
                }
            }
        }
        if e.current && !e.drag {
            return Err(UnitError::parameter(
                "effects",
                "current",
                "the current acts through drag: add the `drag` effect",
            ));
        }
        Ok(e)
    }

    /// Every effect on.
    pub fn all() -> Effects {
        Effects {
            weight: true,
            added_mass: true,
            drag: true,
            current: true,
            geometric_stiffness: true,
            structural_damping: true,
        }
    }
}

impl CableParams {
    /// The taut polyester line of seed 000 (Table 1) with `elements` elements: 1934 m
    /// in 1200 m of water, shear current 0 -> 0.5 m/s, as a full line anchored at
    /// the origin. Rho = 1025 kg/m^3 (not printed; it reproduces Table 3).
    pub fn seed000_polyester(elements: usize) -> CableParams {
        CableParams {
            length: 1934.0,
            elements,
            diameter: 0.264,
            mass_per_length: 44.7,
            youngs_modulus: 8.513e9,
            submerged_weight: 93.2,
            added_mass_normal: 1.0,
            added_mass_tangential: 0.0,
            drag_normal: 1.6,
            drag_tangential: 0.0,
            rayleigh_mass: 0.0,
            rayleigh_stiffness: 4.77e-2,
            water_density: 1025.0,
            water_depth: 1200.0,
            current: CurrentProfile::Linear {
                seabed: 0.0,
                surface: 0.5,
            },
            anchor: [0.0, 0.0],
            static_top_force: None,
            section: Section::Full,
            static_tolerance: static_tolerance(),
            drag_tolerance: drag_tolerance(),
        }
    }

    /// Axial stiffness EA (N).
    pub fn axial_stiffness(&self) -> f64 {
        self.youngs_modulus * std::f64::consts::PI * self.diameter * self.diameter / 4.0
    }

    /// Checks every parameter, naming the first bad one.
    pub fn validate(&self) -> Result<(), UnitError> {
        require_in_range("length", self.length, 1e-2, 1e5, "m")?;
        if self.elements < 2 {
            return Err(UnitError::parameter(
                "elements",
                self.elements,
                "expected at least 2",
            ));
        }
        if self.elements > 100_000 {
            return Err(UnitError::parameter(
                "elements",
                self.elements,
                "expected at most 100000",
            ));
        }
        require_in_range("diameter", self.diameter, 1e-4, 1e2, "m")?;
        require_in_range("mass_per_length", self.mass_per_length, 1e-3, 1e7, "kg/m")?;
        require_in_range("youngs_modulus", self.youngs_modulus, 1e3, 1e13, "Pa")?;
        require_in_range("submerged_weight", self.submerged_weight, 0.0, 1e8, "N/m")?;
        require_non_negative("added_mass_normal", self.added_mass_normal)?;
        require_non_negative("added_mass_tangential", self.added_mass_tangential)?;
        require_non_negative("drag_normal", self.drag_normal)?;
        require_non_negative("drag_tangential", self.drag_tangential)?;
        require_non_negative("rayleigh_mass", self.rayleigh_mass)?;
        require_non_negative("rayleigh_stiffness", self.rayleigh_stiffness)?;
        require_positive("water_density", self.water_density)?;
        require_positive("water_depth", self.water_depth)?;
        require_positive("static_tolerance", self.static_tolerance)?;
        require_positive("drag_tolerance", self.drag_tolerance)?;
        require_finite("anchor[0]", self.anchor[0])?;
        require_finite("anchor[1]", self.anchor[1])?;
        if let Some(f) = self.static_top_force {
            require_finite("static_top_force[0]", f[0])?;
            require_finite("static_top_force[1]", f[1])?;
        }
        self.current.validate()?;
        match self.section {
            Section::Full => {}
            Section::Lower { truncation_ratio } | Section::Upper { truncation_ratio } => {
                if !(truncation_ratio > 0.0 && truncation_ratio < 1.0) {
                    return Err(UnitError::parameter(
                        "section.truncation_ratio",
                        truncation_ratio,
                        "expected a value in (0, 1): the share of the water column held by the lower part",
                    ));
                }
                if self.static_top_force.is_none() {
                    return Err(UnitError::parameter(
                        "static_top_force",
                        "missing",
                        "a lower or upper section needs the whole line's static top force [fx, fz] to find the truncation point",
                    ));
                }
            }
        }
        Ok(())
    }
}
