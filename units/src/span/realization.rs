//! From a rational approximation in x = (beta L)^4 to a state-space system in s, with
//! unstable poles reflected into the left half-plane, and its exact discretisation
//! for an input ramped over each step.

use super::rational::RationalX;
use super::transfer::{C64, Span};
use crate::contract::UnitError;
use crate::numerics::bounded;
use nalgebra::{DMatrix, DVector};

/// A real polynomial in s, ascending coefficients.
pub type Poly = Vec<f64>;

fn poly_mul(a: &[f64], b: &[f64]) -> Poly {
    let mut out = vec![0.0; a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            out[i + j] += x * y;
        }
    }
    out
}

/// p(x(s)) for x(s) = -(L^4 / EI)(c_d s + mu s^2).
fn substitute(p: &[f64], span: &Span) -> Poly {
    let k = -span.length.powi(4) / span.flexural_rigidity;
    let x = [0.0, k * span.damping_per_length, k * span.mass_per_length];
    let mut out = vec![0.0];
    for &c in p.iter().rev() {
        out = poly_mul(&out, &x);
        out[0] += c;
    }
    while out.len() > 1 && out.last().is_some_and(|v| *v == 0.0) {
        out.pop();
    }
    out
}

/// Least-squares residues (and a constant) for the given stable poles against the
/// exact H_{U2 -> U5} at log-spaced frequencies in [band / 1e4, band], weighted by
/// 1 / |H|, realised in real modal form (a 2x2 block per conjugate pair).
fn fit_residues(poles: &[C64], span: &Span, band: f64) -> Result<StateSpace, UnitError> {
    if !(band.is_finite() && band > 0.0) {
        return Err(UnitError::parameter(
            "band",
            band,
            "expected a finite angular frequency > 0 (rad/s)",
        ));
    }
    // One representative per real pole or conjugate pair.
    let mut groups: Vec<C64> = Vec::new();
    for &p in poles {
        if p.im.abs() <= 1e-9 * p.norm().max(1e-300) {
            groups.push(C64::new(p.re, 0.0));
        } else if p.im > 0.0 {
            groups.push(p);
        }
    }
    // The static gain H(0) (the rigid tilt of the span) is kept exactly: the constant
    // is eliminated, d = H(0) - sum_k r_k b_k(0), and the residues r_k fit
    // H(s) - H(0) on b_k(s) - b_k(0).
    let unknowns = groups
        .iter()
        .map(|p| if p.im == 0.0 { 1 } else { 2 })
        .sum::<usize>();
    let samples = (4 * unknowns).max(200);
    let mut rows: Vec<Vec<f64>> = Vec::with_capacity(2 * samples);
    let mut rhs: Vec<f64> = Vec::with_capacity(2 * samples);
    let one = C64::new(1.0, 0.0);
    let basis_at = |s: C64| -> Vec<C64> {
        let mut basis = Vec::with_capacity(unknowns);
        for &p in &groups {
            if p.im == 0.0 {
                basis.push(one / (s - p));
            } else {
                let (a, b) = (one / (s - p), one / (s - p.conj()));
                basis.push(a + b);
                basis.push(C64::new(0.0, 1.0) * (a - b));
            }
        }
        basis
    };
    let zero = C64::new(0.0, 0.0);
    let dc = span.transfer(zero, [1, 2, 7, 8], [3, 4, 5, 6])?[2][1];
    let basis0 = basis_at(zero);
    for k in 0..samples {
        let w = band * 10f64.powf(-4.0 + 4.0 * k as f64 / (samples - 1) as f64);
        let s = C64::new(0.0, w);
        let exact = span.transfer(s, [1, 2, 7, 8], [3, 4, 5, 6])?[2][1];
        let weight = 1.0 / exact.norm().max(1e-300);
        let basis: Vec<C64> = basis_at(s)
            .iter()
            .zip(&basis0)
            .map(|(b, b0)| b - b0)
            .collect();
        rows.push(basis.iter().map(|c| c.re * weight).collect());
        rows.push(basis.iter().map(|c| c.im * weight).collect());
        rhs.push((exact - dc).re * weight);
        rhs.push((exact - dc).im * weight);
    }
    let a = DMatrix::from_fn(rows.len(), unknowns, |r, c| rows[r][c]);
    let b = DVector::from_vec(rhs);
    let x = bounded::least_squares("residue fit", a, &b, 1e-14)?;
    let (am, bm, cm) = real_modal_form(&groups, x.as_slice());
    let d = dc.re
        - basis0
            .iter()
            .zip(x.iter())
            .map(|(b, r)| b.re * r)
            .sum::<f64>();
    Ok(StateSpace {
        a: am,
        b: bm,
        c: cm,
        d,
        poles: poles.to_vec(),
        repaired: 0,
    })
}

