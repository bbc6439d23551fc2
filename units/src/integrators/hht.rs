//! HHT-alpha time integration (alpha in [0, 1/3], beta = (1 + alpha)^2 / 4,
//! gamma = 1/2 + alpha; seed 004 eqs. 4.29-4.37) with Newton iterations, for any
//! [`SecondOrderSystem`] `M a + C v + K q + g(q, v, t) = f(t)` on banded symmetric
//! matrices with some DOFs prescribed.
//!
//! The residual at the step's end is
//! `M a1 + (1 - alpha) (C v1 + K q1 + g1) + alpha (C v0 + K q0 + g0) - (1 - alpha) f1 - alpha f0`,
//! with a1, v1 from q1 by Newmark. Without `g` the Newton matrix
//! `M / (beta h^2) + (1 - alpha) (gamma / (beta h) C + K)` is constant: it is
//! factorised once per step size and one correction solves the step exactly. With
//! `g` the system adds its tangent at every iteration and the matrix is
//! refactorised in place. A step allocates nothing once its buffers are sized.

use crate::contract::UnitError;
use crate::numerics::banded::{BandLdlt, SymmetricBand};

/// The constant matrices of a second-order system.
pub struct Matrices<'a> {
    /// Mass matrix M.
    pub mass: &'a SymmetricBand,
    /// `None` when the system has no damping (its products are skipped).
    pub damping: Option<&'a SymmetricBand>,
    /// `None` when the whole restoring force is the nonlinear force (a
    /// geometrically nonlinear structure): no products with a zero matrix.
    pub stiffness: Option<&'a SymmetricBand>,
    /// Whether the matrices change from step to step (a linear section's
    /// drag linearised at each step's start in its damping): a linear step
    /// then forms and factorises its matrix at every step, in place.
    pub varies: bool,
}

/// How the nonlinear force's derivatives enter the Newton matrix: the tangent
/// stiffness times `stiffness`, the tangent damping times `damping`.
#[derive(Copy, Clone, Debug)]
pub struct TangentScales {
    /// Weight of the stiffness tangent.
    pub stiffness: f64,
    /// Weight of the damping tangent.
    pub damping: f64,
}

impl TangentScales {
    /// The band and scales of a `nonlinear_force` call: without a tangent the
    /// force enters unweighted (stiffness scale 1) and nothing is assembled.
    pub fn split(
        tangent: Option<(&mut SymmetricBand, TangentScales)>,
    ) -> (Option<&mut SymmetricBand>, TangentScales) {
        match tangent {
            Some((band, scales)) => (Some(band), scales),
            None => (
                None,
                TangentScales {
                    stiffness: 1.0,
                    damping: 0.0,
                },
            ),
        }
    }
}

/// `SecondOrderSystem::motion` and `motion_mut` over the fields `q`, `v`
/// and `a` of `self.PATH` (`motion_fields!(state)`) or of `self`
/// (`motion_fields!()`): the accessors every system with its motion in
/// three vectors would otherwise write again.
macro_rules! motion_fields {
    ($($field:ident).*) => {
        fn motion(&self) -> [&[f64]; 3] {
            let s = &(*self)$(.$field)*;
            [&s.q[..], &s.v[..], &s.a[..]]
        }

        fn motion_mut(&mut self) -> [&mut [f64]; 3] {
            let s = &mut (*self)$(.$field)*;
            [&mut s.q[..], &mut s.v[..], &mut s.a[..]]
        }
    };
}
pub(crate) use motion_fields;

/// A system `M a + C v + K q + g(q, v, t) = f(t)` as an integrator steps it.
pub trait SecondOrderSystem {
    /// Name for messages, e.g. "beam".
    fn label(&self) -> &str;

    /// M, C and K.
    fn matrices(&self) -> Matrices<'_>;

    /// Displacements, velocities and accelerations at the step's start.
    fn motion(&self) -> [&[f64]; 3];

