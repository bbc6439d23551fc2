//! The mesh of a nonlinear section and its assembled quantities: internal force
//! and tangent, mass, nodal loads, and the element forces at stations.
//!
//! Nodes carry three DOFs `[u, w, theta]` (displacement from the stress-free
//! position in x and z, m; rotation, rad); elements form a chain, so every matrix
//! is banded with half-bandwidth 5.

// Small dense element blocks read best indexed as in the formulas.
#![allow(clippy::needless_range_loop)]

use super::element::{Element, ElementState, Formulation, LocalForces};
use super::params::{MassKind, NonlinearParams, Segment};
use crate::numerics::banded::SymmetricBand;

/// Half-bandwidth of the assembled matrices.
pub const BAND: usize = 5;

/// The discretised structure.
#[derive(Clone, Debug)]
pub struct Model {
    /// How the elements' forces are computed.
    pub formulation: Formulation,
    /// The elements, from the start.
    pub elements: Vec<Element>,
    /// Segment of each element.
    pub segment_of: Vec<usize>,
    /// Stress-free node positions (m).
    pub reference: Vec<[f64; 2]>,
    /// Arc length of each node (m), unstretched.
    pub arc: Vec<f64>,
    /// The shortest element (m): the most a Newton correction moves a node.
    shortest: f64,
    /// A linear section's axial forces, linear in each element's DOFs about
    /// the static state (`linear.rs`); none for a nonlinear one.
    pub linear_axial: Option<Vec<LinearAxial>>,
}

/// An element's axial force linearised about the static state: N = `axial`
/// + `gradient` . (q_e - `at`) (N; the gradient in N/m and N/rad).
#[derive(Clone, Debug, PartialEq)]
pub struct LinearAxial {
    /// The element's six DOFs at the static state (m, rad).
    pub at: [f64; 6],
    /// The axial force there (N).
    pub axial: f64,
    /// Its derivative with respect to each DOF.
    pub gradient: [f64; 6],
}

/// The six DOFs of element `e` in `q`.
pub fn element_dofs(q: &[f64], e: usize) -> [f64; 6] {
    let mut p = [0.0; 6];
    p.copy_from_slice(&q[3 * e..3 * e + 6]);
    p
}

impl Model {
    /// The mesh of `params` (validated).
    pub fn new(params: &NonlinearParams) -> Model {
        let mut elements = Vec::new();
        let mut segment_of = Vec::new();
        let mut reference = vec![params.start];
        let mut arc = vec![0.0];
        for (i, s) in params.segments.iter().enumerate() {
            let (sin0, cos0) = s.angle_deg.to_radians().sin_cos();
            let l = s.length / s.elements as f64;
            for _ in 0..s.elements {
                let (ea, ei) = (s.axial_stiffness, s.bending_stiffness);
                elements.push(Element::new(l, (cos0, sin0), ea, ei));
                segment_of.push(i);
                let [x, z] = reference[reference.len() - 1];
                reference.push([x + l * cos0, z + l * sin0]);
                arc.push(arc[arc.len() - 1] + l);
            }
        }
        let shortest = elements.iter().fold(f64::INFINITY, |m, e| m.min(e.length));
        Model {
            formulation: params.formulation,
            elements,
            segment_of,
            reference,
            arc,
            shortest,
            linear_axial: None,
        }
    }

    /// The factor (at most 1) that keeps a Newton correction `dq` within the
    /// shortest element's length per node and 0.5 rad per rotation.
    pub fn correction_limit(&self, dq: &[f64]) -> f64 {
        dq.chunks(3).fold(1.0f64, |f, c| {
            let moved = c[0].hypot(c[1]);
            let f = if moved > self.shortest {
                f.min(self.shortest / moved)
            } else {
                f
            };
            if c[2].abs() > 0.5 {
                f.min(0.5 / c[2].abs())
            } else {
                f
            }
        })
    }

    /// Whether a correction no entry of which exceeds `largest` (m or rad)
    /// is surely within [`Model::correction_limit`] (its factor 1), with a
    /// margin over the sqrt(2) of a node's two translations.
    pub fn surely_within_correction_limit(&self, largest: f64) -> bool {
        1.5 * largest <= self.shortest.min(0.5)
    }

    /// Number of DOFs.
    pub fn dofs(&self) -> usize {
        3 * self.reference.len()
    }

    /// Adds the internal force at `q` to `out`, times `scale`; with `tangent`, adds
    /// the tangent stiffness times its factor to the band.
    pub fn add_internal_force(
        &self,
        q: &[f64],
        scale: f64,
        mut tangent: Option<(&mut SymmetricBand, f64)>,
        out: &mut [f64],
    ) {
        let want = tangent.is_some();
        for (e, element) in self.elements.iter().enumerate() {
            let (f, k) = element.force(self.formulation, &element_dofs(q, e), want);
            let base = 3 * e;
            for i in 0..6 {
                out[base + i] += scale * f[i];
            }
            if let Some((band, factor)) = tangent.as_mut() {
                for i in 0..6 {
                    for j in 0..=i {
                        band.add(base + i, base + j, *factor * k[i][j]);
                    }
                }
            }
        }
    }