/// The real modal realisation (A, B, C) of residues `x` at the pole groups (one
/// per real pole or conjugate pair): a 1x1 block per real pole, a 2x2 rotation
/// block per pair (entries of size |p|, well conditioned for the exponential).
fn real_modal_form(groups: &[C64], x: &[f64]) -> (DMatrix<f64>, DVector<f64>, DVector<f64>) {
    let n: usize = groups.iter().map(|p| if p.im == 0.0 { 1 } else { 2 }).sum();
    let mut am = DMatrix::zeros(n, n);
    let mut bm = DVector::zeros(n);
    let mut cm = DVector::zeros(n);
    let (mut row, mut k) = (0, 0);
    for &p in groups {
        let pair = p.im != 0.0;
        let r = if pair {
            C64::new(x[k], x[k + 1])
        } else {
            C64::new(x[k], 0.0)
        };
        row = put_modal_block((&mut am, &mut bm, &mut cm), row, p, r, pair);
        k += if pair { 2 } else { 1 };
    }
    (am, bm, cm)
}

/// Writes the modal block of pole `p` with residue `r` at `row` of (A, B, C)
/// and returns the next row: 1x1 for a real pole; for a conjugate `pair`,
/// r/(s-p) + conj as z' = p z + u, y = 2 Re(r z), z = x1 + i x2, a 2x2
/// rotation block (entries of size |p|, well conditioned for the exponential).
fn put_modal_block(
    (a, b, c): (&mut DMatrix<f64>, &mut DVector<f64>, &mut DVector<f64>),
    row: usize,
    p: C64,
    r: C64,
    pair: bool,
) -> usize {
    a[(row, row)] = p.re;
    b[row] = 1.0;
    if !pair {
        c[row] = r.re;
        return row + 1;
    }
    a[(row, row + 1)] = -p.im;
    a[(row + 1, row)] = p.im;
    a[(row + 1, row + 1)] = p.re;
    c[row] = 2.0 * r.re;
    c[row + 1] = -2.0 * r.im;
    row + 2
}

/// Stable poles in place of an approximation's poles, some in the right half-plane:
/// every pole is reflected to Re < 0, then all are relocated by vector fitting over
/// the band (reflection alone leaves the high orders several per cent off, since
/// the reflected poles no longer sit where the span resonates). Real poles enter
/// the relocation as lightly damped pairs of their size, two at a time; an odd one
/// out stays a real pole.
fn repair_poles(poles: &[C64], span: &Span, band: f64) -> Result<Vec<C64>, UnitError> {
    let mut pairs: Vec<C64> = poles
        .iter()
        .filter(|p| p.im > 1e-9 * p.norm())
        .map(|p| C64::new(-p.re.abs().max(1e-6 * p.norm()), p.im))
        .collect();
    let reals: Vec<f64> = poles
        .iter()
        .filter(|p| p.im.abs() <= 1e-9 * p.norm())
        .map(|p| p.re.abs().max(1e-9))
        .collect();
    for two in reals.chunks_exact(2) {
        let size = 0.5 * (two[0] + two[1]);
        pairs.push(C64::new(-size / 100.0, size));
    }
    let mut relocated = super::fit::relocate_poles(span, &pairs, band)?;
    if reals.len() % 2 == 1 {
        relocated.push(C64::new(-reals[reals.len() - 1], 0.0));
    }
    Ok(relocated)
}

/// Roots of a polynomial (companion-matrix eigenvalues).
fn roots(p: &[f64]) -> Result<Vec<C64>, UnitError> {
    let n = p.len() - 1;
    if n == 0 {
        return Ok(Vec::new());
    }
    let lead = p[n];
    let companion = DMatrix::from_fn(n, n, |r, c| {
        if r + 1 == c {
            1.0
        } else if r == n - 1 {
            -p[c] / lead
        } else {
            0.0
        }
    });
    bounded::complex_eigenvalues("polynomial roots", companion).map(|z| z.iter().copied().collect())
}