    /// The same, to be overwritten (`set_motion`).
    fn motion_mut(&mut self) -> [&mut [f64]; 3];

    /// Accepts the step's end state.
    fn set_motion(&mut self, q: &[f64], v: &[f64], a: &[f64]) {
        let [mq, mv, ma] = self.motion_mut();
        mq.copy_from_slice(q);
        mv.copy_from_slice(v);
        ma.copy_from_slice(a);
    }

    /// Whether `g` is absent (a linear step).
    fn is_linear(&self) -> bool;

    /// The nonlinear force at the iterate (q1 = `q`, v1 = `v`, time `t`), weighted
    /// as it enters the residual (`tangent`'s stiffness scale, `1 - alpha` under
    /// HHT-alpha; 1 without a tangent), into `force` (sized by the system). With
    /// `tangent`, adds the force's tangent scaled by its scales to the matrix
    /// (Newton); without, the integrator iterates on a fixed matrix.
    fn nonlinear_force(
        &mut self,
        q: &[f64],
        v: &[f64],
        t: f64,
        tangent: Option<(&mut SymmetricBand, TangentScales)>,
        force: &mut Vec<f64>,
    );

    /// Whether the tangent the last `nonlinear_force` added is the system's
    /// frozen one (a function of the tangent scales alone, as a reduced
    /// section's at its start): the integrator then reuses its factor of the
    /// same step size instead of refactorising.
    fn tangent_is_frozen(&self) -> bool {
        false
    }

    /// Called after each Newton correction with the new iterate (e.g. Lagrangian
    /// updates of a contact law).
    fn after_iteration(&mut self, q: &[f64], t: f64) {
        let _ = (q, t);
    }

    /// May scale a Newton correction `dq` down (a damped step, e.g. to keep a
    /// rotation from jumping by turns where the tangent is nearly singular);
    /// returns the factor applied (1 leaves it unchanged).
    fn limit_correction(&self, dq: &mut [f64]) -> f64 {
        let _ = dq;
        1.0
    }
}

/// What one step needs besides the system.
pub struct StepLoads<'a> {
    /// Start and end time (s) and the exact step length (s).
    pub t0: f64,
    /// End time of the step (s).
    pub t1: f64,
    /// Exact step length (s).
    pub h: f64,
    /// External loads at the step's start and end.
    pub f0: &'a [f64],
    /// External load at the step's end.
    pub f1: &'a [f64],
    /// The nonlinear force at the step's start, as it enters the constant part
    /// (times alpha); `None` when it does not (energy-conserving contact).
    pub g0: Option<&'a [f64]>,
    /// Prescribed DOFs at the step's end: (DOF, [q, v, a]).
    pub held: &'a [(usize, [f64; 3])],
}

/// Newton's stopping rule.
#[derive(Copy, Clone, Debug)]
pub struct NewtonSettings {
    /// Largest correction relative to max(1, |q|) below which a step has converged.
    pub tolerance: f64,
    /// Most Newton iterations a step may take before it fails.
    pub max_iterations: u32,
}

/// The integrator: its parameters, the linear Newton matrix (factorised per step
/// size) and the step's buffers.
pub struct HhtAlpha {
    alpha: f64,
    linear: SymmetricBand,
    linear_h: f64,
    /// `linear` with the held DOFs as identity rows, factorised (linear steps).
    linear_factor: Option<BandLdlt>,
    jacobian: SymmetricBand,
    /// Factor of the Newton matrix with the tangent, refactorised in place.
    factor: Option<BandLdlt>,
    /// The step size `factor` was formed for with a frozen tangent (NaN when
    /// its tangent was not the frozen one).
    frozen_h: f64,
    q0: Vec<f64>,
    v0: Vec<f64>,
    a0: Vec<f64>,
    constant: Vec<f64>,
    y: Vec<f64>,
    v1: Vec<f64>,
    a1: Vec<f64>,
    residual: Vec<f64>,
    force: Vec<f64>,
    history: Vec<f64>,
    /// A first iterate for the next step only (`guess_next`).
    guess: Vec<f64>,
    /// The last Newton matrix before the held DOFs' identity rows, kept on
    /// request (`keep_newton_matrix`) for an interface Jacobian.
    kept: Option<SymmetricBand>,
    /// Whether the last step was linear (its matrix `linear`, its factor
    /// `linear_factor`).
    last_linear: bool,
    /// Newton starts a step without a guess from the motion carried on
    /// (`predict_start`), not from the start state.
    predicts: bool,
    /// The size of the last step (s).
    last_h: f64,
}

