//! The line's own mechanics, rotation-free: nodes with three translations,
//! straight bars between them for the axial force (EA, and an axial damper
//! BA), and at every inner node a bending energy from the angle between its
//! two bars, `EI / L0 (1 - t1 . t2)` (= EI phi^2 / (2 L0) for small angles,
//! the curvature `|t2 - t1| / L0`), as MoorDyn v2's rods and discrete elastic
//! rods have it. With torsion left out, an isotropic line's bending energy
//! depends on its centreline alone, so no rotation is a degree of freedom;
//! the forces and their exact tangents are in this file.

use crate::numerics::banded::SymmetricBand;
use nalgebra::{Matrix3, Vector3};

/// DOFs per node (x, y, z).
pub const DOF: usize = 3;
/// Half-bandwidth of the line's matrices: a bending triple couples node i
/// with node i + 2.
pub const BAND: usize = 3 * DOF - 1;

/// The mesh and the section's stiffness.
#[derive(Clone, Debug)]
pub struct Mechanics {
    /// Nodes (elements + 1).
    pub nodes: usize,
    /// Unstretched element length (m).
    pub element_length: f64,
    /// EA (N), EI (N m^2), BA (N s).
    pub axial_stiffness: f64,
    /// EI (N m^2).
    pub bending_stiffness: f64,
    /// BA (N s).
    pub axial_damping: f64,
}

/// Node `i`'s position (or velocity) in `q`.
pub fn node(q: &[f64], i: usize) -> Vector3<f64> {
    Vector3::new(q[DOF * i], q[DOF * i + 1], q[DOF * i + 2])
}

/// Adds `s * m` to the band block of nodes (a, b), a <= b (the symmetric
/// partner is implied; a diagonal block adds its lower triangle).
pub fn add_block(band: &mut SymmetricBand, a: usize, b: usize, m: &Matrix3<f64>, s: f64) {
    for r in 0..DOF {
        for c in 0..DOF {
            if a == b && c > r {
                continue;
            }
            band.add(DOF * a + r, DOF * b + c, s * m[(r, c)]);
        }
    }
}

/// Adds `s * f` to node `i`'s entries of `out`.
pub fn add_node(out: &mut [f64], i: usize, f: &Vector3<f64>, s: f64) {
    for k in 0..DOF {
        out[DOF * i + k] += s * f[k];
    }
}

/// The projector on the plane normal to the unit vector `t`.
pub fn normal_projector(t: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::identity() - t * t.transpose()
}

/// How the force's derivatives enter a Newton matrix: (band, stiffness
/// factor, damping factor).
pub type Tangent<'a> = Option<(&'a mut SymmetricBand, f64, f64)>;

impl Mechanics {
    /// Tension of element `e` (N): EA strain plus BA strain rate (bars take
    /// compression: a slack chain buckles as its nodes let it).
    pub fn tension(&self, q: &[f64], v: &[f64], e: usize) -> f64 {
        let d = node(q, e + 1) - node(q, e);
        let l = d.norm();
        let rate = d.dot(&(node(v, e + 1) - node(v, e))) / l;
        let l0 = self.element_length;
        (self.axial_stiffness * (l - l0) + self.axial_damping * rate) / l0
    }

    /// Curvature at inner node `i` (1/m): |t2 - t1| / L0.
    pub fn curvature(&self, q: &[f64], i: usize) -> f64 {
        let t1 = (node(q, i) - node(q, i - 1)).normalize();
        let t2 = (node(q, i + 1) - node(q, i)).normalize();
        (t2 - t1).norm() / self.element_length
    }

    /// Power of the axial dampers on the nodes (W, negative: what they remove).
    pub fn damper_power(&self, q: &[f64], v: &[f64]) -> f64 {
        if self.axial_damping == 0.0 {
            return 0.0;
        }
        let l0 = self.element_length;
        (0..self.nodes - 1)
            .map(|e| {
                let d = node(q, e + 1) - node(q, e);
                let l = d.norm();
                let rate = (d / l).dot(&(node(v, e + 1) - node(v, e)));
                -self.axial_damping * rate * rate / l0
            })
            .sum()
    }

    /// Strain energy (J): axial and bending.
    pub fn strain_energy(&self, q: &[f64]) -> f64 {
        let l0 = self.element_length;
        let axial: f64 = (0..self.nodes - 1)
            .map(|e| {
                let l = (node(q, e + 1) - node(q, e)).norm();
                0.5 * self.axial_stiffness * (l - l0).powi(2) / l0
            })
            .sum();
        let bending: f64 = (1..self.nodes - 1)
            .map(|i| 0.5 * self.bending_stiffness * l0 * self.curvature(q, i).powi(2))
            .sum();
        axial + bending
    }