    /// Adds the internal force at `q` to `out` and keeps each element's
    /// state (local forces, strain energy) in `states`: one evaluation of
    /// every element for what a step's end reads.
    pub fn add_internal_force_keeping(
        &self,
        q: &[f64],
        out: &mut [f64],
        states: &mut Vec<ElementState>,
    ) {
        states.clear();
        for e in 0..self.elements.len() {
            states.push(self.add_element_force(e, q, out));
        }
    }

    /// Adds element `e`'s internal force at `q` to `out` as
    /// [`Self::add_internal_force_keeping`] adds it, and returns its state.
    pub fn add_element_force(&self, e: usize, q: &[f64], out: &mut [f64]) -> ElementState {
        let state = self.elements[e].evaluate(self.formulation, &element_dofs(q, e));
        for (o, f) in out[3 * e..3 * e + 6].iter_mut().zip(&state.force) {
            *o += f;
        }
        state
    }

    /// The elements at the two ends (the first `count` of them: one where
    /// the model has a single element): the only ones that load the end
    /// nodes.
    pub fn end_elements(&self) -> ([usize; 2], usize) {
        let last = self.elements.len().saturating_sub(1);
        ([0, last], if last == 0 { 1 } else { 2 })
    }

    /// Adds `scale` times the discrete gradient of the strain energy between `q0`
    /// and `q1` (Gonzalez 1996, element by element: the midpoint force plus the
    /// correction that makes `g . (q1 - q0) = U(q1) - U(q0)` exactly) to `out`, and
    /// half the tangent at the midpoint times `factor` to the band (Newton on the
    /// leading term).
    pub fn add_discrete_gradient(
        &self,
        (q0, q1): (&[f64], &[f64]),
        scale: f64,
        mut tangent: Option<(&mut SymmetricBand, f64)>,
        out: &mut [f64],
    ) {
        for (e, element) in self.elements.iter().enumerate() {
            let (p0, p1) = (element_dofs(q0, e), element_dofs(q1, e));
            let mid: [f64; 6] = std::array::from_fn(|i| 0.5 * (p0[i] + p1[i]));
            let (f, k) = element.force(self.formulation, &mid, tangent.is_some());
            let delta: [f64; 6] = std::array::from_fn(|i| p1[i] - p0[i]);
            let norm2: f64 = delta.iter().map(|d| d * d).sum();
            let work: f64 = f.iter().zip(&delta).map(|(a, b)| a * b).sum();
            let correction = if norm2 > 1e-30 {
                let du = element.strain_energy(self.formulation, &p1)
                    - element.strain_energy(self.formulation, &p0);
                (du - work) / norm2
            } else {
                0.0
            };
            let base = 3 * e;
            for i in 0..6 {
                out[base + i] += scale * (f[i] + correction * delta[i]);
            }
            if let Some((band, factor)) = tangent.as_mut() {
                for i in 0..6 {
                    for j in 0..=i {
                        band.add(base + i, base + j, 0.5 * *factor * k[i][j]);
                    }
                }
            }
        }
    }

    /// Axial force, end moments and chord of every element at `q`; a
    /// linear section's axial force from its linearisation (the element's own
    /// on the linear state would count a rotation of its chord as stretch).
    pub fn local_forces(&self, q: &[f64], e: usize) -> LocalForces {
        let dofs = element_dofs(q, e);
        let mut local = self.elements[e].local_forces(self.formulation, &dofs);
        if let Some(linear) = &self.linear_axial {
            let l = &linear[e];
            let change: f64 = (0..6).map(|i| l.gradient[i] * (dofs[i] - l.at[i])).sum();
            local.axial = l.axial + change;
        }
        local
    }

    /// Each element's axial force linearised at `q` (central differences,
    /// 1e-6 m or rad).
    pub fn linearise_axial(&self, q: &[f64]) -> Vec<LinearAxial> {
        const H: f64 = 1e-6;
        (0..self.elements.len())
            .map(|e| {
                let at = element_dofs(q, e);
                let axial_at =
                    |dofs: &[f64; 6]| (self.elements[e].local_forces(self.formulation, dofs)).axial;
                let gradient = std::array::from_fn(|i| {
                    let (mut up, mut down) = (at, at);
                    up[i] += H;
                    down[i] -= H;
                    (axial_at(&up) - axial_at(&down)) / (2.0 * H)
                });
                LinearAxial {
                    at,
                    axial: axial_at(&at),
                    gradient,
                }
            })
            .collect()
    }