impl Default for HhtAlpha {
    /// An empty integrator (no DOFs), e.g. as a placeholder while stepping.
    fn default() -> Self {
        HhtAlpha::new(0.0, 0, 0)
    }
}

/// HHT-alpha's (alpha, beta, gamma) for numerical damping `alpha`: Newmark's
/// beta = (1 + alpha)^2 / 4 and gamma = 1/2 + alpha.
pub fn parameters_of(alpha: f64) -> (f64, f64, f64) {
    (alpha, 0.25 * (1.0 + alpha).powi(2), 0.5 + alpha)
}

impl HhtAlpha {
    /// HHT-alpha with numerical damping `alpha` (0: the trapezoidal rule) for `n`
    /// DOFs whose matrices have half-bandwidth `w`.
    pub fn new(alpha: f64, n: usize, w: usize) -> HhtAlpha {
        HhtAlpha {
            alpha,
            linear: SymmetricBand::zeros(n, w),
            linear_h: f64::NAN,
            linear_factor: None,
            jacobian: SymmetricBand::zeros(n, w),
            factor: None,
            frozen_h: f64::NAN,
            q0: Vec::new(),
            v0: Vec::new(),
            a0: Vec::new(),
            constant: Vec::new(),
            y: Vec::new(),
            v1: Vec::new(),
            a1: Vec::new(),
            residual: Vec::new(),
            force: Vec::new(),
            history: Vec::new(),
            guess: Vec::new(),
            kept: None,
            last_linear: false,
            predicts: false,
            last_h: f64::NAN,
        }
    }

    /// The local error of the last step in the degrees of freedom `counted`
    /// picks (their unit: m for translations): Zienkiewicz and Xie's estimate for
    /// the Newmark family, h^2 |beta - 1/6| |a1 - a0|, the difference between
    /// the step's displacement and a third-order one's from the same start
    /// (Zienkiewicz & Xie 1991, Earthq. Eng. Struct. Dyn. 20). The largest
    /// over them; 0 before any step.
    pub fn local_error(&self, counted: impl Fn(usize) -> bool) -> f64 {
        if !self.last_h.is_finite() {
            return 0.0;
        }
        let (_, beta, _) = self.parameters();
        let factor = self.last_h * self.last_h * (beta - 1.0 / 6.0).abs();
        (self.a1.iter().zip(&self.a0).enumerate())
            .filter(|(i, _)| counted(*i))
            .fold(0.0, |worst, (_, (a1, a0))| {
                worst.max(factor * (a1 - a0).abs())
            })
    }

    /// (alpha, beta, gamma).
    pub fn parameters(&self) -> (f64, f64, f64) {
        parameters_of(self.alpha)
    }

    /// Starts each step's Newton (without a `guess_next`) from the motion
    /// carried on over the step, q0 + h v0 + h^2 a0 / 2, instead of the start
    /// state: a step of a moving structure starts an iteration or two closer
    /// to its solution. The answer changes only to Newton's tolerance.
    pub fn predict_start(&mut self) {
        self.predicts = true;
    }

    /// Keeps a copy of every Newton matrix before the held DOFs become identity
    /// rows (one copy of the band per iteration), for an interface Jacobian.
    pub fn keep_newton_matrix(&mut self) {
        if self.kept.is_none() {
            self.kept = Some(SymmetricBand::zeros(
                self.jacobian.size(),
                self.jacobian.half_bandwidth(),
            ));
        }
    }