/// A single-input single-output state-space system dx/dt = A x + B u, y = C x + D u.
#[derive(Clone, Debug)]
pub struct StateSpace {
    /// State matrix A.
    pub a: DMatrix<f64>,
    /// Input vector B.
    pub b: DVector<f64>,
    /// Output vector C.
    pub c: DVector<f64>,
    /// Feedthrough D.
    pub d: f64,
    /// Poles (1/s), after repair.
    pub poles: Vec<C64>,
    /// Poles that were in the right half-plane and were reflected.
    pub repaired: usize,
}

impl StateSpace {
    /// Realises H(s) ~ L num(x(s)) / den(x(s)) in controllable canonical form. An
    /// approximation with poles in the right half-plane is repaired: the poles are
    /// reflected to -Re and the residues refitted by least squares to the exact
    /// transfer function over [band / 1e4, band] (rad/s), realised in real modal form.
    pub fn realize(
        approximation: &RationalX,
        span: &Span,
        band: f64,
    ) -> Result<StateSpace, UnitError> {
        span.validate()?;
        let num: Poly = substitute(&approximation.num, span)
            .iter()
            .map(|c| c * span.length)
            .collect();
        let den = substitute(&approximation.den, span);
        let n = den.len() - 1;
        if n == 0 || num.len() > den.len() {
            return Err(UnitError::Numerical(
                "the approximation is not a proper transfer function in s".into(),
            ));
        }
        let poles = roots(&den)?;
        let repaired = poles.iter().filter(|p| p.re > 0.0).count();
        if repaired > 0 {
            let mut fitted = fit_residues(&repair_poles(&poles, span, band)?, span, band)?;
            fitted.repaired = repaired;
            return Ok(fitted);
        }
        let lead = den[n];
        let (num, den): (Poly, Poly) = (
            num.iter().map(|c| c / lead).collect(),
            den.iter().map(|c| c / lead).collect(),
        );
        let bn = if num.len() == n + 1 { num[n] } else { 0.0 };
        let a = DMatrix::from_fn(n, n, |r, c| {
            if r + 1 == c {
                1.0
            } else if r == n - 1 {
                -den[c]
            } else {
                0.0
            }
        });
        let mut b = DVector::zeros(n);
        b[n - 1] = 1.0;
        let c = DVector::from_fn(n, |k, _| num.get(k).copied().unwrap_or(0.0) - bn * den[k]);
        let canonical = StateSpace {
            a,
            b,
            c,
            d: bn,
            poles,
            repaired,
        };
        // The same system in real modal form steps in O(n) instead of O(n^2) and is
        // better scaled for the matrix exponential; kept only if it reproduces the
        // canonical response (distinct, well-separated poles).
        Ok(match canonical.to_modal(&den) {
            Some(modal) if modal.is_stable() && modal.agrees_with(&canonical, band) => modal,
            _ => canonical,
        })
    }

    /// The system with residues r_k = c(p_k) / den'(p_k) at its poles, in real
    /// modal form (one state per real pole, a rotation block per conjugate pair);
    /// `den` is the monic denominator of the controllable canonical form.
    fn to_modal(&self, den: &[f64]) -> Option<StateSpace> {
        let horner = |p: &[f64], s: C64| {
            p.iter()
                .rev()
                .fold(C64::new(0.0, 0.0), |acc, &c| acc * s + c)
        };
        let derivative: Vec<f64> = den
            .iter()
            .enumerate()
            .skip(1)
            .map(|(k, c)| k as f64 * c)
            .collect();
        let numerator: Vec<f64> = self.c.iter().copied().collect();
        let n = self.order();
        let mut a = DMatrix::zeros(n, n);
        let mut b = DVector::zeros(n);
        let mut c = DVector::zeros(n);
        let mut row = 0;
        let mut polished = Vec::with_capacity(n);
        for &p in &self.poles {
            // Companion eigenvalues carry the polynomial's conditioning; a few Newton
            // steps on den polish each simple root before its residue is taken.
            let mut p = p;
            for _ in 0..4 {
                let slope = horner(&derivative, p);
                if slope.norm() == 0.0 {
                    break;
                }
                let next = p - horner(den, p) / slope;
                if next.is_finite() {
                    p = next;
                }
            }
            polished.push(p);
            let slope = horner(&derivative, p);
            if slope.norm() == 0.0 || !slope.is_finite() {
                return None;
            }
            let r = horner(&numerator, p) / slope;
            let pair = p.im.abs() > 1e-9 * p.norm();
            if pair && p.im < 0.0 {
                // The conjugate's block is its partner's.
                continue;
            }
            if row + usize::from(pair) >= n {
                return None;
            }
            row = put_modal_block((&mut a, &mut b, &mut c), row, p, r, pair);
        }
        (row == n).then_some(StateSpace {
            a,
            b,
            c,
            d: self.d,
            poles: polished,
            repaired: self.repaired,
        })
    }

