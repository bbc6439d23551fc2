//! The span between two pipe sections (scene kind `span_coupling`): the full 4x4
//! transfer matrix of the suspended span, so that it couples to a section at each
//! end.
//!
//! Orientation `upper_motion`: deflection and rotation at the upper end (U1, U2)
//! and moment and shear at the lower end (U7, U8) in; moment and shear at the upper
//! end (U3, U4) and deflection and rotation at the lower end (U5, U6) out.
//! `lower_motion` is the mirror: U5, U6, U3, U4 in; U7, U8, U1, U2 out.
//!
//! Several entries are improper: the upper shear answering the upper deflection
//! grows like |s|^(3/2) (the span's inertia), so no proper rational function
//! follows it. The fit is H(s) ~ sum_k R_k / (s - p_k) + D + E s with common
//! poles for the sixteen entries (vector fitting, Gustavsen and Semlyen 1999, in
//! its fast stacked form), stable by construction, over [band / 1e4, band]; D is
//! then corrected so that H(0) is exact (the static cantilever). The E s term is a
//! mass-like feedthrough of the inputs' rate, exact for ramped inputs (zero under
//! a zero-order hold).
//!
//! Only the loads answering motions are improper; compliances and transmissions
//! vanish at high frequency, so their fits have no feedthrough and get their exact
//! static value from the residues. A constant compliance there made the coupled
//! run with FE sections unstable.
//!
//! Realisation: one 2x2 real modal block per pole pair and input, stepped with the
//! trapezoidal rule (default; the sections' integrator, which a stable coupling
//! needs) or exactly (closed-form ramp response from a 4x4 matrix exponential per
//! pole pair); the cost per step is linear in the order.

pub use super::matrix_fit::{MatrixFit, fit_matrix};
use super::transfer::Span;
use crate::contract::StateSlot;
use crate::contract::Time;
use crate::contract::{Capabilities, StepReport, Unit, UnitDescription, UnitError};
use crate::contract::{Hold, Inputs, Port, PortKind};
use nalgebra::{Matrix2, Matrix4, Vector2};
use serde::Deserialize;

/// Which end's motion is the input.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Orientation {
    /// U1, U2, U7, U8 in; U3, U4, U5, U6 out.
    #[default]
    UpperMotion,
    /// U5, U6, U3, U4 in; U7, U8, U1, U2 out.
    LowerMotion,
}

impl Orientation {
    /// Input and output quantity numbers (seed 004 eq. 5.2), in port order.
    pub fn quantities(self) -> ([usize; 4], [usize; 4]) {
        match self {
            Orientation::UpperMotion => ([1, 2, 7, 8], [3, 4, 5, 6]),
            Orientation::LowerMotion => ([5, 6, 3, 4], [7, 8, 1, 2]),
        }
    }
}

/// Port name and kind of end quantity `q` (1..8).
fn port_of(q: usize) -> (&'static str, PortKind) {
    match q {
        1 => ("upper_deflection", PortKind::Displacement),
        2 => ("upper_rotation", PortKind::Rotation),
        3 => ("upper_moment", PortKind::Moment),
        4 => ("upper_shear", PortKind::Force),
        5 => ("lower_deflection", PortKind::Displacement),
        6 => ("lower_rotation", PortKind::Rotation),
        7 => ("lower_moment", PortKind::Moment),
        _ => ("lower_shear", PortKind::Force),
    }
}

/// How the span's states are stepped.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Discretization {
    /// The trapezoidal rule with a little numerical damping (theta method,
    /// theta = 1/2 + alpha): needed for a stable coupling with FE sections, whose
    /// converged partitioned solution then behaves like one model stepped by one
    /// rule.
    #[default]
    Trapezoidal,
    /// The exact response to the ramped input (matrix exponential): the most
    /// accurate on its own, but coupled to FE sections it goes unstable.
    Exact,
}