    /// The mass matrix (structural plus added mass of `segments`, water density
    /// `rho` in kg/m^3), each element in the frame of its chord at `q`.
    pub fn mass(&self, q: &[f64], segments: &[Segment], kind: MassKind, rho: f64) -> SymmetricBand {
        let mut m = SymmetricBand::zeros(self.dofs(), BAND);
        for (e, element) in self.elements.iter().enumerate() {
            let s = &segments[self.segment_of[e]];
            let area = std::f64::consts::PI * s.diameter * s.diameter / 4.0;
            let axial = s.mass_per_length + rho * area * s.added_mass_tangential;
            let normal = s.mass_per_length + rho * area * s.added_mass_normal;
            let local = self.local_forces(q, e);
            let (c, sn) = match self.formulation {
                Formulation::Corotational => (local.direction[0], local.direction[1]),
                Formulation::Seed002 => (element.cos0, element.sin0),
            };
            let block = element_mass(element.length, axial, normal, kind);
            add_rotated(&mut m, 3 * e, &block, c, sn);
        }
        m
    }

    /// Nodal loads of a distributed load (N/m, global x and z) on the elements
    /// whose midpoint lies in [from, to], added to `out`: translations only for
    /// the co-rotational element (its large rotations make end moments of a fixed
    /// frame wrong), consistent (with end moments, stress-free frame) for seed 002.
    pub fn add_distributed(&self, load: [f64; 2], range: (f64, f64), out: &mut [f64]) {
        for (e, element) in self.elements.iter().enumerate() {
            let mid = 0.5 * (self.arc[e] + self.arc[e + 1]);
            if mid < range.0 || mid > range.1 {
                continue;
            }
            let l = element.length;
            let base = 3 * e;
            for node in [0, 3] {
                out[base + node] += 0.5 * l * load[0];
                out[base + node + 1] += 0.5 * l * load[1];
            }
            if self.formulation == Formulation::Seed002 {
                let normal = -element.sin0 * load[0] + element.cos0 * load[1];
                out[base + 2] += normal * l * l / 12.0;
                out[base + 5] -= normal * l * l / 12.0;
            }
        }
    }

    /// Current node positions (m) at `q`.
    pub fn positions(&self, q: &[f64]) -> Vec<[f64; 2]> {
        self.reference
            .iter()
            .enumerate()
            .map(|(j, r)| [r[0] + q[3 * j], r[1] + q[3 * j + 1]])
            .collect()
    }

    /// Position (m) at arc length `s` under displacements `q`, linear between
    /// the nodes.
    pub fn position_at(&self, q: &[f64], s: f64) -> [f64; 2] {
        let (e, xi) = self.locate(s);
        let (r0, r1) = (self.reference[e], self.reference[e + 1]);
        let at = |k: usize| (1.0 - xi) * (r0[k] + q[3 * e + k]) + xi * (r1[k] + q[3 * e + 3 + k]);
        [at(0), at(1)]
    }

    /// The element holding arc length `s` and the coordinate in it, in [0, 1].
    pub fn locate(&self, s: f64) -> (usize, f64) {
        let last = self.elements.len() - 1;
        let e = (self.arc.partition_point(|&a| a <= s))
            .saturating_sub(1)
            .min(last);
        (
            e,
            ((s - self.arc[e]) / self.elements[e].length).clamp(0.0, 1.0),
        )
    }
}

/// The 6x6 element mass in the element frame: linear axial (mass `axial`), Hermite
/// transverse (mass `normal`, kg/m); lumped: half each to the nodes, rotary
/// `normal l^3 / 78` (HRZ).
fn element_mass(l: f64, axial: f64, normal: f64, kind: MassKind) -> [[f64; 6]; 6] {
    let mut m = [[0.0; 6]; 6];
    match kind {
        MassKind::Consistent => {
            let a = axial * l / 6.0;
            m[0][0] = 2.0 * a;
            m[3][3] = 2.0 * a;
            m[0][3] = a;
            m[3][0] = a;
            let t = normal * l / 420.0;
            let h = [
                [156.0, 22.0 * l, 54.0, -13.0 * l],
                [22.0 * l, 4.0 * l * l, 13.0 * l, -3.0 * l * l],
                [54.0, 13.0 * l, 156.0, -22.0 * l],
                [-13.0 * l, -3.0 * l * l, -22.0 * l, 4.0 * l * l],
            ];
            let idx = [1, 2, 4, 5];
            for i in 0..4 {
                for j in 0..4 {
                    m[idx[i]][idx[j]] = t * h[i][j];
                }
            }
        }
        MassKind::Lumped => {
            for node in [0, 3] {
                m[node][node] = 0.5 * axial * l;
                m[node + 1][node + 1] = 0.5 * normal * l;
                m[node + 2][node + 2] = normal * l.powi(3) / 78.0;
            }
        }
    }
    m
}

/// Adds T^T m T (T the rotation by (c, s) of each node's translations) at `base`.
fn add_rotated(band: &mut SymmetricBand, base: usize, m: &[[f64; 6]; 6], c: f64, s: f64) {
    let t = super::element::rotation(c, s);
    for i in 0..6 {
        for j in 0..=i {
            let mut v = 0.0;
            for a in 0..6 {
                for b in 0..6 {
                    v += t[a][i] * m[a][b] * t[b][j];
                }
            }
            band.add(base + i, base + j, v);
        }
    }
}
