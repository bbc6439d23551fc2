//! Hyper-reduction of the section reduced about its start
//! (`reduced_sampling`): energy-conserving sampling and weighting (ECSW;
//! Farhat, Avery, Chapman and Cortial 2014) of its restoring force.
//!
//! The restoring force is a sum of terms, each on a few DOFs: an element (its
//! internal force and drag, six DOFs) and a node on the seabed (its contact,
//! two). The projected force T^T g(q_s + T z, T z') is replaced by
//!   g_r = o + sum_k w_k T_k^T g_k(q_s,k + T_k z, T_k z')
//! over a sample of terms k with positive weights w_k, T_k the basis rows at
//! the term's DOFs and o the offset that makes it exact at the start state
//! (the equilibrium is kept to round-off); the Newton tangent is the same sum.
//! A Newton iteration then costs the sampled terms (18 m multiply-adds each
//! for their basis rows), not T z, T z' and T^T g (n m each) and the loop over
//! every element: it pays where the sample is under half the section.
//!
//! Training is online, so that it works wherever the section runs (a scene,
//! a study, an exported FMU): for its first `training` seconds the section
//! runs on every term and records its reduced state (z, z') at up to 100
//! evenly spaced step starts (at least 3: a shorter window records on); at
//! the window's end non-negative least squares (`crate::reduced::ecsw`, the
//! active set stopped at `tolerance`) picks the weights that reproduce the
//! free coordinates' force change g(q, v) - g(q_s, 0) over those states. The
//! records are the reduced section's own states: the ones the sample has to
//! reproduce. A term idle in the window (a node that never touched the
//! seabed) is not picked, so the window has to show the motions the section
//! will see; a stinger's rollers (they meet whichever
//! element passes over them) cannot be sampled and stop the run if they press
//! on the section. The step Jacobian ([`super::jacobian`]) is the sampled
//! force's: its tangent through the sample, the reactions' rows through the
//! end elements.

// Small dense term blocks read best indexed as in the formulas.
#![allow(clippy::needless_range_loop)]

use super::Reduction;
use super::products::{dot, times};
use crate::contract::UnitError;
use crate::integrators::hht::TangentScales;
use crate::nonlinear::NonlinearSection;
use crate::numerics::banded::SymmetricBand;
use crate::reduced::ecsw::nnls;
use nalgebra::DMatrix;
use serde::{Deserialize, Serialize};

/// Hyper-reduction of a reduced section (`reduced_sampling`): the section
/// runs on every element for `training` seconds from its start, recording its
/// reduced state, then on the elements and seabed nodes that non-negative
/// least squares picks to reproduce the projected forces of those states to
/// `tolerance` (relative).
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Sampling {
    /// The training window (s) from the section's start.
    pub training: f64,
    /// Relative residual of the trained forces (default 1e-3).
    #[serde(default = "default_sampling_tolerance")]
    pub tolerance: f64,
}

impl Sampling {
    /// The trained forces' relative residual when the scene gives none.
    pub const DEFAULT_TOLERANCE: f64 = 1e-3;
}

fn default_sampling_tolerance() -> f64 {
    Sampling::DEFAULT_TOLERANCE
}

/// Why a section over a stinger's rollers is not sampled.
const ROLLERS: &str = "reduced section: a stinger's roller presses on it, and sampled forces cannot hold a roller's (it meets whichever element passes over it): remove `reduced_sampling` (the `training` of a `reduced` fidelity) from a section that reaches the stinger";

/// The fewest recorded states a sample is trained on.
const FEWEST_RECORDS: usize = 3;

/// Most recorded states of the training window, evenly spaced over it.
const SNAPSHOTS: f64 = 100.0;

/// A part of the restoring force on a few DOFs: an element (its internal
/// force and drag, on its nodes' six DOFs) or a node on a continuous contact
/// surface (its contact force, on the node's x and z).
#[derive(Copy, Clone, Debug, PartialEq)]
enum Term {
    Element(usize),
    Node(usize),
}

impl Term {
    fn first_dof(self) -> usize {
        match self {
            Term::Element(e) => 3 * e,
            Term::Node(j) => 3 * j,
        }
    }

    fn dofs(self) -> usize {
        match self {
            Term::Element(_) => 6,
            Term::Node(_) => 2,
        }
    }
}

