use super::*;

/// A chain of `n` unit masses on springs of stiffness `k` between them and to
/// walls at both ends: K = k tridiag(-1, 2, -1), M = I.
fn chain(n: usize, k: f64) -> (SymmetricBand, SymmetricBand) {
    let mut stiffness = SymmetricBand::zeros(n, 1);
    let mut mass = SymmetricBand::zeros(n, 1);
    for i in 0..n {
        stiffness.add(i, i, 2.0 * k);
        mass.add(i, i, 1.0);
        if i > 0 {
            stiffness.add(i, i - 1, -k);
        }
    }
    (stiffness, mass)
}

#[test]
fn finds_a_spring_chains_modes_as_the_closed_form() {
    // w_j^2 = 2 k (1 - cos(j pi / (n + 1))), phi_j(i) ~ sin(i j pi / (n + 1)).
    let (n, k) = (400, 1.0e4);
    let (stiffness, mass) = chain(n, k);
    let modes = lowest_banded_modes(&stiffness, &mass, &[], 6).expect("converges");
    assert_eq!(modes.len(), 6);
    let pi = std::f64::consts::PI;
    for (j, (w2, phi)) in modes.iter().enumerate() {
        let order = (j + 1) as f64;
        let exact = 2.0 * k * (1.0 - (order * pi / (n as f64 + 1.0)).cos());
        assert!(
            (w2 / exact - 1.0).abs() < 1e-11,
            "mode {j}: {w2} against {exact}"
        );
        let shape: Vec<f64> = (0..n)
            .map(|i| ((i + 1) as f64 * order * pi / (n as f64 + 1.0)).sin())
            .collect();
        let scale = dot(&shape, phi) / dot(&shape, &shape);
        let miss = phi
            .iter()
            .zip(&shape)
            .fold(0.0f64, |a, (p, s)| a.max((p - scale * s).abs()));
        let largest = phi.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        assert!(miss < 1e-8 * largest, "mode {j}: shape off by {miss:e}");
        assert!(mass.quadratic_form(phi) - 1.0 < 1e-12, "M-normalised");
    }
}

/// A banded pencil with coupling across its band, a mass that is not
/// diagonal and DOFs held: as the dense reduction, to round-off.
#[test]
fn agrees_with_the_dense_reduction_with_dofs_held() {
    let (n, w) = (90, 5);
    let mut stiffness = SymmetricBand::zeros(n, w);
    let mut mass = SymmetricBand::zeros(n, w);
    for i in 0..n {
        stiffness.add(i, i, 40.0 + (i % 7) as f64);
        mass.add(i, i, 2.0 + (i % 3) as f64 * 0.1);
        for s in 1..=w.min(i) {
            stiffness.add(i, i - s, -3.0 / s as f64);
            mass.add(i, i - s, 0.05 / s as f64);
        }
    }
    let held = [0, 1, 44, 89];
    let modes = lowest_banded_modes(&stiffness, &mass, &held, 8).expect("converges");
    let free: Vec<usize> = (0..n).filter(|d| !held.contains(d)).collect();
    let pick = |a: &SymmetricBand| {
        DMatrix::from_fn(free.len(), free.len(), |i, j| a.get(free[i], free[j]))
    };
    let dense = lowest_modes(&pick(&mass), &pick(&stiffness), 8, "test").expect("dense");
    for ((w2, phi), (d2, dphi)) in modes.iter().zip(&dense) {
        assert!((w2 / d2 - 1.0).abs() < 1e-12, "{w2} against {d2}");
        held.iter().for_each(|&d| assert_eq!(phi[d], 0.0));
        let sign = dot(
            &free.iter().map(|&d| phi[d]).collect::<Vec<_>>(),
            dphi.as_slice(),
        )
        .signum();
        for (a, &d) in free.iter().enumerate() {
            assert!((phi[d] - sign * dphi[a]).abs() < 1e-8, "DOF {d}");
        }
    }
}

#[test]
fn gives_up_when_the_last_wanted_eigenvalue_is_repeated() {
    // Eigenvalues 1, 2, 3, 3, 4, ...: asked for three, the Sturm check counts
    // four below the third (so the dense path decides which pair to keep).
    let n = 30;
    let mut stiffness = SymmetricBand::zeros(n, 1);
    let mut mass = SymmetricBand::zeros(n, 1);
    for i in 0..n {
        let lambda = if i < 3 { i as f64 + 1.0 } else { i as f64 };
        stiffness.add(i, i, lambda);
        mass.add(i, i, 1.0);
    }
    assert!(lowest_banded_modes(&stiffness, &mass, &[], 3).is_none());
    let two = lowest_banded_modes(&stiffness, &mass, &[], 2).expect("two are distinct");
    assert!((two[1].0 - 2.0).abs() < 1e-12);
}

#[test]
fn refuses_a_stiffness_that_is_not_positive_definite() {
    let (mut stiffness, mass) = chain(20, 1.0);
    stiffness.add(10, 10, -5.0);
    assert!(lowest_banded_modes(&stiffness, &mass, &[], 3).is_none());
}