    /// Frequency response C (sI - A)^-1 B + D at s (solves a dense system).
    pub fn response(&self, s: C64) -> C64 {
        let n = self.order();
        let m = DMatrix::from_fn(n, n, |i, j| {
            let diagonal = if i == j { s } else { C64::new(0.0, 0.0) };
            diagonal - C64::from(self.a[(i, j)])
        });
        let rhs = DVector::from_fn(n, |i, _| C64::from(self.b[i]));
        match m.lu().solve(&rhs) {
            Some(x) => (0..n).map(|i| x[i] * self.c[i]).sum::<C64>() + self.d,
            None => C64::new(f64::NAN, f64::NAN),
        }
    }

    /// Whether both systems have the same response to 1e-9 of its largest value at
    /// s = 0 and 60 log-spaced frequencies up to ten times the band (rad/s).
    fn agrees_with(&self, other: &StateSpace, band: f64) -> bool {
        let points: Vec<C64> = std::iter::once(C64::new(0.0, 0.0))
            .chain((0..60).map(|k| C64::new(0.0, band * 10f64.powf(-5.0 + 6.0 * k as f64 / 59.0))))
            .collect();
        let (mine, theirs): (Vec<C64>, Vec<C64>) = points
            .iter()
            .map(|&s| (self.response(s), other.response(s)))
            .unzip();
        let scale = theirs.iter().fold(0.0f64, |m, v| m.max(v.norm()));
        scale.is_finite()
            && mine
                .iter()
                .zip(&theirs)
                .all(|(x, y)| (x - y).norm() <= 1e-9 * scale)
    }

    /// The 1x1 and 2x2 diagonal blocks of A as (first state, size), if A has no
    /// entry outside them (modal form): the step then costs O(n).
    pub fn diagonal_blocks(&self) -> Option<Vec<(usize, usize)>> {
        let n = self.order();
        let mut blocks = Vec::new();
        let mut i = 0;
        while i < n {
            let size = if i + 1 < n && (self.a[(i, i + 1)] != 0.0 || self.a[(i + 1, i)] != 0.0) {
                2
            } else {
                1
            };
            blocks.push((i, size));
            i += size;
        }
        let block_of = |k: usize| blocks.iter().position(|&(s, z)| (s..s + z).contains(&k));
        for r in 0..n {
            for col in 0..n {
                if self.a[(r, col)] != 0.0 && block_of(r) != block_of(col) {
                    return None;
                }
            }
        }
        Some(blocks)
    }

    /// The system with the given stable poles and least-squares residues against the
    /// exact H_{U2 -> U5} over [band / 1e4, band].
    pub fn from_poles(poles: &[C64], span: &Span, band: f64) -> Result<StateSpace, UnitError> {
        fit_residues(poles, span, band)
    }

    /// Order (number of states).
    pub fn order(&self) -> usize {
        self.b.len()
    }

    /// Whether every pole has a negative real part.
    pub fn is_stable(&self) -> bool {
        self.poles.iter().all(|p| p.re < 0.0)
    }

