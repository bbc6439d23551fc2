//! The 2D beam-column element in its two formulations: internal force and
//! tangent stiffness in global coordinates from the element's nodal
//! displacements `p = [u1, w1, theta1, u2, w2, theta2]` (m, m, rad; x horizontal,
//! z up, theta counter-clockwise).
//!
//! - [`Formulation::Corotational`]: a shallow-arch Euler-Bernoulli element in a
//!   frame that follows the chord (Crisfield 1991, ch. 7; Battini 2002): any rigid motion,
//!   however large, produces no force, and the local rotations are wrapped to
//!   (-pi, pi] so a node may turn any number of times.
//! - [`Formulation::Seed002`]: seed 002's kinematically nonlinear element (P2
//!   App. B): linear axial and Hermite transverse displacement in the undeformed
//!   element frame, strain `u' + w'^2 / 2`, curvature `w''`, so the restoring force
//!   is a cubic polynomial of the DOFs; five-point Gauss integrates it exactly
//!   (degree 8 in the element coordinate). Valid for moderate rotations.

// Small dense element blocks read best indexed as in the formulas.
#![allow(clippy::needless_range_loop)]

use serde::{Deserialize, Serialize};

/// Which element kinematics a section uses.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Formulation {
    /// Large displacements and rotations.
    #[default]
    Corotational,
    /// Moderate rotations, restoring force cubic in the DOFs (seed 002).
    Seed002,
}

/// An element's stress-free geometry and stiffness.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Element {
    /// Unstretched length (m).
    pub length: f64,
    /// Direction cosines of the stress-free chord.
    pub cos0: f64,
    /// Direction sine of the stress-free chord.
    pub sin0: f64,
    /// Axial stiffness EA (N) and bending stiffness EI (N m^2).
    pub ea: f64,
    /// Bending stiffness EI (N m^2).
    pub ei: f64,
    /// The stress-free chord's angle, atan2(sin0, cos0) (rad): kept, so
    /// that the corotational kinematics take one arctangent, not two.
    angle0: f64,
}

/// Internal force (N, N m) and tangent stiffness of one element, global frame.
pub type ElementForce = ([f64; 6], [[f64; 6]; 6]);

/// The element's axial force N (N) and end moments M1, M2 (N m, counter-clockwise
/// on the element), plus its current chord length (m) and angle (rad).
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct LocalForces {
    /// Axial force N (N, tension positive).
    pub axial: f64,
    /// End moments M1, M2 (N m, counter-clockwise on the element).
    pub moments: [f64; 2],
    /// Current chord length (m).
    pub chord: f64,
    /// Current chord angle (rad).
    pub angle: f64,
    /// Its cosine and sine (the chord over its length), kept so that a
    /// caller needs no trigonometry per element.
    pub direction: [f64; 2],
}

/// An element at a state: its internal force (N, N m, global frame), local
/// forces and strain energy (J).
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct ElementState {
    /// Internal force on the element's six DOFs.
    pub force: [f64; 6],
    /// Axial force, end moments and chord.
    pub local: LocalForces,
    /// Strain energy (J).
    pub strain_energy: f64,
}

/// Where a co-rotational element is: its local rotations (rad, wrapped to
/// (-pi, pi]), stretch (m), chord length (m) and chord angle (rad).
struct Kinematics {
    rotations: [f64; 2],
    stretch: f64,
    chord: f64,
    angle: f64,
    direction: [f64; 2],
}

/// Five-point Gauss-Legendre on [0, 1]: (abscissa, weight).
const GAUSS5: [(f64, f64); 5] = [
    (0.046_910_077_030_668_0, 0.118_463_442_528_094_5),
    (0.230_765_344_947_158_5, 0.239_314_335_249_683_2),
    (0.5, 0.284_444_444_444_444_4),
    (0.769_234_655_052_841_5, 0.239_314_335_249_683_2),
    (0.953_089_922_969_332, 0.118_463_442_528_094_5),
];

/// Wraps an angle to (-pi, pi].
fn wrap(angle: f64) -> f64 {
    use std::f64::consts::PI;
    let a = angle.rem_euclid(2.0 * PI);
    if a > PI { a - 2.0 * PI } else { a }
}

