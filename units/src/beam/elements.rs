//! Euler-Bernoulli beam elements with Hermite cubic shape functions: 2 DOFs per
//! node (deflection y, rotation theta = y'), element lengths may differ.
//!
//! Node j has DOFs 2j (y) and 2j + 1 (theta); element k joins nodes k and k + 1.

use crate::numerics::banded::SymmetricBand;

/// Half-bandwidth of a 2-DOF-per-node chain.
pub const BAND: usize = 3;

/// Hermite shape functions at xi in [0, 1] for element length `l`:
/// y(xi) = N . (y_a, theta_a, y_b, theta_b).
pub fn shape(xi: f64, l: f64) -> [f64; 4] {
    let (x2, x3) = (xi * xi, xi * xi * xi);
    [
        1.0 - 3.0 * x2 + 2.0 * x3,
        l * (xi - 2.0 * x2 + x3),
        3.0 * x2 - 2.0 * x3,
        l * (x3 - x2),
    ]
}

/// Two-point Gauss-Legendre points on [0, 1] and their weights.
pub const GAUSS: [(f64, f64); 2] = [
    (0.211_324_865_405_187_13, 0.5),
    (0.788_675_134_594_812_9, 0.5),
];

/// Adds a 4x4 element matrix of element k into a banded matrix.
fn add_element(m: &mut SymmetricBand, k: usize, e: &[[f64; 4]; 4], scale: f64) {
    for (r, row) in e.iter().enumerate() {
        for (c, v) in row.iter().enumerate().take(r + 1) {
            m.add(2 * k + r, 2 * k + c, scale * v);
        }
    }
}

/// Bending stiffness EI y'''' assembled over elements of the given lengths.
pub fn stiffness(ei: f64, lengths: &[f64]) -> SymmetricBand {
    let mut m = SymmetricBand::zeros(2 * (lengths.len() + 1), BAND);
    for (k, &l) in lengths.iter().enumerate() {
        let e = [
            [12.0, 6.0 * l, -12.0, 6.0 * l],
            [6.0 * l, 4.0 * l * l, -6.0 * l, 2.0 * l * l],
            [-12.0, -6.0 * l, 12.0, -6.0 * l],
            [6.0 * l, 2.0 * l * l, -6.0 * l, 4.0 * l * l],
        ];
        add_element(&mut m, k, &e, ei / (l * l * l));
    }
    m
}

/// Geometric stiffness of a constant axial tension, -T y'' (T in N, negative in
/// compression), assembled over elements: T / (30 l) times the Hermite matrix of
/// integral N'^T N' dx, added to the bending stiffness where a section carries
/// tension (a hanging pipe; EI -> 0 leaves a taut string).
pub fn add_geometric_stiffness(k: &mut SymmetricBand, tension: f64, lengths: &[f64]) {
    if tension == 0.0 {
        return;
    }
    for (e, &l) in lengths.iter().enumerate() {
        let m = [
            [36.0, 3.0 * l, -36.0, 3.0 * l],
            [3.0 * l, 4.0 * l * l, -3.0 * l, -l * l],
            [-36.0, -3.0 * l, 36.0, -3.0 * l],
            [3.0 * l, -l * l, -3.0 * l, 4.0 * l * l],
        ];
        add_element(k, e, &m, tension / (30.0 * l));
    }
}

/// Consistent mass mu y'' assembled over elements.
pub fn mass(mu: f64, lengths: &[f64]) -> SymmetricBand {
    let mut m = SymmetricBand::zeros(2 * (lengths.len() + 1), BAND);
    for (k, &l) in lengths.iter().enumerate() {
        let e = [
            [156.0, 22.0 * l, 54.0, -13.0 * l],
            [22.0 * l, 4.0 * l * l, 13.0 * l, -3.0 * l * l],
            [54.0, 13.0 * l, 156.0, -22.0 * l],
            [-13.0 * l, -3.0 * l * l, -22.0 * l, 4.0 * l * l],
        ];
        add_element(&mut m, k, &e, mu * l / 420.0);
    }
    m
}

/// Load vector of a distributed load w(x) (N/m), by two-point Gauss-Legendre per
/// element (seed 004 eq. 4.25), into `out`.
pub fn load(w: impl Fn(f64) -> f64, lengths: &[f64], out: &mut [f64]) {
    out.fill(0.0);
    let mut x0 = 0.0;
    for (k, &l) in lengths.iter().enumerate() {
        for (xi, weight) in GAUSS {
            let n = shape(xi, l);
            let wx = w(x0 + xi * l);
            for i in 0..4 {
                out[2 * k + i] += l * weight * wx * n[i];
            }
        }
        x0 += l;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_uniform_load_gives_the_textbook_vector() {
        let mut f = vec![0.0; 4];
        load(|_| 2.0, &[3.0], &mut f);
        let expected = [3.0, 1.5, 3.0, -1.5]; // W L (1/2, L/12, 1/2, -L/12)
        for i in 0..4 {
            assert!((f[i] - expected[i]).abs() < 1e-12, "{i}: {}", f[i]);
        }
    }
}