/// Parameters of the `span_coupling` unit.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpanCouplingParams {
    /// EI (N m^2).
    pub flexural_rigidity: f64,
    /// mu (kg/m).
    pub mass_per_length: f64,
    /// c_d (N s/m^2), default 0.
    #[serde(default)]
    pub damping_per_length: f64,
    /// L (m).
    pub length: f64,
    /// Constant axial tension T (N), default 0: the shears are then the
    /// transverse forces EI y''' - T y'.
    #[serde(default)]
    pub tension: f64,
    /// Which end's motion is the input.
    #[serde(default)]
    pub orientation: Orientation,
    /// Number of poles (even, 2..=40), default 16.
    #[serde(default = "sixteen")]
    pub order: usize,
    /// Band of the fit (rad/s), default 2 pi 10.
    #[serde(default = "ten_hz")]
    pub band: f64,
    /// How the span's states are stepped.
    #[serde(default)]
    pub discretization: Discretization,
    /// Numerical damping of the trapezoidal stepping, in [0, 1/3]: the theta
    /// method with theta = 1/2 + alpha. Default 0 (second order). The theta
    /// method damps a mode at about alpha h omega^2 per second, more than the
    /// span's own damping for its upper modes, so keep it small: 0.01 keeps the
    /// coupled example bounded at h = 10 ms (it grows slowly after 300 s with 0)
    /// but costs about 2 % of accuracy.
    #[serde(default)]
    pub alpha: f64,
}

fn sixteen() -> usize {
    16
}

fn ten_hz() -> f64 {
    2.0 * std::f64::consts::PI * 10.0
}

/// The modal states of one pole pair, for each of the four inputs (the inputs are
/// the inner index, so one step updates four lanes at once): z = re + i im.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
struct PairStates {
    re: [f64; 4],
    im: [f64; 4],
}

crate::state_struct! {
    /// Everything that changes while stepping.
    #[derive(Debug, serde::Serialize, serde::Deserialize)]
    struct CouplingState {
        /// Modal states, one entry per pole pair.
        z: Vec<PairStates>,
        /// Rate of each input over the last step (1/s times its unit).
        rate: [f64; 4],
    }
}

/// Exact ramp step of one pole pair's block: z1 = Phi z0 + g1 u0 + g2 (u1 - u0).
#[derive(Clone, Debug)]
struct BlockStep {
    phi: Matrix2<f64>,
    g1: Vector2<f64>,
    g2: Vector2<f64>,
}

/// Weights of one pole pair's states in the four outputs: output o gets
/// re[i][o] z_re[i] + im[i][o] z_im[i] summed over inputs i.
#[derive(Clone, Debug)]
struct PairWeights {
    re: [[f64; 4]; 4],
    im: [[f64; 4]; 4],
}

/// The span between two sections as a 4x4 transfer-function unit.
pub struct SpanCoupling {
    description: UnitDescription,
    fit: MatrixFit,
    /// Output weights of each pole pair's states.
    c: Vec<PairWeights>,
    state: CouplingState,
    step: f64,
    blocks: Vec<BlockStep>,
    discretization: Discretization,
    alpha: f64,
}