/// A term's force on its DOFs (N, N m) with its stiffness and damping
/// (dF/dq, dF/dv), in the term's own DOF order.
/// A term's DOFs' displacements and velocities, and the time (s).
type State<'a> = (&'a [f64; 6], &'a [f64; 6], f64);

struct Local {
    force: [f64; 6],
    stiffness: [[f64; 6]; 6],
    damping: [[f64; 6]; 6],
}

/// Where the sampling is: recording the section's states, or trained.
pub(super) enum Hyper {
    Training(Training),
    Sampled(Sample),
}

/// The training window's records.
pub(super) struct Training {
    tolerance: f64,
    /// The window's end and the next record's time (s).
    end: f64,
    next: f64,
    every: f64,
    /// (z, z') at each recorded step start (2 m values each).
    snapshots: Vec<Vec<f64>>,
}

/// The trained sample: its terms, weights and basis rows, and the offset
/// that makes the sampled force exact at the start state.
pub(super) struct Sample {
    terms: Vec<SampledTerm>,
    offset: Vec<f64>,
    /// K R of one term (6 x m), for the tangent.
    scratch: Vec<f64>,
    /// Terms the sample could have picked from.
    candidates: usize,
}

struct SampledTerm {
    term: Term,
    weight: f64,
    /// The basis rows at the term's DOFs, row-major (dofs x m).
    rows: Vec<f64>,
    /// q_s at the term's DOFs (m, rad).
    start: [f64; 6],
}

impl Hyper {
    /// Recording from `t0` (s), the section's start.
    pub(super) fn new(sampling: &Sampling, t0: f64) -> Hyper {
        Hyper::Training(Training {
            tolerance: sampling.tolerance,
            end: t0 + sampling.training,
            next: t0,
            every: sampling.training / SNAPSHOTS,
            snapshots: Vec::new(),
        })
    }

    /// The sampled terms and the terms they were picked from, once trained.
    pub(super) fn size(&self) -> Option<(usize, usize)> {
        match self {
            Hyper::Sampled(s) => Some((s.terms.len(), s.candidates)),
            Hyper::Training(_) => None,
        }
    }
}

impl NonlinearSection {
    /// Before a reduced step from `t0` (s; step `h`): records the state while
    /// training, and trains the sample at the window's end.
    pub(super) fn advance_sampling(
        &self,
        r: &mut Reduction,
        t0: f64,
        h: f64,
    ) -> Result<(), UnitError> {
        let training = match r.hyper.as_mut() {
            Some(Hyper::Training(training)) => training,
            Some(Hyper::Sampled(_)) => return self.check_rollers(),
            None => return Ok(()),
        };
        let slack = 1e-9 * h;
        if t0 + slack >= training.next {
            training
                .snapshots
                .push(self.state.reduced[..2 * r.m].to_vec());
            training.next = t0 + training.every;
        }
        // A window shorter than a few steps (or a state restored past it
        // into a new instance) records on until it holds a few states.
        if t0 + slack < training.end || training.snapshots.len() < FEWEST_RECORDS {
            return Ok(());
        }
        let mut sample = self.train(r)?;
        // The frozen Newton tangent becomes the sample's at the start, so
        // that Newton's first iterations converge on the force they solve.
        let rest = vec![0.0; r.m];
        let mut force = vec![0.0; r.m];
        let at = (rest.as_slice(), rest.as_slice(), self.state.t);
        for (stiffness, damping, frozen) in [
            (1.0, 0.0, &mut r.stiffness),
            (0.0, 1.0, &mut r.drag_damping),
        ] {
            let scales = TangentScales { stiffness, damping };
            sample.force(self, at, 1.0, Some((scales, frozen)), &mut force);
        }
        r.hht.forget_matrices();
        r.hyper = Some(Hyper::Sampled(sample));
        Ok(())
    }

    /// Refuses a state where a stinger's roller presses on the section: the
    /// sample does not hold that force.
    fn check_rollers(&self) -> Result<(), UnitError> {
        let s = &self.state;
        match (self.environment.contacts).rollers_press(&self.model, (&s.q, s.t, &s.lambda)) {
            true => Err(UnitError::Numerical(ROLLERS.into())),
            false => Ok(()),
        }
    }

    /// Every term of the section: its elements, and its nodes where it has
    /// contact surfaces.
    fn terms(&self) -> Vec<Term> {
        let elements = (0..self.model.elements.len()).map(Term::Element);
        let nodes = match self.environment.contacts.is_empty() {
            true => 0,
            false => self.model.reference.len(),
        };
        elements.chain((0..nodes).map(Term::Node)).collect()
    }

