//! Master settings: scheme, iteration limits, acceleration and tolerances.
//!
//! These are the `[master]` table of a scene; the same types configure a master
//! built in code.

use serde::{Deserialize, Serialize};
use slender_contract::PortKind;

/// How units are stepped within a synchronisation step.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Scheme {
    /// All units step once, in parallel, with inputs predicted from step-start outputs.
    Jacobi,
    /// Units step once, in order; a unit uses the fresh outputs of those before it.
    GaussSeidel,
    /// Jacobi sweeps repeated with rollback until the interface converges.
    IterativeJacobi,
    /// Gauss-Seidel sweeps repeated with rollback until the interface converges
    /// (seed 000 Algorithm 1).
    IterativeGaussSeidel,
}

impl Scheme {
    /// Whether the scheme repeats steps (and so needs rollback).
    pub fn is_iterative(self) -> bool {
        matches!(self, Scheme::IterativeJacobi | Scheme::IterativeGaussSeidel)
    }

    /// Whether units see fresh outputs of units earlier in the order.
    pub fn is_sequential(self) -> bool {
        matches!(self, Scheme::GaussSeidel | Scheme::IterativeGaussSeidel)
    }

    /// Name as written in scene files.
    pub fn name(self) -> &'static str {
        match self {
            Scheme::Jacobi => "jacobi",
            Scheme::GaussSeidel => "gauss_seidel",
            Scheme::IterativeJacobi => "iterative_jacobi",
            Scheme::IterativeGaussSeidel => "iterative_gauss_seidel",
        }
    }
}

/// What to do when an iterative step reaches `max_iterations` unconverged.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OnMaxIterations {
    /// Stop the run with an error naming the worst connection.
    #[default]
    Error,
    /// Accept the last iterate, count the step as non-converged and go on.
    Accept,
}

/// How a fixed-point iteration updates the iterate of the coupled variables.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Acceleration {
    /// Plain fixed point: the next iterate is what the sweep returned.
    #[default]
    None,
    /// Constant under-relaxation `x <- x + factor (G(x) - x)`.
    Constant {
        /// Relaxation factor in (0, 1] (over-relaxation up to 2 allowed);
        /// 0.5 by default, as the other kinds start.
        #[serde(default = "half")]
        factor: f64,
    },
    /// Aitken dynamic relaxation; the factor restarts at `initial_factor` each step.
    Aitken {
        /// The relaxation factor of each step's first update (default 0.5).
        #[serde(default = "half")]
        initial_factor: f64,
    },
    /// Interface quasi-Newton, inverse least squares (IQN-ILS, Anderson type).
    IqnIls {
        /// Relaxation of the first iteration of a step (no history yet).
        #[serde(default = "half")]
        initial_factor: f64,
        /// Earlier steps whose secant pairs are kept (0: only the current step).
        #[serde(default)]
        reuse_steps: u32,
    },
}