    /// The last step's Newton matrix with its held rows in place and its
    /// factor (held DOFs as identity rows): the linear ones after a linear
    /// step, the kept and last ones after a nonlinear step.
    pub fn last_newton(&self) -> Option<(&SymmetricBand, &BandLdlt)> {
        if self.last_linear {
            Some((&self.linear, self.linear_factor.as_ref()?))
        } else {
            Some((self.kept.as_ref()?, self.factor.as_ref()?))
        }
    }

    /// [`HhtAlpha::last_newton`], or an error naming the unit (`label`) when
    /// the last step kept none.
    pub fn last_newton_of(&self, label: &str) -> Result<(&SymmetricBand, &BandLdlt), UnitError> {
        self.last_newton()
            .ok_or_else(|| UnitError::Numerical(format!("{label}: the step kept no Newton matrix")))
    }

    /// Starts the next step's Newton from `y` instead of the start state (the
    /// held DOFs still take their prescribed values): a step repeated with
    /// slightly changed inputs starts near its solution. Used once.
    pub fn guess_next(&mut self, y: &[f64]) {
        self.guess.clear();
        self.guess.extend_from_slice(y);
    }

    /// The Newton matrix with the tangent of the last iteration.
    pub fn newton_matrix(&self) -> &SymmetricBand {
        &self.jacobian
    }

    /// Forgets the linear Newton matrix: the system's M, C or K changed (a
    /// unit initialised again), so the next step forms it anew.
    pub fn forget_matrices(&mut self) {
        self.linear_h = f64::NAN;
        self.frozen_h = f64::NAN;
    }

    /// Forms and factorises the linear Newton matrix when `h` changed, or
    /// at every step when the matrices vary.
    fn prepare_linear(&mut self, m: &Matrices<'_>, h: f64, held: &[(usize, [f64; 3])]) {
        if m.varies {
            return self.prepare_varying(m, h, held);
        }
        if self.linear_h == h {
            return;
        }
        let (alpha, beta, gamma) = self.parameters();
        self.linear.set_present_combination(&[
            (1.0 / (beta * h * h), Some(m.mass)),
            ((1.0 - alpha) * gamma / (beta * h), m.damping),
            (1.0 - alpha, m.stiffness),
        ]);
        let mut with_held = self.linear.clone();
        for (d, _) in held {
            with_held.set_identity_row(*d);
        }
        self.linear_factor = BandLdlt::new(&with_held);
        self.linear_h = h;
    }

    /// The linear Newton matrix of matrices that vary by step, formed and
    /// factorised into the kept buffers (`jacobian` holds the held rows):
    /// nothing allocated once they are sized.
    fn prepare_varying(&mut self, m: &Matrices<'_>, h: f64, held: &[(usize, [f64; 3])]) {
        let (alpha, beta, gamma) = self.parameters();
        self.linear.set_present_combination(&[
            (1.0 / (beta * h * h), Some(m.mass)),
            ((1.0 - alpha) * gamma / (beta * h), m.damping),
            (1.0 - alpha, m.stiffness),
        ]);
        self.jacobian.copy_from(&self.linear);
        for (d, _) in held {
            self.jacobian.set_identity_row(*d);
        }
        let (n, w) = (self.jacobian.size(), self.jacobian.half_bandwidth());
        let factor = self
            .linear_factor
            .get_or_insert_with(|| BandLdlt::zeros(n, w));
        if !factor.refactorise(&self.jacobian) {
            self.linear_factor = None;
        }
        // The next constant matrices are formed anew.
        self.linear_h = f64::NAN;
    }

    fn resize(&mut self, n: usize) {
        for v in [
            &mut self.q0,
            &mut self.v0,
            &mut self.a0,
            &mut self.constant,
            &mut self.y,
            &mut self.v1,
            &mut self.a1,
            &mut self.residual,
        ] {
            v.resize(n, 0.0);
        }
    }