impl Element {
    /// An element of unstretched `length` (m) along the stress-free chord's
    /// direction `(cos0, sin0)`, of axial stiffness `ea` (N) and bending
    /// stiffness `ei` (N m^2).
    pub fn new(length: f64, (cos0, sin0): (f64, f64), ea: f64, ei: f64) -> Element {
        Element {
            length,
            cos0,
            sin0,
            ea,
            ei,
            angle0: sin0.atan2(cos0),
        }
    }

    /// Current chord (dx, dz) from the stress-free chord and the displacements.
    fn chord(&self, p: &[f64; 6]) -> (f64, f64) {
        (
            self.length * self.cos0 + p[3] - p[0],
            self.length * self.sin0 + p[4] - p[1],
        )
    }

    /// Axial force, end moments, chord length and angle at `p`.
    pub fn local_forces(&self, formulation: Formulation, p: &[f64; 6]) -> LocalForces {
        match formulation {
            Formulation::Corotational => self.corotational_local(&self.corotational_kinematics(p)),
            Formulation::Seed002 => self.seed002_local(p),
        }
    }

    /// Internal force and (with `tangent`) tangent stiffness at `p`.
    pub fn force(&self, formulation: Formulation, p: &[f64; 6], tangent: bool) -> ElementForce {
        match formulation {
            Formulation::Corotational => self.corotational(p, tangent),
            Formulation::Seed002 => self.seed002(p, tangent),
        }
    }

    /// Internal force, local forces and strain energy (J) at `p` from one
    /// evaluation of the element's kinematics: what a state's bookkeeping
    /// (reactions, extremes, energies) reads, as [`Element::force`],
    /// [`Element::local_forces`] and [`Element::strain_energy`] give it.
    pub fn evaluate(&self, formulation: Formulation, p: &[f64; 6]) -> ElementState {
        match formulation {
            Formulation::Corotational => {
                let kinematics = self.corotational_kinematics(p);
                let local = self.corotational_local(&kinematics);
                ElementState {
                    force: self.corotational_from(&kinematics, &local, false).0,
                    local,
                    strain_energy: self.corotational_energy(&kinematics),
                }
            }
            Formulation::Seed002 => ElementState {
                force: self.seed002(p, false).0,
                local: self.seed002_local(p),
                strain_energy: self.strain_energy(formulation, p),
            },
        }
    }

    /// Strain energy (J) at `p`.
    pub fn strain_energy(&self, formulation: Formulation, p: &[f64; 6]) -> f64 {
        match formulation {
            Formulation::Corotational => self.corotational_energy(&self.corotational_kinematics(p)),
            Formulation::Seed002 => {
                let v = self.local_dofs(p);
                GAUSS5
                    .iter()
                    .map(|&(xi, w)| {
                        let [du, dw, ddw] = self.derivative_rows(xi);
                        let dot =
                            |row: &[f64; 6]| row.iter().zip(&v).map(|(a, b)| a * b).sum::<f64>();
                        let (u1, w1, w2) = (dot(&du), dot(&dw), dot(&ddw));
                        let eps = u1 + 0.5 * w1 * w1;
                        0.5 * w * self.length * (self.ea * eps * eps + self.ei * w2 * w2)
                    })
                    .sum()
            }
        }
    }

    /// The co-rotational element's strain energy (J).
    fn corotational_energy(&self, kinematics: &Kinematics) -> f64 {
        let [t1, t2] = kinematics.rotations;
        let (l0, strain) = (self.length, self.shallow_arch_strain(kinematics));
        0.5 * self.ea * l0 * strain * strain
            + self.ei / l0 * (2.0 * t1 * t1 + 2.0 * t1 * t2 + 2.0 * t2 * t2)
    }

    /// The end rotations (rad) relative to the chord at angle `beta` (rad),
    /// from the nodes' rotation displacements `r1` and `r2`: the
    /// co-rotational element's local rotations.
    pub fn local_rotations(&self, r1: f64, r2: f64, beta: f64) -> [f64; 2] {
        [wrap(r1 + self.angle0 - beta), wrap(r2 + self.angle0 - beta)]
    }