impl SpanCoupling {
    /// Fits and realises the unit; fails for bad properties, order or band.
    pub fn new(params: SpanCouplingParams) -> Result<SpanCoupling, UnitError> {
        let span = Span {
            flexural_rigidity: params.flexural_rigidity,
            mass_per_length: params.mass_per_length,
            damping_per_length: params.damping_per_length,
            length: params.length,
            tension: params.tension,
        };
        if !(0.0..=1.0 / 3.0 + 1e-12).contains(&params.alpha) {
            return Err(UnitError::parameter(
                "alpha",
                params.alpha,
                "expected a numerical damping in [0, 1/3]",
            ));
        }
        let (inputs, outputs) = params.orientation.quantities();
        let fit = fit_matrix(&span, inputs, outputs, params.order, params.band)?;
        let pairs = fit.poles.len();
        // r/(s - p) + conj from z' = p z + u: y = 2 Re(r z) = 2 r_re z_re - 2 r_im z_im.
        let c = (0..pairs)
            .map(|k| PairWeights {
                re: std::array::from_fn(|i| {
                    std::array::from_fn(|o| 2.0 * fit.residues[o][i][k].re)
                }),
                im: std::array::from_fn(|i| {
                    std::array::from_fn(|o| -2.0 * fit.residues[o][i][k].im)
                }),
            })
            .collect();
        // At a communication point an output follows the inputs its fit's
        // direct term D couples it to (the rate term E acts through a step).
        let direct = |o: usize| -> Vec<usize> { (0..4).filter(|&i| fit.d[o][i] != 0.0).collect() };
        let description = UnitDescription {
            kind: "span_coupling".into(),
            inputs: inputs
                .iter()
                .map(|&q| {
                    let (name, kind) = port_of(q);
                    Port::input(name, kind)
                })
                .collect(),
            outputs: outputs
                .iter()
                .enumerate()
                .map(|(o, &q)| {
                    let (name, kind) = port_of(q);
                    Port::output(name, kind).with_feedthrough(&direct(o))
                })
                .collect(),
            capabilities: Capabilities {
                step_jacobian: true,
                ..Capabilities::default()
            },
        };
        Ok(SpanCoupling {
            description,
            state: CouplingState {
                z: vec![PairStates::default(); pairs],
                rate: [0.0; 4],
            },
            fit,
            c,
            step: f64::NAN,
            blocks: Vec::new(),
            discretization: params.discretization,
            alpha: params.alpha,
        })
    }

    /// The fitted transfer matrix.
    pub fn fit(&self) -> &MatrixFit {
        &self.fit
    }

    fn discretize(&mut self, h: f64) {
        self.blocks = self
            .fit
            .poles
            .iter()
            .map(|p| {
                let mut m = Matrix4::zeros();
                m[(0, 0)] = p.re * h;
                m[(0, 1)] = -p.im * h;
                m[(1, 0)] = p.im * h;
                m[(1, 1)] = p.re * h;
                m[(0, 2)] = h;
                m[(2, 3)] = 1.0;
                if self.discretization == Discretization::Trapezoidal {
                    let a = Matrix2::new(p.re * h, -p.im * h, p.im * h, p.re * h);
                    let i2 = Matrix2::identity();
                    // I - A h / 2 is invertible for every stable pole.
                    let theta = 0.5 + self.alpha;
                    let left = (i2 - a * theta).try_inverse().unwrap_or(i2);
                    let ga = left * Vector2::new((1.0 - theta) * h, 0.0);
                    let gb = left * Vector2::new(theta * h, 0.0);
                    return BlockStep {
                        phi: left * (i2 + a * (1.0 - theta)),
                        g1: ga + gb,
                        g2: gb,
                    };
                }
                let e = m.exp();
                BlockStep {
                    phi: Matrix2::new(e[(0, 0)], e[(0, 1)], e[(1, 0)], e[(1, 1)]),
                    g1: Vector2::new(e[(0, 2)], e[(1, 2)]),
                    g2: Vector2::new(e[(0, 3)], e[(1, 3)]),
                }
            })
            .collect();
        self.step = h;
    }
}

impl Unit for SpanCoupling {
    fn description(&self) -> &UnitDescription {
        &self.description
    }

    fn initialize(&mut self, _t0: Time, inputs: Inputs<'_>) -> Result<(), UnitError> {
        self.state.rate = [0.0; 4];
        // Steady state of each block for a constant input: z = -A^-1 [u, 0].
        for i in 0..4 {
            let u = inputs.at(i, 0.0);
            for (z, p) in self.state.z.iter_mut().zip(&self.fit.poles) {
                let norm = p.norm_sqr();
                // A = [[a, -b], [b, a]], A^-1 = [[a, b], [-b, a]] / |p|^2.
                z.re[i] = -p.re * u / norm;
                z.im[i] = p.im * u / norm;
            }
        }
        Ok(())
    }