    /// Newmark: acceleration and velocity at the step's end from the iterate, the
    /// held DOFs keeping their prescribed motion.
    fn kinematics(&mut self, h: f64, held: &[(usize, [f64; 3])]) {
        let (_, beta, gamma) = self.parameters();
        for i in 0..self.y.len() {
            self.a1[i] = (self.y[i] - self.q0[i] - h * self.v0[i]) / (beta * h * h)
                - (0.5 / beta - 1.0) * self.a0[i];
            self.v1[i] = self.v0[i] + h * ((1.0 - gamma) * self.a0[i] + gamma * self.a1[i]);
        }
        for &(d, [_, v, a]) in held {
            self.v1[d] = v;
            self.a1[d] = a;
        }
    }

    /// The constant part of the residual:
    /// alpha (C v0 + K q0 + g0) - (1 - alpha) f1 - alpha f0.
    fn constant_part(&mut self, m: &Matrices<'_>, loads: &StepLoads<'_>) {
        let alpha = self.alpha;
        for i in 0..self.constant.len() {
            let g0 = loads.g0.map_or(0.0, |g| g[i]);
            self.constant[i] = alpha * g0 - (1.0 - alpha) * loads.f1[i] - alpha * loads.f0[i];
        }
        if let Some(c) = m.damping {
            c.mul_add(alpha, &self.v0, &mut self.constant);
        }
        if let Some(k) = m.stiffness {
            k.mul_add(alpha, &self.q0, &mut self.constant);
        }
    }

    /// One step of `system` from `loads.t0` to `loads.t1`; returns the Newton
    /// iterations. On failure the system keeps its start state.
    pub fn step<S: SecondOrderSystem + ?Sized>(
        &mut self,
        system: &mut S,
        loads: &StepLoads<'_>,
        newton: NewtonSettings,
    ) -> Result<u32, UnitError> {
        let (alpha, beta, gamma) = self.parameters();
        let h = loads.h;
        self.prepare_linear(&system.matrices(), h, loads.held);
        let [q, v, a] = system.motion();
        self.resize(q.len());
        self.q0.copy_from_slice(q);
        self.v0.copy_from_slice(v);
        self.a0.copy_from_slice(a);
        self.constant_part(&system.matrices(), loads);
        let linear = system.is_linear();
        self.first_iterate(loads.held, h, self.predicts && !linear);
        self.history.clear();
        self.last_linear = linear;
        self.last_h = h;
        let scales = TangentScales {
            stiffness: 1.0 - alpha,
            damping: (1.0 - alpha) * gamma / (beta * h),
        };
        let mut converged = None;
        for iteration in 1..=newton.max_iterations {
            self.kinematics(h, loads.held);
            let fresh = if linear {
                self.force.clear();
                false
            } else {
                self.tangent_step(system, loads, scales)
            };
            self.form_residual(&system.matrices(), loads.held);
            let factor = if linear {
                self.linear_factor.as_ref()
            } else if fresh {
                self.factor.as_ref()
            } else {
                None
            };
            let factor = factor.ok_or_else(|| {
                UnitError::Numerical(format!(
                    "{}: the Newton matrix is singular or not finite at t = {} s (iteration {iteration})",
                    system.label(),
                    loads.t1
                ))
            })?;
            for r in self.residual.iter_mut() {
                *r = -*r;
            }
            factor.solve_in_place(&mut self.residual);
            let damped = system.limit_correction(&mut self.residual) < 1.0;
            let step = self.residual.iter().fold(0.0f64, |m, r| m.max(r.abs()));
            self.history.push(step);
            for (y, dy) in self.y.iter_mut().zip(&self.residual) {
                *y += dy;
            }
            system.after_iteration(&self.y, loads.t1);
            if !step.is_finite() {
                break;
            }
            // Relative to the solution's size: below ~1e-12 |y| only round-off moves.
            let size = self.y.iter().fold(1.0f64, |m, y| m.max(y.abs()));
            if linear || (!damped && step < newton.tolerance * size) {
                converged = Some(iteration);
                break;
            }
        }
        let Some(iterations) = converged else {
            return Err(self.not_converged(system.label(), loads.t1));
        };
        self.kinematics(h, loads.held);
        system.set_motion(&self.y, &self.v1, &self.a1);
        Ok(iterations)
    }