    /// Adds `scale` times the internal force (the energy's gradient plus the
    /// axial damper) at (q, v) to `force`, and its tangent to the band.
    pub fn add_force(
        &self,
        q: &[f64],
        v: &[f64],
        scale: f64,
        mut tangent: Tangent<'_>,
        force: &mut [f64],
    ) {
        for e in 0..self.nodes - 1 {
            self.add_bar(
                q,
                v,
                e,
                scale,
                tangent.as_mut().map(|(b, k, c)| (&mut **b, *k, *c)),
                force,
            );
        }
        if self.bending_stiffness > 0.0 {
            for i in 1..self.nodes - 1 {
                let band = tangent.as_mut().map(|(b, k, _)| (&mut **b, *k));
                self.add_bend(q, i, scale, band, force);
            }
        }
    }

    /// Element `e`: force T t on its end node, -T t on its start node;
    /// stiffness EA/L0 t t^T + T_elastic / l (I - t t^T), damping BA/L0 t t^T.
    fn add_bar(
        &self,
        q: &[f64],
        v: &[f64],
        e: usize,
        scale: f64,
        tangent: Tangent<'_>,
        force: &mut [f64],
    ) {
        let d = node(q, e + 1) - node(q, e);
        let l = d.norm();
        let t = d / l;
        let l0 = self.element_length;
        let elastic = self.axial_stiffness * (l - l0) / l0;
        let rate = t.dot(&(node(v, e + 1) - node(v, e)));
        let damper = self.axial_damping / l0;
        let tension = elastic + damper * rate;
        add_node(force, e + 1, &t, scale * tension);
        add_node(force, e, &t, -scale * tension);
        if let Some((band, k, c)) = tangent {
            let tt = t * t.transpose();
            let stiffness = k
                * (self.axial_stiffness / l0 * tt + elastic / l * normal_projector(&t))
                + c * damper * tt;
            add_block(band, e, e, &stiffness, 1.0);
            add_block(band, e + 1, e + 1, &stiffness, 1.0);
            add_block(band, e, e + 1, &stiffness, -1.0);
        }
    }

    /// Inner node `i`: E = c (1 - t1 . t2), c = EI / L0, with e1 = x_i - x_{i-1}
    /// and e2 = x_{i+1} - x_i; the gradient and the exact Hessian of t1 . t2.
    fn add_bend(
        &self,
        q: &[f64],
        i: usize,
        scale: f64,
        tangent: Option<(&mut SymmetricBand, f64)>,
        force: &mut [f64],
    ) {
        let c = self.bending_stiffness / self.element_length;
        let e1 = node(q, i) - node(q, i - 1);
        let e2 = node(q, i + 1) - node(q, i);
        let (l1, l2) = (e1.norm(), e2.norm());
        let (t1, t2) = (e1 / l1, e2 / l2);
        let (p1, p2) = (normal_projector(&t1), normal_projector(&t2));
        // dE/de1 = -c P1 t2 / l1, dE/de2 = -c P2 t1 / l2.
        let g1 = -c * p1 * t2 / l1;
        let g2 = -c * p2 * t1 / l2;
        add_node(force, i - 1, &g1, -scale);
        add_node(force, i, &(g1 - g2), scale);
        add_node(force, i + 1, &g2, scale);
        let Some((band, k)) = tangent else {
            return;
        };
        let s = t1.dot(&t2);
        let h = |p: &Matrix3<f64>, t: &Vector3<f64>, a: &Vector3<f64>, l: f64| {
            let pa = p * a;
            -(s * p + t * pa.transpose() + pa * t.transpose()) / (l * l)
        };
        // Hessian of E over (e1, e2): -c times that of t1 . t2.
        let h11 = -c * h(&p1, &t1, &t2, l1);
        let h22 = -c * h(&p2, &t2, &t1, l2);
        let h12 = -c * (p1 * p2) / (l1 * l2);
        // Nodes (i-1, i, i+1) from (e1, e2): de1 = [-I, I, 0], de2 = [0, -I, I].
        let blocks = [
            (i - 1, i - 1, h11),
            (i - 1, i, -h11 + h12),
            (i - 1, i + 1, -h12),
            (i, i, h11 - h12 - h12.transpose() + h22),
            (i, i + 1, h12 - h22),
            (i + 1, i + 1, h22),
        ];
        for (a, b, m) in blocks {
            add_block(band, a, b, &m, k);
        }
    }
}