/// Newton on the interface residual `G(x) - x`: not a fixed-point update, so it
/// is its own `[master] newton` key. Its Jacobian comes from whole sweeps
/// (finite differences, one extra sweep per coupled variable) or is assembled
/// from each unit's interface Jacobian through the connection graph.
#[derive(Copy, Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NewtonSettings {
    /// Relative perturbation of finite differences: delta = perturbation *
    /// max(|x|, 1) in SI units for a sweep; for a unit's input, delta =
    /// max(perturbation * |u|, 10 x the tolerance of the connection feeding it).
    #[serde(default = "default_perturbation")]
    pub perturbation: f64,
    /// `every_iteration` (default), `once_per_step` or `reuse`.
    #[serde(default)]
    pub jacobian: JacobianUpdate,
    /// Where the Jacobian comes from: `sweeps` (default) or `units`.
    #[serde(default)]
    pub derivatives: Derivatives,
    /// With `jacobian = "reuse"`: the most steps one Jacobian serves (default 100).
    #[serde(default = "default_refresh_steps")]
    pub refresh_steps: u32,
    /// With `jacobian = "reuse"`: an iteration that shrinks the residual by less
    /// than this factor evaluates the Jacobian anew (default 0.1).
    #[serde(default = "default_refresh_rate")]
    pub refresh_rate: f64,
    /// With `derivatives = "units"`: a unit repeating a step starts its own
    /// solve from its last attempt, moved by its Jacobian (default true): the
    /// repeated sweep costs a Newton iteration or two instead of a whole solve.
    #[serde(default = "yes")]
    pub warm_start: bool,
    /// With `derivatives = "units"`: a sweep not within tolerance is closed
    /// by a linear correction instead of another sweep (default false). The
    /// Newton update of the torn values moves every unit's end state by its
    /// own step derivatives (`Unit::correct_step`); the step is accepted when
    /// the residual after the correction (the units' forces at the moved
    /// state against the updated values) is within tolerance. Otherwise the
    /// step is swept again at the updated values and that sweep is corrected
    /// in turn, from the units' Jacobians of it (so only with a Jacobian
    /// evaluated at every iteration); a unit that cannot correct its step
    /// leaves every step iterated.
    #[serde(default)]
    pub one_sweep: bool,
}

impl Default for NewtonSettings {
    fn default() -> Self {
        NewtonSettings {
            perturbation: default_perturbation(),
            jacobian: JacobianUpdate::default(),
            derivatives: Derivatives::default(),
            refresh_steps: default_refresh_steps(),
            refresh_rate: default_refresh_rate(),
            warm_start: true,
            one_sweep: false,
        }
    }
}

/// Where Newton's interface Jacobian comes from.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Derivatives {
    /// Finite differences of whole sweeps from the rolled-back step start: one
    /// sweep per torn value.
    #[default]
    Sweeps,
    /// Each unit's interface Jacobian (`Unit::step_jacobian`, or finite
    /// differences of that unit alone from its rolled-back start: one step per
    /// coupled input), chained through the connections in the sweep order.
    Units,
}

/// How the coupled values of an iterative step are solved: a fixed-point
/// iteration with an acceleration, or Newton.
#[derive(Clone, Debug, PartialEq)]
pub enum Solver {
    /// A fixed-point iteration with its acceleration.
    FixedPoint(Acceleration),
    /// Newton on the interface with the units' Jacobians.
    Newton(NewtonSettings),
}

impl From<Acceleration> for Solver {
    fn from(a: Acceleration) -> Solver {
        Solver::FixedPoint(a)
    }
}

impl From<NewtonSettings> for Solver {
    fn from(n: NewtonSettings) -> Solver {
        Solver::Newton(n)
    }
}

/// When Newton re-evaluates the interface Jacobian.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum JacobianUpdate {
    /// A new Jacobian at every iteration (Newton's method proper).
    #[default]
    EveryIteration,
    /// One Jacobian per step, at its first iterate.
    OncePerStep,
    /// One Jacobian kept across steps, evaluated anew when an iteration
    /// converges slowly (`refresh_rate`) or after `refresh_steps` steps: the
    /// interface of a structure changes little from step to step.
    Reuse,
}

fn half() -> f64 {
    0.5
}

fn default_perturbation() -> f64 {
    1e-7
}

fn yes() -> bool {
    true
}

fn default_refresh_steps() -> u32 {
    100
}

fn default_refresh_rate() -> f64 {
    0.1
}

impl Acceleration {
    /// Name as written in scene files.
    pub fn name(&self) -> &'static str {
        match self {
            Acceleration::None => "none",
            Acceleration::Constant { .. } => "constant",
            Acceleration::Aitken { .. } => "aitken",
            Acceleration::IqnIls { .. } => "iqn_ils",
        }
    }
}