    /// Local rotations (wrapped), stretch and the chord at `p`.
    fn corotational_kinematics(&self, p: &[f64; 6]) -> Kinematics {
        let (dx, dz) = self.chord(p);
        let ln = (dx * dx + dz * dz).sqrt();
        let beta = dz.atan2(dx);
        let [t1, t2] = self.local_rotations(p[2], p[5], beta);
        Kinematics {
            rotations: [t1, t2],
            // ln - l0 without cancellation.
            stretch: (ln * ln - self.length * self.length) / (ln + self.length),
            chord: ln,
            angle: beta,
            direction: [dx / ln, dz / ln],
        }
    }

    /// Shallow-arch local strain (Crisfield 1991 sec. 7.3; Battini 2002): the
    /// axial strain `u / l0 + (2 t1^2 - t1 t2 + 2 t2^2) / 30` couples the local
    /// rotations to the axial force, which gives a tensioned element the
    /// geometric stiffness of the Hermite beam against rotation of its nodes (a
    /// hanging line with small EI would otherwise have unresisted rotations).
    fn corotational_local(&self, kinematics: &Kinematics) -> LocalForces {
        let [t1, t2] = kinematics.rotations;
        let l0 = self.length;
        let n = self.ea * self.shallow_arch_strain(kinematics);
        let k = self.ei / l0;
        LocalForces {
            axial: n,
            moments: [
                k * (4.0 * t1 + 2.0 * t2) + n * l0 * (4.0 * t1 - t2) / 30.0,
                k * (2.0 * t1 + 4.0 * t2) + n * l0 * (4.0 * t2 - t1) / 30.0,
            ],
            chord: kinematics.chord,
            angle: kinematics.angle,
            direction: kinematics.direction,
        }
    }

    /// The axial strain `u / l0 + (2 t1^2 - t1 t2 + 2 t2^2) / 30`.
    fn shallow_arch_strain(&self, kinematics: &Kinematics) -> f64 {
        let [t1, t2] = kinematics.rotations;
        kinematics.stretch / self.length + (2.0 * t1 * t1 - t1 * t2 + 2.0 * t2 * t2) / 30.0
    }

    /// f = B^T [N, M1, M2]; K = B^T D B + z z^T N / ln + (r z^T + z r^T)(M1 + M2) / ln^2
    /// with D the local tangent (Crisfield eq. 7.54 with this sign convention;
    /// checked by finite differences).
    fn corotational(&self, p: &[f64; 6], tangent: bool) -> ElementForce {
        let kinematics = self.corotational_kinematics(p);
        let local = self.corotational_local(&kinematics);
        self.corotational_from(&kinematics, &local, tangent)
    }

    /// [`Element::corotational`] from the kinematics and local forces.
    fn corotational_from(
        &self,
        kinematics: &Kinematics,
        local: &LocalForces,
        tangent: bool,
    ) -> ElementForce {
        let (ln, [c, s]) = (local.chord, local.direction);
        let r = [-c, -s, 0.0, c, s, 0.0];
        let z = [s, -c, 0.0, -s, c, 0.0];
        // Rows of B: d(stretch), d(theta1 local), d(theta2 local).
        let mut b = [[0.0; 6]; 3];
        for i in 0..6 {
            b[0][i] = r[i];
            b[1][i] = -z[i] / ln;
            b[2][i] = -z[i] / ln;
        }
        b[1][2] += 1.0;
        b[2][5] += 1.0;
        let stress = [local.axial, local.moments[0], local.moments[1]];
        let mut f = [0.0; 6];
        for i in 0..6 {
            f[i] = (0..3).map(|a| b[a][i] * stress[a]).sum();
        }
        let mut k = [[0.0; 6]; 6];
        if tangent {
            let d = self.local_tangent(kinematics.rotations, local.axial);
            let (n, m) = (local.axial, local.moments[0] + local.moments[1]);
            for i in 0..6 {
                for j in 0..6 {
                    let mut v = z[i] * z[j] * n / ln + (r[i] * z[j] + z[i] * r[j]) * m / (ln * ln);
                    for a in 0..3 {
                        for bb in 0..3 {
                            v += b[a][i] * d[a][bb] * b[bb][j];
                        }
                    }
                    k[i][j] = v;
                }
            }
        }
        (f, k)
    }

