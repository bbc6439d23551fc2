//! Errors of the master, and the "did you mean" helper shared by messages.

use slender_contract::UnitError;
use thiserror::Error;

/// Why building or running a coupled simulation failed.
#[derive(Debug, Error)]
pub enum MasterError {
    /// The system or the call order is inconsistent.
    #[error("{0}")]
    Invalid(String),
    /// A master setting is out of range.
    #[error(transparent)]
    Settings(#[from] crate::settings::SettingsError),
    /// An iterative scheme needs a unit that cannot roll back.
    #[error(
        "{scheme} repeats steps, but unit `{unit}` cannot roll back: use `jacobi` or `gauss_seidel` with a fixed step, or a unit with rollback"
    )]
    RollbackUnsupported {
        /// The unit that cannot roll back.
        unit: String,
        /// What repeats steps: the scheme asked for, or the adaptive step.
        scheme: String,
    },
    /// A unit call returned an error.
    #[error("unit `{unit}`: {call} failed at t = {time} s (iteration {iteration}): {source}")]
    Unit {
        /// The unit's name.
        unit: String,
        /// The call that failed (`do_step`, `initialize`, ...).
        call: &'static str,
        /// The time of the step (s).
        time: f64,
        /// The iteration of the step.
        iteration: u32,
        /// What the unit said.
        #[source]
        source: UnitError,
    },
    /// A unit produced NaN or infinity.
    #[error(
        "unit `{unit}` produced {value} on output `{port}` at t = {time} s (iteration {iteration})"
    )]
    NonFinite {
        /// The unit's name.
        unit: String,
        /// The output.
        port: String,
        /// The value (NaN or an infinity).
        value: f64,
        /// The time of the step (s).
        time: f64,
        /// The iteration of the step.
        iteration: u32,
    },
    /// An iterative step reached its iteration cap with `on_max_iterations = "error"`.
    #[error(
        "the coupled values at t = {time} s did not converge in {iterations} iterations: connection `{connection}` still changes by {change:.3e} (tolerance {tolerance:.3e}, set by {key})"
    )]
    NotConverged {
        /// The time of the step (s).
        time: f64,
        /// The iterations made.
        iterations: u32,
        /// The connection that changed most, "unit.port -> unit.port".
        connection: String,
        /// Its last change (unit of its input).
        change: f64,
        /// Its tolerance (unit of its input).
        tolerance: f64,
        /// The scene key the tolerance comes from.
        key: String,
    },
    /// A unit solved its statics under a coupled load that the other side
    /// left in the first step by more than `start_tolerance`.
    #[error(
        "the start is off equilibrium: `{to}` solved its statics under {used:.6e} from `{from}`, which reported {after:.6e} after the first step ({percent:.1} % change, start_tolerance {tolerance}); fade the end motion in (`fade_in`), start from a consistent state, or raise [master] start_tolerance"
    )]
    StartOffEquilibrium {
        /// The output that feeds the load, "unit.port".
        from: String,
        /// The loaded input, "unit.port".
        to: String,
        /// The load the statics were solved under.
        used: f64,
        /// What the output reported after the first step.
        after: f64,
        /// The change, in per cent of the load.
        percent: f64,
        /// `[master] start_tolerance` (relative).
        tolerance: f64,
    },
    /// Newton's interface Jacobian could not be inverted.
    #[error("newton: the interface Jacobian is singular at t = {time} s (iteration {iteration})")]
    SingularJacobian {
        /// The time of the step (s).
        time: f64,
        /// The iteration of the step.
        iteration: u32,
    },
}

pub use slender_contract::names::did_you_mean;
