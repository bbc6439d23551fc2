//! Parameters of the nonlinear section unit (scene kind `nonlinear`), SI units.
//!
//! Geometry is the stress-free shape: a start point and segments, each a straight
//! run of equal elements at an angle. The displacements the unit computes are from
//! that shape; end conditions prescribe displacements from it.

use super::element::Formulation;
use crate::beam::boundary::TimeFunction;
use crate::contact::Law;
use crate::contact::surface::Surface;
use serde::{Deserialize, Serialize};

/// A straight run of equal elements of one cross-section.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Segment {
    /// Unstretched length (m).
    pub length: f64,
    /// Direction of the stress-free segment, counter-clockwise from +x (deg:
    /// the key says so, as every angle input in degrees does).
    #[serde(default)]
    pub angle_deg: f64,
    /// Number of equal elements.
    pub elements: usize,
    /// EA (N).
    pub axial_stiffness: f64,
    /// EI (N m^2).
    pub bending_stiffness: f64,
    /// Structural mass per unit length (kg/m).
    pub mass_per_length: f64,
    /// Weight in water per unit length (N/m, positive down); 0 for no gravity.
    #[serde(default)]
    pub submerged_weight: f64,
    /// Hydrodynamic diameter (m); needed for drag and added mass.
    #[serde(default)]
    pub diameter: f64,
    /// Morison drag coefficients normal and tangential to the element.
    #[serde(default)]
    pub drag_normal: f64,
    /// Morison drag coefficient tangential to the element (on the surface pi D).
    #[serde(default)]
    pub drag_tangential: f64,
    /// Added-mass coefficients normal and tangential.
    #[serde(default)]
    pub added_mass_normal: f64,
    /// Added-mass coefficient tangential to the element.
    #[serde(default)]
    pub added_mass_tangential: f64,
}

/// How one DOF of an end is held or loaded.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum DofCondition {
    /// Nothing acts on it.
    Free,
    /// Held at its stress-free value.
    Held,
    /// Prescribed displacement from the stress-free position (m or rad); `"input"`
    /// reads it from a coupled input.
    Displacement(TimeFunction),
    /// Coupled velocity input (m/s or rad/s), integrated by the trapezoidal rule.
    Velocity,
    /// A coupled velocity input starting from this displacement (m or rad) rather
    /// than the stress-free value: a cut that starts in a static shape.
    VelocityFrom(f64),
    /// Applied force (N) or moment (N m); `"input"` reads it from a coupled input.
    Force(TimeFunction),
}

impl DofCondition {
    /// Whether the DOF's motion is prescribed.
    pub fn is_kinematic(&self) -> bool {
        matches!(
            self,
            DofCondition::Held
                | DofCondition::Displacement(_)
                | DofCondition::Velocity
                | DofCondition::VelocityFrom(_)
        )
    }
}

/// Shorthand for an end; per-DOF keys override it.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum EndKind {
    /// x, z and rotation held.
    Fixed,
    /// x and z held, rotation free.
    Pinned,
    /// Nothing held.
    #[default]
    Free,
}

/// One end of the structure.
#[derive(Clone, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct End {
    /// A shorthand for the DOFs' conditions; a DOF given below overrides it.
    #[serde(default)]
    pub kind: EndKind,
    /// Condition of the x displacement.
    pub x: Option<DofCondition>,
    /// Condition of the z displacement.
    pub z: Option<DofCondition>,
    /// Condition of the rotation.
    pub rotation: Option<DofCondition>,
}

impl End {
    /// The conditions on x, z and rotation.
    pub fn conditions(&self) -> [DofCondition; 3] {
        let base = |held: bool| {
            if held {
                DofCondition::Held
            } else {
                DofCondition::Free
            }
        };
        let (t, r) = match self.kind {
            EndKind::Fixed => (true, true),
            EndKind::Pinned => (true, false),
            EndKind::Free => (false, false),
        };
        [
            self.x.clone().unwrap_or(base(t)),
            self.z.clone().unwrap_or(base(t)),
            self.rotation.clone().unwrap_or(base(r)),
        ]
    }
}

/// Both ends: `start` at arc length 0, `end` at the far end.
#[derive(Clone, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Ends {
    /// The first node's end.
    #[serde(default)]
    pub start: End,
    /// The last node's end.
    #[serde(default)]
    pub end: End,
}