    /// A term's force at its DOFs' displacements and velocities `q`, `v` at
    /// time `t` (s), with its stiffness and damping when `tangent`.
    fn term_force(&self, term: Term, (q, v, t): State<'_>, tangent: bool) -> Local {
        let mut local = Local {
            force: [0.0; 6],
            stiffness: [[0.0; 6]; 6],
            damping: [[0.0; 6]; 6],
        };
        match term {
            Term::Element(e) => {
                let (f, k) = self.model.elements[e].force(self.model.formulation, q, tangent);
                (local.force, local.stiffness) = (f, k);
                let env = &self.environment;
                let (drag, c) = env.element_drag(&self.model, e, (q, v), tangent);
                // Half the drag to each node; each node's velocity enters with 1/2.
                for a in [0, 3] {
                    for r in 0..2 {
                        local.force[a + r] += 0.5 * drag[r];
                        for b in [0, 3] {
                            for s in 0..2 {
                                local.damping[a + r][b + s] += 0.25 * c[r][s];
                            }
                        }
                    }
                }
            }
            Term::Node(j) => {
                let contacts = &self.environment.contacts;
                let at = ([q[0], q[1]], t);
                let (f, k) = contacts.node_force(&self.model, j, at, &self.state.lambda);
                for a in 0..2 {
                    local.force[a] = f[a];
                    local.stiffness[a][..2].copy_from_slice(&k[a]);
                }
            }
        }
        local
    }

    /// The sample trained on the window's records (see the module's notes).
    fn train(&self, r: &Reduction) -> Result<Sample, UnitError> {
        let Some(Hyper::Training(training)) = r.hyper.as_ref() else {
            return Err(UnitError::State("a sample trained twice".into()));
        };
        let (m, free) = (r.m, r.m - r.held.len());
        let terms = self.terms();
        let rows: Vec<Vec<f64>> = terms.iter().map(|&t| rows_of(r, t)).collect();
        let starts: Vec<[f64; 6]> = terms.iter().map(|&t| gather(&r.start, t)).collect();
        let rest = [0.0; 6];
        let at_start: Vec<[f64; 6]> = (terms.iter().zip(&starts))
            .map(|(&term, q)| self.term_force(term, (q, &rest, self.state.t), false).force)
            .collect();
        // Each term's force at the start, projected: R^T g(q_s) (m values).
        let projected: Vec<Vec<f64>> = (0..terms.len())
            .map(|c| project_local(&rows[c], terms[c].dofs(), &at_start[c]))
            .collect();
        let records = &training.snapshots;
        let g = self.training_matrix(r, (&terms, &rows, &at_start), records)?;
        let b = g.column_sum();
        // A change below 1e-9 of the start's forces on the free coordinates
        // is round-off of a section at rest.
        let scale = (0..free)
            .map(|i| projected.iter().map(|p| p[i].abs()).sum::<f64>().powi(2))
            .sum::<f64>()
            .sqrt();
        if b.norm() <= 1e-9 * scale * (records.len() as f64).sqrt() {
            return Err(UnitError::Numerical(format!(
                "reduced section: its forces did not change over the training window ({} states to t = {} s), so there is nothing to sample them by: lengthen `reduced_sampling.training` past the start of the motion",
                records.len(),
                training.end
            )));
        }
        let weights = nnls(&g, &b, training.tolerance, 3 * terms.len())?;
        // o = the sum over all terms of R^T g(q_s) less the sampled ones'.
        let mut offset = vec![0.0; m];
        let mut sampled = Vec::new();
        for (c, &term) in terms.iter().enumerate() {
            let share = 1.0 - weights[c];
            offset
                .iter_mut()
                .zip(&projected[c])
                .for_each(|(o, p)| *o += share * p);
            if weights[c] > 0.0 {
                sampled.push(SampledTerm {
                    term,
                    weight: weights[c],
                    rows: rows[c].clone(),
                    start: starts[c],
                });
            }
        }
        Ok(Sample {
            terms: sampled,
            offset,
            scratch: vec![0.0; 6 * m],
            candidates: terms.len(),
        })
    }

