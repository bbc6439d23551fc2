//! Bar elements of a cable: tension, tangent stiffness (elastic + geometric) and
//! consistent mass (structural + added), assembled over a chain of nodes.
//!
//! Node j has DOFs 2j (x) and 2j + 1 (z); element e joins nodes e and e + 1.

use crate::numerics::banded::SymmetricBand;

/// Half-bandwidth of a 2-DOF-per-node chain.
pub const BAND: usize = 3;

/// Element properties shared by every element of a line.
#[derive(Clone, Debug)]
pub struct ElementProperties {
    /// Unstretched element length (m).
    pub length: f64,
    /// EA (N).
    pub axial_stiffness: f64,
    /// Structural mass per unit length (kg/m).
    pub mass_per_length: f64,
    /// Added mass per unit length normal and along the element (kg/m):
    /// rho pi D^2 / 4 times the coefficients (zero without the effect).
    pub added_mass_normal: f64,
    /// Added mass per unit length along the element (kg/m).
    pub added_mass_tangential: f64,
}

/// Unit direction, current length and tension of element e.
pub fn element_state(p: &ElementProperties, a: [f64; 2], b: [f64; 2]) -> ([f64; 2], f64, f64) {
    let d = [b[0] - a[0], b[1] - a[1]];
    let l = (d[0] * d[0] + d[1] * d[1]).sqrt();
    let e = [d[0] / l, d[1] / l];
    let tension = p.axial_stiffness * (l - p.length) / p.length;
    (e, l, tension)
}

/// Internal forces at the nodes (the pull of the elements, N) into `forces`, and
/// element tensions into `tensions`.
pub fn internal_forces(
    p: &ElementProperties,
    x: &[[f64; 2]],
    forces: &mut [[f64; 2]],
    tensions: &mut [f64],
) {
    forces.iter_mut().for_each(|f| *f = [0.0, 0.0]);
    for e in 0..x.len() - 1 {
        let (dir, _, t) = element_state(p, x[e], x[e + 1]);
        tensions[e] = t;
        for c in 0..2 {
            forces[e][c] += t * dir[c];
            forces[e + 1][c] -= t * dir[c];
        }
    }
}

/// Adds the 2x2 block `k` in the pattern [[k, -k], [-k, k]] of element e.
#[allow(clippy::needless_range_loop)] // (r, c) index the block and the DOFs alike
fn add_element_block(m: &mut SymmetricBand, e: usize, k: [[f64; 2]; 2], off_diagonal: f64) {
    for r in 0..2 {
        for c in 0..2 {
            let v = k[r][c];
            let (i0, i1) = (2 * e + r, 2 * (e + 1) + r);
            let (j0, j1) = (2 * e + c, 2 * (e + 1) + c);
            if i0 >= j0 {
                m.add(i0, j0, v);
            }
            if i1 >= j1 {
                m.add(i1, j1, v);
            }
            m.add(i1, j0, off_diagonal * v);
        }
    }
}

/// Tangent stiffness at positions `x`: elastic (EA / L0) e e^T plus, when
/// `geometric`, the tension stiffness (T / l)(I - e e^T).
pub fn stiffness(p: &ElementProperties, x: &[[f64; 2]], geometric: bool) -> SymmetricBand {
    let mut k = SymmetricBand::zeros(2 * x.len(), BAND);
    for e in 0..x.len() - 1 {
        let (dir, l, t) = element_state(p, x[e], x[e + 1]);
        let ea = p.axial_stiffness / p.length;
        let g = if geometric { t / l } else { 0.0 };
        let mut block = [[0.0; 2]; 2];
        for r in 0..2 {
            for c in 0..2 {
                let eet = dir[r] * dir[c];
                let identity = if r == c { 1.0 } else { 0.0 };
                block[r][c] = ea * eet + g * (identity - eet);
            }
        }
        add_element_block(&mut k, e, block, -1.0);
    }
    k
}

/// Consistent mass at positions `x`: structural mass in both directions, added mass
/// normal and along each element's direction.
pub fn mass(p: &ElementProperties, x: &[[f64; 2]]) -> SymmetricBand {
    let mut m = SymmetricBand::zeros(2 * x.len(), BAND);
    for e in 0..x.len() - 1 {
        let (dir, _, _) = element_state(p, x[e], x[e + 1]);
        let mut block = [[0.0; 2]; 2];
        for r in 0..2 {
            for c in 0..2 {
                let eet = dir[r] * dir[c];
                let identity = if r == c { 1.0 } else { 0.0 };
                block[r][c] = p.mass_per_length * identity
                    + p.added_mass_normal * (identity - eet)
                    + p.added_mass_tangential * eet;
            }
        }
        // Consistent bar mass: L/6 [[2, 1], [1, 2]].
        let scale = p.length / 6.0;
        let diagonal = block.map(|row| row.map(|v| 2.0 * scale * v));
        let coupling = block.map(|row| row.map(|v| scale * v));
        for r in 0..2 {
            for c in 0..2 {
                let (i0, i1) = (2 * e + r, 2 * (e + 1) + r);
                let (j0, j1) = (2 * e + c, 2 * (e + 1) + c);
                if i0 >= j0 {
                    m.add(i0, j0, diagonal[r][c]);
                    m.add(i1, j1, diagonal[r][c]);
                }
                m.add(i1, j0, coupling[r][c]);
            }
        }
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    fn props() -> ElementProperties {
        ElementProperties {
            length: 10.0,
            axial_stiffness: 1e6,
            mass_per_length: 2.0,
            added_mass_normal: 1.0,
            added_mass_tangential: 0.0,
        }
    }

    #[test]
    fn the_tangent_matches_finite_differences_of_the_internal_forces() {
        let p = props();
        let x = vec![[0.0, 0.0], [3.0, 9.6], [5.0, 20.0]];
        let k = stiffness(&p, &x, true);
        let mut f0 = vec![[0.0; 2]; 3];
        let mut t = vec![0.0; 2];
        internal_forces(&p, &x, &mut f0, &mut t);
        for j in 0..6 {
            let mut xp = x.clone();
            let h = 1e-6;
            xp[j / 2][j % 2] += h;
            let mut f1 = vec![[0.0; 2]; 3];
            internal_forces(&p, &xp, &mut f1, &mut t);
            for i in 0..6 {
                // Internal forces pull the nodes: K = -dF/dx.
                let fd = -(f1[i / 2][i % 2] - f0[i / 2][i % 2]) / h;
                assert!(
                    (fd - k.get(i, j)).abs() < 1e-3 * (1.0 + k.get(i, j).abs()),
                    "({i},{j}) {fd} vs {}",
                    k.get(i, j)
                );
            }
        }
    }

    #[test]
    fn total_mass_is_line_mass_plus_normal_added_mass() {
        let p = props();
        let x = vec![[0.0, 0.0], [0.0, 10.0], [0.0, 20.0]];
        let m = mass(&p, &x);
        // A rigid translation along x: sum of all x-x entries = (m + ma) L.
        let mut total = 0.0;
        for i in (0..6).step_by(2) {
            for j in (0..6).step_by(2) {
                total += m.get(i, j);
            }
        }
        assert!((total - 3.0 * 20.0).abs() < 1e-12);
    }
}