/// Absolute convergence tolerance per port kind, in the kind's SI unit. A
/// connection uses the tolerance of its destination port's kind unless it
/// overrides it.
#[derive(Copy, Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Tolerances {
    /// N (seed 000: 0.1 N).
    pub force: f64,
    /// m/s (seed 000: 1e-6 m/s).
    pub velocity: f64,
    /// m.
    pub displacement: f64,
    /// rad.
    pub rotation: f64,
    /// N m.
    pub moment: f64,
    /// Any other quantity (a port without a unit of measure): the floor of
    /// its relative tolerance, or its tolerance when `generic_relative` is 0.
    pub generic: f64,
    /// A port without a unit of measure converges within this fraction of the
    /// largest value its connection has carried (at least `generic`): no
    /// absolute number suits both a 1.9 MN force and a 1e-3 signal.
    pub generic_relative: f64,
}

impl Default for Tolerances {
    fn default() -> Self {
        Tolerances {
            force: 0.1,
            velocity: 1e-6,
            displacement: 1e-9,
            rotation: 1e-9,
            moment: 0.1,
            generic: 1e-9,
            generic_relative: 1e-9,
        }
    }
}

impl Tolerances {
    /// The tolerance for ports of `kind`.
    pub fn of(&self, kind: PortKind) -> f64 {
        match kind {
            PortKind::Force => self.force,
            PortKind::Velocity => self.velocity,
            PortKind::Displacement => self.displacement,
            PortKind::Rotation => self.rotation,
            PortKind::Moment => self.moment,
            PortKind::Generic => self.generic,
        }
    }
}

/// How the coupled values at the end of a step are predicted from accepted values
/// (used by non-iterative schemes, and as the first iterate of iterative ones).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Extrapolation {
    /// The value at the start of the step.
    #[default]
    Constant,
    /// Linear through the values at the start of this step and of the previous one.
    Linear,
    /// Quadratic through the values at the start of this step and of the two
    /// before (error third order in the step where the values are smooth: a
    /// first iterate close enough that an iterative scheme may accept it).
    Quadratic,
}

/// A master setting out of range (the key and what was expected).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct SettingsError(
    /// The setting and what was expected.
    pub String,
);

/// Everything that configures the master.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MasterSettings {
    /// The synchronisation scheme.
    pub scheme: Scheme,
    /// Order of the units for Gauss-Seidel schemes, by name; empty: derived from the
    /// connection graph (upstream first, scene order among equals).
    #[serde(default)]
    pub order: Vec<String>,
    /// Iterations allowed per step for iterative schemes (default 50).
    #[serde(default = "default_max_iterations")]
    pub max_iterations: u32,
    /// What a step that reaches `max_iterations` does.
    #[serde(default)]
    pub on_max_iterations: OnMaxIterations,
    /// Update of a fixed-point iteration (iterative schemes).
    #[serde(default)]
    pub acceleration: Acceleration,
    /// Newton instead of a fixed-point iteration (iterative schemes).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub newton: Option<NewtonSettings>,
    /// When the coupled values of an iterative step have converged.
    #[serde(default)]
    pub tolerances: Tolerances,
    /// The first iterate of a step from the accepted values before it.
    #[serde(default)]
    pub extrapolation: Extrapolation,
    /// Threads that step the units of a Jacobi sweep side by side (default 1:
    /// one after another). Results are bit-identical for any count: each unit
    /// steps as it would alone.
    #[serde(default = "one_thread")]
    pub threads: u32,
    /// The largest relative change over the first step of a load a unit's
    /// statics were solved under (default 0.2); beyond it the run stops as
    /// started off its equilibrium (see the master's start check).
    #[serde(default = "default_start_tolerance")]
    pub start_tolerance: f64,
    /// The coupling step chosen by the master within each synchronisation
    /// step from an error estimate (`[master.adaptive]`); absent: every step
    /// is the synchronisation step.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub adaptive: Option<AdaptiveStep>,
}

