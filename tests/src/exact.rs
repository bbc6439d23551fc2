//! Analytic solutions of the benchmark chains (B1-B3) and the check of a
//! scene's `exact` indicator, which carries such a solution as signals.

use crate::{Chain, Series};
use nalgebra::{Matrix2, SymmetricEigen, Vector2};

impl Chain {
    /// The exact displacements `[u1, u2]` (m) at t (s) of a chain whose damping
    /// shares its stiffness's modes (B2: none; B3: c and dc like k and kc),
    /// from the modes of M^-1/2 K M^-1/2, each mode a (damped) free vibration.
    pub fn exact(&self, t: f64) -> [f64; 2] {
        let root = Vector2::new(self.m[0].sqrt(), self.m[1].sqrt());
        let scale = |a: Matrix2<f64>| Matrix2::from_fn(|i, j| a[(i, j)] / (root[i] * root[j]));
        let couple = |ground: [f64; 2], c: f64| Matrix2::new(ground[0] + c, -c, -c, ground[1] + c);
        let k = scale(couple(self.k, self.kc));
        let c = scale(couple(self.c, self.dc));
        let modes = SymmetricEigen::new(k);
        let u0 = Vector2::from(self.u0).component_mul(&root);
        let v0 = Vector2::from(self.v0).component_mul(&root);
        let mut u = Vector2::zeros();
        for i in 0..2 {
            let phi = modes.eigenvectors.column(i);
            let off = (phi.transpose() * c * modes.eigenvectors.column(1 - i))[0];
            assert!(
                off.abs() < 1e-9 * c.norm().max(1.0),
                "damping couples the modes"
            );
            let d = 0.5 * (phi.transpose() * c * phi)[0];
            let wd = (modes.eigenvalues[i] - d * d).sqrt();
            let (q0, dq0) = (phi.dot(&u0), phi.dot(&v0));
            let q = (-d * t).exp() * (q0 * (wd * t).cos() + (dq0 + d * q0) / wd * (wd * t).sin());
            u += phi * q;
        }
        [u[0] / root[0], u[1] / root[1]]
    }
}

/// Checks a run's `exact` indicator: the scene's `reference` signals against
/// `formula` (to 1e-12 of their size), and the reported epsilon against one
/// computed by hand from the recorded `motion` (to 1e-9); returns epsilon.
pub fn check_exact_indicator(
    s: &Series,
    motion: [&str; 2],
    reference: [&str; 2],
    formula: impl Fn(f64) -> [f64; 2],
) -> f64 {
    let exact: Vec<[f64; 2]> = s.time.iter().map(|&t| formula(t)).collect();
    let columns: [Vec<f64>; 2] = [0, 1].map(|j| exact.iter().map(|e| e[j]).collect());
    for (signal, formula) in reference.iter().zip(&columns) {
        let size = formula.iter().fold(0.0, |m: f64, v| m.max(v.abs()));
        let worst = (s.get(signal).iter().zip(formula))
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(worst < 1e-12 * size, "{signal}: {worst:e} from the formula");
    }
    let x = [s.get(motion[0]), s.get(motion[1])];
    let by_hand =
        slender_app::indicators::normalized_error(&s.time, &x, &[&columns[0], &columns[1]]).sqrt();
    let reported = s
        .indicators
        .iter()
        .find(|i| i.name == "exact")
        .expect("the scene's exact indicator")
        .relative_error;
    assert!(
        (reported - by_hand).abs() <= 1e-9 * by_hand,
        "{reported} vs {by_hand}"
    );
    reported
}