    /// Newton's first iterate: the guess if one was given, else the start
    /// state carried on over `h` (s) where asked (`predict`: a `linear` step
    /// is solved exactly from anywhere), else the start state; the held DOFs
    /// at their prescribed values.
    fn first_iterate(&mut self, held: &[(usize, [f64; 3])], h: f64, predict: bool) {
        if self.guess.len() == self.q0.len() {
            self.y.copy_from_slice(&self.guess);
        } else if predict {
            let carried = (self.q0.iter().zip(&self.v0).zip(&self.a0))
                .map(|((q, v), a)| q + h * v + 0.5 * h * h * a);
            for (y, p) in self.y.iter_mut().zip(carried) {
                *y = p;
            }
        } else {
            self.y.copy_from_slice(&self.q0);
        }
        self.guess.clear();
        for &(d, [q, _, _]) in held {
            self.y[d] = q;
        }
    }

    /// Newton's failure, with the corrections it made.
    fn not_converged(&self, label: &str, t1: f64) -> UnitError {
        UnitError::Numerical(format!(
            "{label}: Newton did not converge in the step ending at t = {t1} s; largest corrections per iteration: {}",
            self.history
                .iter()
                .map(|v| format!("{v:.3e}"))
                .collect::<Vec<_>>()
                .join(", ")
        ))
    }

    /// The Newton matrix with the system's tangent at the iterate, refactorised;
    /// whether the factorisation succeeded.
    fn tangent_step<S: SecondOrderSystem + ?Sized>(
        &mut self,
        system: &mut S,
        loads: &StepLoads<'_>,
        scales: TangentScales,
    ) -> bool {
        self.jacobian.copy_from(&self.linear);
        system.nonlinear_force(
            &self.y,
            &self.v1,
            loads.t1,
            Some((&mut self.jacobian, scales)),
            &mut self.force,
        );
        if let Some(kept) = self.kept.as_mut() {
            kept.copy_from(&self.jacobian);
        }
        let frozen = system.tangent_is_frozen();
        if frozen && self.frozen_h == loads.h && self.factor.is_some() {
            return true;
        }
        for (d, _) in loads.held {
            self.jacobian.set_identity_row(*d);
        }
        // A nonlinear structure past a limit point (or a slack part under a large
        // step) has an indefinite Newton matrix: accepted while nonsingular.
        let factor = self.factor.get_or_insert_with(|| {
            BandLdlt::zeros(self.jacobian.size(), self.jacobian.half_bandwidth())
        });
        let factorised = factor.refactorise_nonsingular(&self.jacobian);
        self.frozen_h = if frozen && factorised {
            loads.h
        } else {
            f64::NAN
        };
        factorised
    }

    /// residual = constant + g1 + M a1 + (1 - alpha) (C v1 + K q1), zero at held DOFs.
    fn form_residual(&mut self, m: &Matrices<'_>, held: &[(usize, [f64; 3])]) {
        let alpha = self.alpha;
        let r = &mut self.residual;
        r.copy_from_slice(&self.constant);
        for (ri, f) in r.iter_mut().zip(&self.force) {
            *ri += f;
        }
        m.mass.mul_add(1.0, &self.a1, r);
        if let Some(c) = m.damping {
            c.mul_add(1.0 - alpha, &self.v1, r);
        }
        if let Some(k) = m.stiffness {
            k.mul_add(1.0 - alpha, &self.y, r);
        }
        for (d, _) in held {
            r[*d] = 0.0;
        }
    }
}