    /// ECSW's training matrix: row block k holds the free coordinates'
    /// rows of each term's projected force change R^T (g(q_k, v_k) -
    /// g(q_s, 0)) at record k, one column per term.
    fn training_matrix(
        &self,
        r: &Reduction,
        (terms, rows, at_start): (&[Term], &[Vec<f64>], &[[f64; 6]]),
        records: &[Vec<f64>],
    ) -> Result<DMatrix<f64>, UnitError> {
        let (n, m, free) = (r.n, r.m, r.m - r.held.len());
        let (t, contacts) = (self.state.t, &self.environment.contacts);
        let mut g = DMatrix::zeros(records.len() * free, terms.len());
        let (mut q, mut v) = (vec![0.0; n], vec![0.0; n]);
        for (k, record) in records.iter().enumerate() {
            q.copy_from_slice(&r.start);
            times(&r.basis, (n, m), &record[..m], &mut q);
            v.fill(0.0);
            times(&r.basis, (n, m), &record[m..], &mut v);
            if contacts.rollers_press(&self.model, (&q, t, &self.state.lambda)) {
                return Err(UnitError::Numerical(ROLLERS.into()));
            }
            for (c, &term) in terms.iter().enumerate() {
                let at = (&gather(&q, term), &gather(&v, term), t);
                let mut change = self.term_force(term, at, false).force;
                change
                    .iter_mut()
                    .zip(&at_start[c])
                    .for_each(|(f, s)| *f -= s);
                let projected = project_local(&rows[c], term.dofs(), &change);
                for i in 0..free {
                    g[(k * free + i, c)] = projected[i];
                }
            }
        }
        Ok(g)
    }
}

impl Sample {
    /// `scale` times the sampled reduced force at (z, z') at time `t` (s) into `out` (m
    /// values), and with `tangent` its stiffness and damping scaled as the
    /// integrator asks, summed into `projected` (m x m, row-major).
    pub(super) fn force(
        &mut self,
        section: &NonlinearSection,
        (z, zv, t): (&[f64], &[f64], f64),
        scale: f64,
        mut tangent: Option<(TangentScales, &mut Vec<f64>)>,
        out: &mut [f64],
    ) {
        let m = self.offset.len();
        out.iter_mut()
            .zip(&self.offset)
            .for_each(|(o, f)| *o = scale * f);
        if let Some((_, projected)) = tangent.as_mut() {
            projected.clear();
            projected.resize(m * m, 0.0);
        }
        for term in &self.terms {
            let dofs = term.term.dofs();
            let local = term.at(section, (z, zv, t), tangent.is_some());
            for a in 0..dofs {
                let f = scale * term.weight * local.force[a];
                let row = &term.rows[a * m..(a + 1) * m];
                out.iter_mut().zip(row).for_each(|(o, t)| *o += f * t);
            }
            if let Some((scales, projected)) = tangent.as_mut() {
                add_projected(term, &local, *scales, &mut self.scratch, projected);
            }
        }
    }
}

impl Sample {
    /// The sampled tangents at the section's state, for its step Jacobian:
    /// K_r + `c` C_r into `combined` and the columns `from..m` of C_r (the
    /// drag's damping) into `damping` (both m x m, row-major; the rest of
    /// `damping` zero). Each sampled term is evaluated once.
    pub(super) fn tangents(
        &mut self,
        section: &NonlinearSection,
        c: f64,
        from: usize,
        (combined, damping): (&mut Vec<f64>, &mut Vec<f64>),
    ) {
        let m = self.offset.len();
        let s = &section.state;
        let at = (&s.reduced[..m], &s.reduced[m..2 * m], s.t);
        let scales = TangentScales {
            stiffness: 1.0,
            damping: c,
        };
        for out in [&mut *combined, &mut *damping] {
            out.clear();
            out.resize(m * m, 0.0);
        }
        for term in &self.terms {
            let local = term.at(section, at, true);
            add_projected(term, &local, scales, &mut self.scratch, combined);
            if !matches!(term.term, Term::Element(_)) {
                continue;
            }
            for j in from..m {
                let mut cr = [0.0; 6];
                for (a, out) in cr.iter_mut().enumerate() {
                    *out = (0..6)
                        .map(|b| local.damping[a][b] * term.rows[b * m + j])
                        .sum();
                }
                for i in 0..m {
                    let value: f64 = (0..6).map(|a| term.rows[a * m + i] * cr[a]).sum();
                    damping[i * m + j] += term.weight * value;
                }
            }
        }
    }
}