/// An interior support: the DOFs of the node at arc length `at` it holds.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Support {
    /// Arc length (m) of the node held; it must be a node of the mesh.
    pub at: f64,
    /// Hold the node's x displacement.
    #[serde(default)]
    pub x: bool,
    /// Hold its z displacement.
    #[serde(default)]
    pub z: bool,
    /// Hold its rotation.
    #[serde(default)]
    pub rotation: bool,
}

/// A distributed load (N/m, global components) over an arc-length range.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct DistributedLoad {
    /// Arc-length range (m); elements whose midpoint lies in it carry the load.
    #[serde(default)]
    pub from: f64,
    /// End of the arc-length range (m).
    #[serde(default = "infinity")]
    pub to: f64,
    /// Load along x (N/m) over time.
    #[serde(default = "zero_function")]
    pub x: TimeFunction,
    /// Load along z (N/m) over time.
    #[serde(default = "zero_function")]
    pub z: TimeFunction,
}

fn infinity() -> f64 {
    f64::INFINITY
}

fn zero_function() -> TimeFunction {
    TimeFunction::Constant(0.0)
}

/// The mass matrix.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum MassKind {
    /// Linear axial, Hermite transverse (seed 002), in each element's frame at the
    /// start of the dynamics.
    #[default]
    Consistent,
    /// Row-sum translational mass, rotary m l^3 / 78 (HRZ): for central differences.
    Lumped,
}

/// The time integrator.
#[derive(Copy, Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Integrator {
    /// HHT-alpha with Newton iterations.
    Hht {
        /// Numerical damping alpha in [0, 1/3].
        #[serde(default)]
        alpha: f64,
        /// Newton's tolerance on the largest correction relative to max(1, |q|).
        #[serde(default = "default_tolerance")]
        tolerance: f64,
        /// Most Newton iterations a step may take.
        #[serde(default = "default_iterations")]
        max_iterations: u32,
    },
    /// The trapezoidal rule (HHT with alpha = 0) with the elastic force over each
    /// step the discrete gradient of the strain energy: undamped free vibration
    /// keeps its energy to the Newton tolerance at any step, where the plain rule
    /// can pump energy into unresolved axial modes of a nonlinear structure.
    /// Newton uses the midpoint tangent, so it converges linearly; round-off in
    /// the energy difference floors its corrections near 1e-9 m, hence a looser
    /// default tolerance than HHT's.
    EnergyConserving {
        /// Newton's tolerance on the largest correction relative to max(1, |q|).
        #[serde(default = "default_discrete_gradient_tolerance")]
        tolerance: f64,
        /// Most Newton iterations a step may take.
        #[serde(default = "default_iterations")]
        max_iterations: u32,
    },
    /// Explicit central differences; the step must stay below the critical step.
    CentralDifference,
}

impl Default for Integrator {
    fn default() -> Self {
        Integrator::Hht {
            alpha: 0.0,
            tolerance: default_tolerance(),
            max_iterations: default_iterations(),
        }
    }
}

fn default_tolerance() -> f64 {
    1e-10
}

fn default_discrete_gradient_tolerance() -> f64 {
    1e-8
}

fn default_iterations() -> u32 {
    30
}

/// The start guess of the static solve.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StartShape {
    /// The stress-free shape (ends moved to their prescribed positions).
    #[default]
    Reference,
    /// The inextensible catenary through the two ends (hanging lines).
    Catenary,
    /// The polyline `start_points`, nodes spread over it by arc length (S-lay
    /// pipes on a stinger, any shape far from the stress-free one).
    Points,
}

impl StartShape {
    /// The scene's word for it.
    pub fn name(self) -> &'static str {
        match self {
            StartShape::Reference => "reference",
            StartShape::Catenary => "catenary",
            StartShape::Points => "points",
        }
    }
}

/// Contact with a surface z >= f(x, t), at the nodes.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct NodalContact {
    /// The contact law.
    pub method: Law,
    /// The surface the nodes touch.
    pub surface: Surface,
}

impl NodalContact {
    /// Whether the surface moves.
    pub fn moves(&self) -> bool {
        self.surface.motion != crate::contact::surface::Motion::None
    }
}

