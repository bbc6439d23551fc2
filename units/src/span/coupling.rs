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

use super::fit::{check_order_and_band, sigma_zeros};
use super::transfer::{C64, Span};
use crate::contract::StateSlot;
use crate::contract::Time;
use crate::contract::{Capabilities, StepReport, Unit, UnitDescription, UnitError};
use crate::contract::{Inputs, Port, PortKind};
use crate::numerics::bounded;
use nalgebra::{DMatrix, DVector, Matrix2, Matrix4, Vector2};
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

/// A common-pole rational fit of the 4x4 transfer matrix.
#[derive(Clone, Debug)]
pub struct MatrixFit {
    /// One pole of each conjugate pair (Im > 0), all with Re < 0 (1/s).
    pub poles: Vec<C64>,
    /// residues[o][i][k]: residue of output o, input i at pole k (its conjugate
    /// pair has the conjugate residue).
    pub residues: [[Vec<C64>; 4]; 4],
    pub d: [[f64; 4]; 4],
    pub e: [[f64; 4]; 4],
}

impl MatrixFit {
    /// The fitted 4x4 response at s.
    pub fn response(&self, s: C64) -> [[C64; 4]; 4] {
        let mut h = [[C64::new(0.0, 0.0); 4]; 4];
        for (o, row) in h.iter_mut().enumerate() {
            for (i, v) in row.iter_mut().enumerate() {
                *v = self
                    .poles
                    .iter()
                    .zip(&self.residues[o][i])
                    .map(|(&p, &r)| r / (s - p) + r.conj() / (s - p.conj()))
                    .sum::<C64>()
                    + self.d[o][i]
                    + s * self.e[o][i];
            }
        }
        h
    }
}

/// Real basis of a conjugate pole pair: 1/(s-p) + 1/(s-p*) and i(1/(s-p) - 1/(s-p*)).
fn basis(s: C64, poles: &[C64]) -> Vec<C64> {
    let one = C64::new(1.0, 0.0);
    let i = C64::new(0.0, 1.0);
    let mut b = Vec::with_capacity(2 * poles.len());
    for &p in poles {
        let (x, y) = (one / (s - p), one / (s - p.conj()));
        b.push(x + y);
        b.push(i * (x - y));
    }
    b
}

/// Fits the 4x4 transfer matrix from `inputs` to `outputs` with `order` poles
/// (even, 2..=40) over [band / 1e4, band] rad/s.
pub fn fit_matrix(
    span: &Span,
    inputs: [usize; 4],
    outputs: [usize; 4],
    order: usize,
    band: f64,
) -> Result<MatrixFit, UnitError> {
    span.validate()?;
    check_order_and_band(order, band)?;
    span.check_admissible(inputs)?;
    let samples = (8 * order).max(200);
    let omegas: Vec<f64> = (0..samples)
        .map(|k| band * 10f64.powf(-4.0 + 4.0 * k as f64 / (samples - 1) as f64))
        .collect();
    let data: Vec<[[C64; 4]; 4]> = omegas
        .iter()
        .map(|&w| span.transfer(C64::new(0.0, w), inputs, outputs))
        .collect::<Result<_, _>>()?;
    // Each entry weighted by its size over the band, so that all sixteen count.
    let mut scale = [[0.0_f64; 4]; 4];
    for h in &data {
        for o in 0..4 {
            for i in 0..4 {
                scale[o][i] = scale[o][i].max(h[o][i].norm());
            }
        }
    }
    let pairs = order / 2;
    let mut poles: Vec<C64> = (0..pairs)
        .map(|k| {
            let b = band * 10f64.powf(-4.0 + 4.0 * (k as f64 + 0.5) / pairs as f64);
            C64::new(-b / 100.0, b)
        })
        .collect();
    for _ in 0..15 {
        poles = relocate(&poles, &omegas, &data, &scale)?;
    }
    residues(span, poles, inputs, outputs, &omegas, &data, &scale)
}

/// One relocation of the common poles (fast vector fitting: each entry's block
/// is reduced by QR to the rows that involve the shared sigma function).
fn relocate(
    poles: &[C64],
    omegas: &[f64],
    data: &[[[C64; 4]; 4]],
    scale: &[[f64; 4]; 4],
) -> Result<Vec<C64>, UnitError> {
    let n = 2 * poles.len();
    let own = n + 2; // residues, d, e
    let cols = own + n + 1; // + sigma residues + right-hand side
    let mut stacked = DMatrix::zeros(16 * n, n);
    let mut rhs = DVector::zeros(16 * n);
    let bases: Vec<Vec<C64>> = omegas
        .iter()
        .map(|&w| basis(C64::new(0.0, w), poles))
        .collect();
    for o in 0..4 {
        for i in 0..4 {
            let weight = 1.0 / scale[o][i].max(1e-300);
            let mut m = DMatrix::zeros(2 * omegas.len(), cols);
            for (k, (&w, b)) in omegas.iter().zip(&bases).enumerate() {
                let h = data[k][o][i] * weight;
                let s = C64::new(0.0, w);
                let mut row: Vec<C64> = b.iter().map(|v| v * weight).collect();
                row.push(C64::new(weight, 0.0));
                row.push(s * weight);
                row.extend(b.iter().map(|&v| -h * v));
                row.push(h);
                for (c, v) in row.iter().enumerate() {
                    m[(2 * k, c)] = v.re;
                    m[(2 * k + 1, c)] = v.im;
                }
            }
            let r = m.qr().r();
            let block = 4 * o + i;
            for row in 0..n {
                for c in 0..n {
                    stacked[(block * n + row, c)] = r[(own + row, own + c)];
                }
                rhs[block * n + row] = r[(own + row, cols - 1)];
            }
        }
    }
    let x = bounded::least_squares("vector fitting", stacked, &rhs, 1e-14)?;
    sigma_zeros(poles, &x.as_slice()[..n])
}