    fn do_step(&mut self, _t: Time, h: Time, inputs: Inputs<'_>) -> Result<StepReport, UnitError> {
        let h = h.as_secs();
        if h != self.step {
            self.discretize(h);
        }
        let u0: [f64; 4] = std::array::from_fn(|i| inputs.at(i, 0.0));
        let du: [f64; 4] = std::array::from_fn(|i| inputs.at(i, 1.0) - u0[i]);
        self.state.rate = std::array::from_fn(|i| inputs.rate(i, h));
        let mut sum = 0.0;
        for (z, b) in self.state.z.iter_mut().zip(&self.blocks) {
            let (p, g1, g2) = (&b.phi, &b.g1, &b.g2);
            for i in 0..4 {
                let (re, im) = (z.re[i], z.im[i]);
                z.re[i] = p[(0, 0)] * re + p[(0, 1)] * im + g1[0] * u0[i] + g2[0] * du[i];
                z.im[i] = p[(1, 0)] * re + p[(1, 1)] * im + g1[1] * u0[i] + g2[1] * du[i];
                sum += z.re[i] + z.im[i];
            }
        }
        // A non-finite state makes the sum non-finite.
        if !sum.is_finite() {
            return Err(UnitError::Numerical(
                "the span's state became non-finite".into(),
            ));
        }
        Ok(StepReport::default())
    }

    fn outputs(&self, inputs: Inputs<'_>, out: &mut [f64]) {
        let u = inputs.end();
        let mut modal = [0.0; 4];
        for (z, c) in self.state.z.iter().zip(&self.c) {
            for i in 0..4 {
                let (re, im) = (z.re[i], z.im[i]);
                for ((m, cr), ci) in modal.iter_mut().zip(&c.re[i]).zip(&c.im[i]) {
                    *m += cr * re + ci * im;
                }
            }
        }
        for (o, value) in out.iter_mut().enumerate().take(4) {
            let direct: f64 = (0..4)
                .map(|i| self.fit.d[o][i] * u[i] + self.fit.e[o][i] * self.state.rate[i])
                .sum();
            *value = modal[o] + direct;
        }
    }

    fn save_state(&self, slot: &mut StateSlot) -> Result<(), UnitError> {
        slot.store(&self.state);
        Ok(())
    }

    /// Exact: the states are linear in the inputs' start and end values, the
    /// outputs linear in the states, the end inputs and their rate.
    fn step_jacobian(&mut self, inputs: Inputs<'_>, jacobian: &mut [f64]) -> Result<(), UnitError> {
        let h = self.step;
        for i in 0..4 {
            // d u0, d (u1 - u0) and d rate per unit change of the end value.
            let (d_u0, d_du, d_rate) = match inputs.hold(i) {
                Hold::Ramp => (0.0, 1.0, 1.0 / h),
                Hold::ZeroOrder => (1.0, 0.0, 0.0),
            };
            for o in 0..4 {
                let mut sum = self.fit.d[o][i] + self.fit.e[o][i] * d_rate;
                for (b, c) in self.blocks.iter().zip(&self.c) {
                    let d_re = b.g1[0] * d_u0 + b.g2[0] * d_du;
                    let d_im = b.g1[1] * d_u0 + b.g2[1] * d_du;
                    sum += c.re[i][o] * d_re + c.im[i][o] * d_im;
                }
                jacobian[o * 4 + i] = sum;
            }
        }
        Ok(())
    }

    fn restore_state(&mut self, slot: &StateSlot) -> Result<(), UnitError> {
        self.state.clone_from(&*slot.load::<CouplingState>()?);
        Ok(())
    }
}