impl SampledTerm {
    /// The term's force (with its tangents when `tangent`) at the reduced
    /// state (z, z') at time t (s): its DOFs' values q_s + T_k z, T_k z'.
    fn at(
        &self,
        section: &NonlinearSection,
        (z, zv, t): (&[f64], &[f64], f64),
        tangent: bool,
    ) -> Local {
        let m = z.len();
        let (mut q, mut v) = (self.start, [0.0; 6]);
        for a in 0..self.term.dofs() {
            let row = &self.rows[a * m..(a + 1) * m];
            q[a] += dot(row, z);
            v[a] = dot(row, zv);
        }
        section.term_force(self.term, (&q, &v, t), tangent)
    }
}

impl NonlinearSection {
    /// Adds the full tangent stiffness and drag damping of the terms at the
    /// section's end nodes (its first and last elements, its end nodes'
    /// contact) at its state to `stiffness` and `damping`: all that the
    /// reactions' rows of the step Jacobian read.
    pub(super) fn add_end_tangents(
        &self,
        stiffness: &mut SymmetricBand,
        damping: &mut SymmetricBand,
    ) {
        let (elements, nodes) = (self.model.elements.len(), self.model.reference.len());
        let mut ends = vec![Term::Element(0), Term::Element(elements - 1)];
        if !self.environment.contacts.is_empty() {
            ends.extend([Term::Node(0), Term::Node(nodes - 1)]);
        }
        let s = &self.state;
        for term in ends {
            let (q, v) = (gather(&s.q, term), gather(&s.v, term));
            let local = self.term_force(term, (&q, &v, s.t), true);
            let first = term.first_dof();
            for a in 0..term.dofs() {
                for b in 0..=a {
                    stiffness.add(first + a, first + b, local.stiffness[a][b]);
                    damping.add(first + a, first + b, local.damping[a][b]);
                }
            }
        }
    }
}

/// Adds w R^T (k K + c C) R of one term to `projected` (m x m, row-major),
/// with `scratch` (6 x m) for the product's right half.
fn add_projected(
    term: &SampledTerm,
    local: &Local,
    scales: TangentScales,
    scratch: &mut [f64],
    projected: &mut [f64],
) {
    let (dofs, m) = (term.term.dofs(), term.rows.len() / term.term.dofs());
    for a in 0..dofs {
        let out = &mut scratch[a * m..(a + 1) * m];
        out.fill(0.0);
        for b in 0..dofs {
            let k = scales.stiffness * local.stiffness[a][b] + scales.damping * local.damping[a][b];
            if k != 0.0 {
                let row = &term.rows[b * m..(b + 1) * m];
                out.iter_mut().zip(row).for_each(|(o, t)| *o += k * t);
            }
        }
    }
    for a in 0..dofs {
        let row = &term.rows[a * m..(a + 1) * m];
        let kr = &scratch[a * m..(a + 1) * m];
        for (i, &ti) in row.iter().enumerate() {
            let wt = term.weight * ti;
            if wt != 0.0 {
                let line = &mut projected[i * m..(i + 1) * m];
                line.iter_mut().zip(kr).for_each(|(p, k)| *p += wt * k);
            }
        }
    }
}

/// R^T f for a term's basis rows `rows` (dofs x m, row-major) and its
/// force `f` on its `dofs` DOFs.
fn project_local(rows: &[f64], dofs: usize, f: &[f64; 6]) -> Vec<f64> {
    let m = rows.len() / dofs;
    (0..m)
        .map(|i| (0..dofs).map(|a| rows[a * m + i] * f[a]).sum())
        .collect()
}

/// The basis rows at a term's DOFs, row-major (dofs x m).
fn rows_of(r: &Reduction, term: Term) -> Vec<f64> {
    let (n, m, first) = (r.n, r.m, term.first_dof());
    let mut rows = vec![0.0; term.dofs() * m];
    for a in 0..term.dofs() {
        for i in 0..m {
            rows[a * m + i] = r.basis[i * n + first + a];
        }
    }
    rows
}

/// A term's values of a full vector (the rest zero).
fn gather(full: &[f64], term: Term) -> [f64; 6] {
    let mut out = [0.0; 6];
    let first = term.first_dof();
    out[..term.dofs()].copy_from_slice(&full[first..first + term.dofs()]);
    out
}