/// An adaptive coupling step (`[master.adaptive]`). The synchronisation step
/// (the scene's `step`, at which outputs are recorded) is the largest step;
/// the master steps at it divided by 1, 2, 4, ... down to `min_step`,
/// halving a step whose interface error estimate exceeds `tolerance` or whose
/// iteration fails, and doubling again after `calm_steps` steps well within it
/// (see `coupler::adaptive`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AdaptiveStep {
    /// The local error allowed per step: each connection's value against its
    /// quadratic extrapolation from the three accepted values before it,
    /// relative to the largest value the connection has carried (default 1e-3).
    #[serde(default = "default_adaptive_tolerance")]
    pub tolerance: f64,
    /// The smallest step (s): the synchronisation step halved as often as it
    /// stays at least this long.
    pub min_step: f64,
    /// Accepted steps in a row with an estimate below a sixteenth of the
    /// tolerance (so that twice the step should pass) before the step doubles
    /// (default 4).
    #[serde(default = "default_calm_steps")]
    pub calm_steps: u32,
    /// The port kinds whose connections the estimate judges (default: all).
    /// A cut of a beam carries moments and angular velocities with content
    /// near the step's own frequency that no step resolves; judging its
    /// forces (`["force"]`) follows the loads.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub kinds: Vec<PortKind>,
    /// Whether the connections' estimate is judged at all (default true;
    /// false: only the units' own, `displacement`).
    #[serde(default = "yes")]
    pub interface: bool,
    /// The local displacement error allowed per step in each unit's own
    /// estimate (m; `Unit::local_error`, the sections' and lines' HHT-alpha
    /// steps); absent: the units' estimates are not judged.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub displacement: Option<f64>,
}

fn default_adaptive_tolerance() -> f64 {
    1e-3
}

fn default_calm_steps() -> u32 {
    4
}

fn default_start_tolerance() -> f64 {
    0.2
}

fn default_max_iterations() -> u32 {
    50
}

fn one_thread() -> u32 {
    1
}

impl MasterSettings {
    /// Settings for `scheme` with every other field at its default.
    pub fn new(scheme: Scheme) -> MasterSettings {
        MasterSettings {
            scheme,
            order: Vec::new(),
            max_iterations: default_max_iterations(),
            on_max_iterations: OnMaxIterations::default(),
            acceleration: Acceleration::default(),
            newton: None,
            tolerances: Tolerances::default(),
            extrapolation: Extrapolation::default(),
            threads: one_thread(),
            start_tolerance: default_start_tolerance(),
            adaptive: None,
        }
    }

    /// Chooses how iterative steps are solved.
    pub fn set_solver(&mut self, solver: impl Into<Solver>) {
        match solver.into() {
            Solver::FixedPoint(a) => {
                self.acceleration = a;
                self.newton = None;
            }
            Solver::Newton(n) => {
                self.acceleration = Acceleration::None;
                self.newton = Some(n);
            }
        }
    }

    /// Tolerances: each port kind's finite and > 0, the relative one a
    /// fraction, the start check's > 0.
    fn check_tolerances(&self) -> Result<(), SettingsError> {
        let start = self.start_tolerance;
        if start.is_nan() || start <= 0.0 {
            return Err(SettingsError(format!(
                "start_tolerance {start}: expected a value > 0 (inf turns the start check off)"
            )));
        }
        for kind in PortKind::ALL {
            let tol = self.tolerances.of(kind);
            if !(tol.is_finite() && tol > 0.0) {
                return Err(SettingsError(format!(
                    "tolerances.{}: {tol} is not a finite value > 0",
                    kind.name()
                )));
            }
        }
        let relative = self.tolerances.generic_relative;
        if !(0.0..1.0).contains(&relative) {
            return Err(SettingsError(format!(
                "tolerances.generic_relative: {relative} is not a fraction in [0, 1) (0: ports without a unit take the absolute tolerances.generic)"
            )));
        }
        Ok(())
    }

    /// An acceleration's relaxation factor in (0, 2].
    fn check_acceleration(&self) -> Result<(), SettingsError> {
        let factor_ok = |f: f64| f.is_finite() && f > 0.0 && f <= 2.0;
        match self.acceleration {
            Acceleration::None => {}
            Acceleration::Constant { factor }
            | Acceleration::Aitken {
                initial_factor: factor,
            }
            | Acceleration::IqnIls {
                initial_factor: factor,
                ..
            } => {
                if !factor_ok(factor) {
                    return Err(SettingsError(format!(
                        "acceleration factor {factor}: expected a value in (0, 2]"
                    )));
                }
            }
        }
        Ok(())
    }