/// Residues, D and E of every entry with the poles fixed; D corrected so that the
/// static response is exact.
fn residues(
    span: &Span,
    poles: Vec<C64>,
    inputs: [usize; 4],
    outputs: [usize; 4],
    omegas: &[f64],
    data: &[[[C64; 4]; 4]],
    scale: &[[f64; 4]; 4],
) -> Result<MatrixFit, UnitError> {
    let n = 2 * poles.len();
    let bases: Vec<Vec<C64>> = omegas
        .iter()
        .map(|&w| basis(C64::new(0.0, w), &poles))
        .collect();
    let static_gain = span.transfer(C64::new(0.0, 0.0), inputs, outputs)?;
    let at_zero = basis(C64::new(0.0, 0.0), &poles);
    let mut fit = MatrixFit {
        residues: Default::default(),
        d: [[0.0; 4]; 4],
        e: [[0.0; 4]; 4],
        poles,
    };
    for o in 0..4 {
        for i in 0..4 {
            // Only a load answering a motion grows without bound (stiffness and
            // inertia); compliances and transmissions vanish at high frequency, so
            // they get no feedthrough and their static value comes from the
            // residues (a heavily weighted row), keeping the model strictly proper
            // where the span is.
            let improper = is_motion(inputs[i]) && !is_motion(outputs[o]);
            let unknowns = if improper { n + 2 } else { n };
            let rows = 2 * omegas.len() + usize::from(!improper);
            let weight = 1.0 / scale[o][i].max(1e-300);
            let mut a = DMatrix::zeros(rows, unknowns);
            let mut b = DVector::zeros(rows);
            for (k, (&w, basis)) in omegas.iter().zip(&bases).enumerate() {
                let s = C64::new(0.0, w);
                let mut row = basis.clone();
                if improper {
                    row.push(C64::new(1.0, 0.0));
                    row.push(s);
                }
                for (c, v) in row.iter().enumerate() {
                    a[(2 * k, c)] = v.re * weight;
                    a[(2 * k + 1, c)] = v.im * weight;
                }
                b[2 * k] = data[k][o][i].re * weight;
                b[2 * k + 1] = data[k][o][i].im * weight;
            }
            if !improper {
                let static_weight = 1e4 * weight;
                for (c, v) in at_zero.iter().enumerate() {
                    a[(rows - 1, c)] = v.re * static_weight;
                }
                b[rows - 1] = static_gain[o][i].re * static_weight;
            }
            let x = bounded::least_squares("vector fitting", a, &b, 1e-14)?;
            fit.residues[o][i] = (0..n / 2)
                .map(|k| C64::new(x[2 * k], x[2 * k + 1]))
                .collect();
            let dynamic_at_zero: f64 = (0..n).map(|m| x[m] * at_zero[m].re).sum();
            if improper {
                fit.d[o][i] = static_gain[o][i].re - dynamic_at_zero;
                fit.e[o][i] = x[n + 1];
            } else {
                // Spread what the weighted row left of the static value over the
                // residues of the slowest pole pair (tiny), so H(0) stays exact.
                let gap = static_gain[o][i].re - dynamic_at_zero;
                let slowest = (0..n / 2)
                    .min_by(|&p, &q| fit.poles[p].norm().total_cmp(&fit.poles[q].norm()))
                    .unwrap_or(0);
                let unit_gain = at_zero[2 * slowest].re;
                if unit_gain != 0.0 {
                    fit.residues[o][i][slowest].re += gap / unit_gain;
                }
            }
        }
    }
    Ok(fit)
}

/// Whether end quantity `q` (1..8) is a motion (deflection or rotation).
fn is_motion(q: usize) -> bool {
    matches!(q, 1 | 2 | 5 | 6)
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
    #[serde(default)]
    pub orientation: Orientation,
    /// Number of poles (even, 2..=40), default 16.
    #[serde(default = "sixteen")]
    pub order: usize,
    /// Band of the fit (rad/s), default 2 pi 10.
    #[serde(default = "ten_hz")]
    pub band: f64,
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
        let all: Vec<usize> = (0..4).collect();
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
                .map(|&q| {
                    let (name, kind) = port_of(q);
                    Port::output(name, kind).with_feedthrough(&all)
                })
                .collect(),
            capabilities: Capabilities::default(),
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

    fn restore_state(&mut self, slot: &StateSlot) -> Result<(), UnitError> {
        self.state.clone_from(&*slot.load::<CouplingState>()?);
        Ok(())
    }
}