    /// Exact step over h for an input ramped from u0 to u1:
    /// x1 = Phi x0 + Gamma1 u0 + Gamma2 (u1 - u0), from one matrix exponential.
    pub fn discretize(&self, h: f64) -> (DMatrix<f64>, DVector<f64>, DVector<f64>) {
        let n = self.order();
        let mut m = DMatrix::zeros(n + 2, n + 2);
        m.view_mut((0, 0), (n, n)).copy_from(&(&self.a * h));
        m.view_mut((0, n), (n, 1)).copy_from(&(&self.b * h));
        m[(n, n + 1)] = 1.0;
        let e = m.exp();
        let phi = e.view((0, 0), (n, n)).into_owned();
        let g1 = e.column(n).rows(0, n).into_owned();
        let g2 = e.column(n + 1).rows(0, n).into_owned();
        (phi, g1, g2)
    }

    /// The exact ramp step over h in the cheapest form A's structure allows: O(n)
    /// per step for a modal realisation, a dense Phi otherwise.
    pub fn stepper(&self, h: f64) -> Stepper {
        let (phi, gamma1, gamma2) = self.discretize(h);
        match self.diagonal_blocks() {
            Some(blocks) => Stepper::Modal(
                blocks
                    .into_iter()
                    .map(|(first, size)| {
                        let at = |r: usize, c: usize| {
                            if r < size && c < size {
                                phi[(first + r, first + c)]
                            } else {
                                0.0
                            }
                        };
                        let g =
                            |v: &DVector<f64>, r: usize| if r < size { v[first + r] } else { 0.0 };
                        ModalBlock {
                            first,
                            size,
                            phi: [at(0, 0), at(0, 1), at(1, 0), at(1, 1)],
                            gamma1: [g(&gamma1, 0), g(&gamma1, 1)],
                            gamma2: [g(&gamma2, 0), g(&gamma2, 1)],
                        }
                    })
                    .collect(),
            ),
            None => Stepper::Dense {
                scratch: DVector::zeros(phi.nrows()),
                phi,
                gamma1,
                gamma2,
            },
        }
    }
}

/// One 1x1 or 2x2 diagonal block of a modal system's exact step: its states
/// `first..first + size`, its block of Phi (row-major) and of Gamma1 and Gamma2.
#[derive(Clone, Debug)]
pub struct ModalBlock {
    first: usize,
    size: usize,
    phi: [f64; 4],
    gamma1: [f64; 2],
    gamma2: [f64; 2],
}

/// The exact step x1 = Phi x0 + Gamma1 u0 + Gamma2 (u1 - u0) of a SISO system over
/// a fixed h, stored as cheaply as the realisation allows.
#[derive(Clone, Debug)]
pub enum Stepper {
    /// Canonical (companion) form: a dense Phi, O(n^2) per step.
    Dense {
        /// Transition matrix Phi = exp(A h).
        phi: DMatrix<f64>,
        /// Input vector Gamma1 of the held input u0.
        gamma1: DVector<f64>,
        /// Input vector Gamma2 of the input's change over the step.
        gamma2: DVector<f64>,
        /// Scratch for the step (no allocation).
        scratch: DVector<f64>,
    },
    /// Modal form: each block advances on its own, O(n) per step.
    Modal(Vec<ModalBlock>),
}

impl Stepper {
    /// Advances x over the step for an input ramped from u0 to u1.
    pub fn advance(&mut self, x: &mut DVector<f64>, u0: f64, u1: f64) {
        let du = u1 - u0;
        match self {
            Stepper::Dense {
                phi,
                gamma1,
                gamma2,
                scratch,
            } => {
                scratch.gemv(1.0, phi, x, 0.0);
                scratch.axpy(u0, gamma1, 1.0);
                scratch.axpy(du, gamma2, 1.0);
                std::mem::swap(scratch, x);
            }
            Stepper::Modal(blocks) => {
                let x = x.as_mut_slice();
                for b in blocks.iter() {
                    let (p, g1, g2) = (&b.phi, &b.gamma1, &b.gamma2);
                    if b.size == 1 {
                        let x0 = &mut x[b.first];
                        *x0 = p[0] * *x0 + g1[0] * u0 + g2[0] * du;
                    } else {
                        let pair = &mut x[b.first..b.first + 2];
                        let (x0, x1) = (pair[0], pair[1]);
                        pair[0] = p[0] * x0 + p[1] * x1 + g1[0] * u0 + g2[0] * du;
                        pair[1] = p[2] * x0 + p[3] * x1 + g1[1] * u0 + g2[1] * du;
                    }
                }
            }
        }
    }
}