    /// d[N, M1, M2] / d[stretch, t1, t2] of the shallow-arch local element.
    fn local_tangent(&self, [t1, t2]: [f64; 2], n: f64) -> [[f64; 3]; 3] {
        let (l0, ea) = (self.length, self.ea);
        let k = self.ei / l0;
        let (g1, g2) = ((4.0 * t1 - t2) / 30.0, (4.0 * t2 - t1) / 30.0);
        [
            [ea / l0, ea * g1, ea * g2],
            [
                ea * g1,
                4.0 * k + 4.0 * n * l0 / 30.0 + ea * l0 * g1 * g1,
                2.0 * k - n * l0 / 30.0 + ea * l0 * g1 * g2,
            ],
            [
                ea * g2,
                2.0 * k - n * l0 / 30.0 + ea * l0 * g1 * g2,
                4.0 * k + 4.0 * n * l0 / 30.0 + ea * l0 * g2 * g2,
            ],
        ]
    }

    /// Global displacements to the element frame (the stress-free chord).
    fn local_dofs(&self, p: &[f64; 6]) -> [f64; 6] {
        let (c, s) = (self.cos0, self.sin0);
        [
            c * p[0] + s * p[1],
            -s * p[0] + c * p[1],
            p[2],
            c * p[3] + s * p[4],
            -s * p[3] + c * p[4],
            p[5],
        ]
    }

    /// The derivative rows at element coordinate xi: u' (B_eps), w' (N_w') and
    /// w'' (B_kappa), each against the local DOFs.
    fn derivative_rows(&self, xi: f64) -> [[f64; 6]; 3] {
        let l = self.length;
        let du = [-1.0 / l, 0.0, 0.0, 1.0 / l, 0.0, 0.0];
        let dw = [
            0.0,
            (-6.0 * xi + 6.0 * xi * xi) / l,
            1.0 - 4.0 * xi + 3.0 * xi * xi,
            0.0,
            (6.0 * xi - 6.0 * xi * xi) / l,
            -2.0 * xi + 3.0 * xi * xi,
        ];
        let ddw = [
            0.0,
            (-6.0 + 12.0 * xi) / (l * l),
            (-4.0 + 6.0 * xi) / l,
            0.0,
            (6.0 - 12.0 * xi) / (l * l),
            (-2.0 + 6.0 * xi) / l,
        ];
        [du, dw, ddw]
    }

    fn seed002_local(&self, p: &[f64; 6]) -> LocalForces {
        let v = self.local_dofs(p);
        let dot = |row: &[f64; 6]| row.iter().zip(&v).map(|(a, b)| a * b).sum::<f64>();
        let [du, dw, _] = self.derivative_rows(0.5);
        let (u1, w1) = (dot(&du), dot(&dw));
        // The end moments are the rotational entries of the nodal force.
        let (f, _) = self.seed002(p, false);
        let (dx, dz) = self.chord(p);
        let chord = (dx * dx + dz * dz).sqrt();
        LocalForces {
            axial: self.ea * (u1 + 0.5 * w1 * w1),
            moments: [f[2], f[5]],
            chord,
            angle: dz.atan2(dx),
            direction: [dx / chord, dz / chord],
        }
    }

