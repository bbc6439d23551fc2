//! The buffers of a section's step, kept between steps: the loads, the
//! state at the step's start, what its end changed (for a correction to take
//! that end again) and whether that end is pending (`deferred_end.rs`).

/// The buffers of one step, kept between steps.
#[derive(Default)]
pub(super) struct StepWork {
    pub(super) f0: Vec<f64>,
    pub(super) f1: Vec<f64>,
    pub(super) g0: Vec<f64>,
    /// Displacements at the step's start.
    pub(super) q0: Vec<f64>,
    /// The state at the step's start, restored before sub-stepping.
    pub(super) backup: Option<super::SectionState>,
    pub(super) held: Vec<(usize, [f64; 3])>,
    /// A linear section's drag remainder F_d(v_0) - D_0 v_0 at the step's
    /// start, and its step's loads.
    pub(super) drag_remainder: Vec<f64>,
    pub(super) linear_f0: Vec<f64>,
    pub(super) linear_f1: Vec<f64>,
    /// The outside force at the step's end (`energy::record_step`).
    pub(super) outside: Vec<f64>,
    /// What the last step's end changed, kept to take that end again at a
    /// corrected state (`correction.rs`): the energy ledger and the
    /// contacts' Lagrangian parameters before it, the bend moments at the
    /// step's start, the moving surfaces' energy jump.
    pub(super) before_end: EndOfStep,
    /// The master will correct the next step (`deferred_end.rs`).
    pub(super) defer_next: bool,
    /// The last step's end is pending: only the end reactions were taken.
    pub(super) end_pending: bool,
    /// Scratch of a pending end: the restoring force at the end nodes.
    pub(super) end_force: Vec<f64>,
}

/// The section's ledger and Lagrangian parameters before a step's end was
/// taken, the bend moments at the step's start and its surfaces' jump.
#[derive(Default)]
pub(super) struct EndOfStep {
    pub(super) ledger: super::energy::EnergyLedger,
    pub(super) lambda: Vec<f64>,
    pub(super) bend_start: [f64; 2],
    pub(super) surface_jump: f64,
}