/// A current: horizontal velocity (m/s) as a table over z (m), linear between and
/// constant beyond its points.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Current {
    /// Heights (m), increasing.
    pub z: Vec<f64>,
    /// Current speed along +x at each height (m/s).
    pub velocity: Vec<f64>,
}

/// Parameters of the nonlinear section unit.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct NonlinearParams {
    /// How the elements' forces are computed (co-rotational by default, or seed 002's cubic).
    #[serde(default)]
    pub formulation: Formulation,
    /// Stress-free position of the start (m).
    #[serde(default)]
    pub start: [f64; 2],
    /// The stress-free geometry, from the start.
    pub segments: Vec<Segment>,
    /// How the two ends are held, loaded or coupled.
    #[serde(default)]
    pub ends: Ends,
    /// Interior supports (e.g. a frame's corner held horizontally).
    #[serde(default)]
    pub supports: Vec<Support>,
    /// Distributed loads over arc-length ranges.
    #[serde(default)]
    pub loads: Vec<DistributedLoad>,
    /// Lumped or consistent mass.
    #[serde(default)]
    pub mass: MassKind,
    /// The time integrator.
    #[serde(default)]
    pub integrator: Integrator,
    /// Rayleigh damping C = a M + b K0 (1/s, s).
    #[serde(default)]
    pub rayleigh_mass: f64,
    /// Rayleigh damping proportional to stiffness (s): C = a M + b K, this is b.
    #[serde(default)]
    pub rayleigh_stiffness: f64,
    /// Water density (kg/m^3) for drag and added mass.
    #[serde(default = "water_density")]
    pub water_density: f64,
    /// A current by height, for drag.
    #[serde(default)]
    pub current: Option<Current>,
    /// Contact with the seabed (its nodes define the touchdown point).
    pub contact: Option<NodalContact>,
    /// Contact with a stinger (rollers), not counted for touchdown.
    pub stinger: Option<NodalContact>,
    /// Start from the static equilibrium under the loads at t = 0.
    #[serde(default)]
    pub static_start: bool,
    /// Step the section linearised about its start state (see `linear`).
    #[serde(default)]
    pub linear: bool,
    /// Step the section on N modes of its tangent at the start (see `reduced`).
    pub reduced_modes: Option<usize>,
    /// With `reduced_modes`: forces through sampled elements (see `reduced`).
    pub reduced_sampling: Option<super::reduced::Sampling>,
    /// The shape the statics start from (stress-free, a catenary, or given points).
    #[serde(default)]
    pub start_shape: StartShape,
    /// The polyline (x, z in m) of `start_shape = "points"`.
    #[serde(default)]
    pub start_points: Vec<[f64; 2]>,
    /// The most sub-steps (1, 2, 4, ...) a step is divided into when Newton fails.
    #[serde(default = "default_max_substeps")]
    pub max_substeps: u32,
    /// Load increments of the static solve (halved on failure, at most 12 times).
    #[serde(default = "default_load_steps")]
    pub load_steps: u32,
    /// Arc lengths (m) where tension, moment and curvature are reported.
    #[serde(default)]
    pub stations: Vec<f64>,
}

fn water_density() -> f64 {
    1025.0
}

fn default_max_substeps() -> u32 {
    32
}

fn default_load_steps() -> u32 {
    10
}

impl NonlinearParams {
    /// Total unstretched length (m).
    pub fn length(&self) -> f64 {
        self.segments.iter().map(|s| s.length).sum()
    }

    /// The node at arc length `s` (within 1e-9 of the length), if there is one.
    pub fn node_at(&self, s: f64) -> Option<usize> {
        let (mut arc, mut node) = (0.0, 0);
        let tolerance = 1e-9 * self.length();
        for segment in &self.segments {
            let l = segment.length / segment.elements as f64;
            for _ in 0..segment.elements {
                if (arc - s).abs() <= tolerance {
                    return Some(node);
                }
                arc += l;
                node += 1;
            }
        }
        ((arc - s).abs() <= tolerance).then_some(node)
    }
}

impl Current {
    /// Horizontal current (m/s) at height z.
    pub fn at(&self, z: f64) -> f64 {
        crate::numerics::table::interpolate(&self.z, &self.velocity, z)
    }
}