    /// f = int (a N + EI B_k^T w''), a = B_eps^T + w' N_w'^T;
    /// K = int (EA a a^T + N N_w'^T N_w' + EI B_k^T B_k) (exact by five-point Gauss).
    fn seed002(&self, p: &[f64; 6], tangent: bool) -> ElementForce {
        let v = self.local_dofs(p);
        let mut fl = [0.0; 6];
        let mut kl = [[0.0; 6]; 6];
        for &(xi, weight) in &GAUSS5 {
            let w = weight * self.length;
            let [du, dw, ddw] = self.derivative_rows(xi);
            let dot = |row: &[f64; 6]| row.iter().zip(&v).map(|(a, b)| a * b).sum::<f64>();
            let (u1, w1, w2) = (dot(&du), dot(&dw), dot(&ddw));
            let n = self.ea * (u1 + 0.5 * w1 * w1);
            let m = self.ei * w2;
            let mut a = [0.0; 6];
            for i in 0..6 {
                a[i] = du[i] + w1 * dw[i];
                fl[i] += w * (a[i] * n + ddw[i] * m);
            }
            if tangent {
                for i in 0..6 {
                    for j in 0..6 {
                        kl[i][j] += w
                            * (self.ea * a[i] * a[j]
                                + n * dw[i] * dw[j]
                                + self.ei * ddw[i] * ddw[j]);
                    }
                }
            }
        }
        self.rotated_to_global(&fl, &kl, tangent)
    }

    /// Seed 002's restoring force term by term (P2 eqs. 55-57), global element
    /// DOFs: `[K0 b, K1(a) b, K2(a, b) c]`, so that the internal force is
    /// g(v) = K0 v + K1(v) v + K2(v, v) v; with G = N_w'^T N_w',
    /// K1(a) b = int EA / 2 (B_eps^T a^T G b + 2 G a B_eps b) and
    /// K2(a, b) c = int EA / 2 G a b^T G c (exact by five-point Gauss).
    pub fn seed002_terms(&self, a: &[f64; 6], b: &[f64; 6], c: &[f64; 6]) -> [[f64; 6]; 3] {
        let (la, lb, lc) = (self.local_dofs(a), self.local_dofs(b), self.local_dofs(c));
        let dot = |row: &[f64; 6], v: &[f64; 6]| row.iter().zip(v).map(|(x, y)| x * y).sum::<f64>();
        let mut local = [[0.0; 6]; 3];
        for &(xi, weight) in &GAUSS5 {
            let w = weight * self.length;
            let [du, dw, ddw] = self.derivative_rows(xi);
            let (ub, wb, kb) = (dot(&du, &lb), dot(&dw, &lb), dot(&ddw, &lb));
            let (wa, wc) = (dot(&dw, &la), dot(&dw, &lc));
            for i in 0..6 {
                local[0][i] += w * (self.ea * du[i] * ub + self.ei * ddw[i] * kb);
                local[1][i] += w * 0.5 * self.ea * (du[i] * wa * wb + 2.0 * dw[i] * wa * ub);
                local[2][i] += w * 0.5 * self.ea * dw[i] * wa * wb * wc;
            }
        }
        let t = rotation(self.cos0, self.sin0);
        local.map(|f| std::array::from_fn(|i| (0..6).map(|k| t[k][i] * f[k]).sum()))
    }

    /// T^T f and T^T K T with T the element's rotation.
    fn rotated_to_global(&self, fl: &[f64; 6], kl: &[[f64; 6]; 6], tangent: bool) -> ElementForce {
        let t = rotation(self.cos0, self.sin0);
        let mut f = [0.0; 6];
        let mut k = [[0.0; 6]; 6];
        for i in 0..6 {
            f[i] = (0..6).map(|a| t[a][i] * fl[a]).sum();
        }
        if tangent {
            let mut kt = [[0.0; 6]; 6];
            for a in 0..6 {
                for j in 0..6 {
                    kt[a][j] = (0..6).map(|b| kl[a][b] * t[b][j]).sum();
                }
            }
            for i in 0..6 {
                for j in 0..6 {
                    k[i][j] = (0..6).map(|a| t[a][i] * kt[a][j]).sum();
                }
            }
        }
        (f, k)
    }
}

/// The 6x6 rotation of an element's DOFs from the global frame to the frame at
/// angle (cos, sin): each node's translations rotated, its rotation kept.
pub fn rotation(c: f64, s: f64) -> [[f64; 6]; 6] {
    let mut t = [[0.0; 6]; 6];
    for base in [0, 3] {
        t[base][base] = c;
        t[base][base + 1] = s;
        t[base + 1][base] = -s;
        t[base + 1][base + 1] = c;
        t[base + 2][base + 2] = 1.0;
    }
    t
}