    /// Checks values that serde cannot: positive tolerances, an iteration cap of at
    /// least 1, sensible acceleration factors, acceleration only with iteration.
    pub fn validate(&self) -> Result<(), SettingsError> {
        let invalid = |m: String| SettingsError(m);
        if self.max_iterations == 0 {
            return Err(invalid("max_iterations: expected at least 1".into()));
        }
        if !(1..=256).contains(&self.threads) {
            return Err(invalid(format!(
                "threads {}: expected 1 to 256",
                self.threads
            )));
        }
        self.check_tolerances()?;
        if !self.scheme.is_iterative() && self.acceleration != Acceleration::None {
            return Err(invalid(format!(
                "acceleration `{}` needs an iterative scheme, but scheme is `{}`",
                self.acceleration.name(),
                self.scheme.name()
            )));
        }
        if let Some(newton) = self.newton {
            if !self.scheme.is_iterative() {
                return Err(invalid(format!(
                    "newton needs an iterative scheme, but scheme is `{}`",
                    self.scheme.name()
                )));
            }
            if self.acceleration != Acceleration::None {
                return Err(invalid(format!(
                    "newton replaces the fixed-point iteration: remove acceleration `{}`",
                    self.acceleration.name()
                )));
            }
            let p = newton.perturbation;
            if !(p.is_finite() && p > 0.0 && p < 1.0) {
                return Err(invalid(format!(
                    "newton.perturbation {p}: expected a value in (0, 1)"
                )));
            }
            if newton.refresh_steps == 0 {
                return Err(invalid(
                    "newton.refresh_steps 0: expected at least 1".into(),
                ));
            }
            let r = newton.refresh_rate;
            if !(r.is_finite() && r > 0.0 && r < 1.0) {
                return Err(invalid(format!(
                    "newton.refresh_rate {r}: expected a value in (0, 1)"
                )));
            }
            if newton.one_sweep
                && (newton.derivatives != Derivatives::Units
                    || newton.jacobian == JacobianUpdate::Reuse)
            {
                return Err(invalid(
                    "newton.one_sweep = true: expected derivatives = \"units\" and a Jacobian of each step (jacobian = \"every_iteration\" or \"once_per_step\"): the correction moves the units by the derivatives of the step they took".into(),
                ));
            }
        }
        if let Some(adaptive) = &self.adaptive {
            adaptive.validate()?;
        }
        self.check_acceleration()?;
        Ok(())
    }
}

impl AdaptiveStep {
    /// A tolerance in (0, 1), a finite `min_step` > 0, at least one calm step.
    fn validate(&self) -> Result<(), SettingsError> {
        let tol = self.tolerance;
        if !(tol.is_finite() && tol > 0.0 && tol < 1.0) {
            return Err(SettingsError(format!(
                "adaptive.tolerance {tol}: expected a relative error in (0, 1)"
            )));
        }
        let min = self.min_step;
        if !(min.is_finite() && min > 0.0) {
            return Err(SettingsError(format!(
                "adaptive.min_step {min}: expected a step > 0 in seconds"
            )));
        }
        if self.calm_steps == 0 {
            return Err(SettingsError(
                "adaptive.calm_steps 0: expected at least 1".into(),
            ));
        }
        if let Some(d) = self.displacement
            && !(d.is_finite() && d > 0.0)
        {
            return Err(SettingsError(format!(
                "adaptive.displacement {d}: expected a local displacement error > 0 in metres"
            )));
        }
        if !self.interface && self.displacement.is_none() {
            return Err(SettingsError(
                "adaptive.interface = false: expected adaptive.displacement (m) then, or nothing would judge the step".into(),
            ));
        }
        Ok(())
    }
}
