//! Seed 002's reduced restoring forces on a linear basis (LRBF, issue 15): the
//! reduced tensors against the projected full force and tangent; the simply
//! supported cable (notes sec. 8.4) reduced to 3 modes and 5 novel derivatives
//! (CRD3) against the full 59-DOF model, with the Taylor coordinate relations
//! that only the novel derivatives satisfy (the frame: `reduced_frame.rs`).

use crate::support::rms;
use crate::support::{random_vector, section};
use nalgebra::{DMatrix, DVector};
use slender_units::integrators::central_difference::CentralDifference;
use slender_units::nonlinear::seed002::cable;
use slender_units::numerics::banded::SymmetricBand;
use slender_units::reduced::basis::{Derivative, Normalisation, derivative_columns, linear_modes};
use slender_units::reduced::polynomial::CubicSection;
use slender_units::reduced::system::{ReducedSection, RestoringForce};
use slender_units::{Driver, Time};

/// Seed 002's cable basis: 3 stiffness-normalised modes and the derivatives
/// x11, 2 x21, 2 x31, 2 x32, x33 (x22 depends on them and is left out).
fn crd3(c: &CubicSection, kind: Derivative) -> DMatrix<f64> {
    let modes = linear_modes(c, 3, Normalisation::Stiffness).unwrap();
    let mds = derivative_columns(c, &modes, kind, 3).unwrap();
    let mut columns = modes.shapes.clone();
    columns.extend([0, 1, 3, 4, 5].map(|k| mds[k].clone()));
    DMatrix::from_columns(&columns)
}

#[test]
fn reduced_tensors_are_the_projected_force_and_tangent_at_random_states() {
    let driver = section(&cable(""));
    let c = CubicSection::new(&driver).unwrap();
    let basis = crd3(&c, Derivative::Novel);
    let mut reduced = ReducedSection::new(&c, basis.clone());
    let model = driver.model();
    let free = c.free_dofs().to_vec();
    for seed in 0..4 {
        let s = random_vector(basis.ncols(), seed, 0.3);
        let v = &basis * &s;
        let projected = basis.tr_mul(&c.force(&v));
        let RestoringForce::Tensors(tensors) = reduced.restoring_force() else {
            panic!("tensors")
        };
        let force = tensors.force(s.as_slice());
        let error = (&force - &projected).amax() / projected.amax();
        // The full tangent at V = Phi s from the section's own element.
        let mut band = SymmetricBand::zeros(model.dofs(), 5);
        let mut sink = vec![0.0; model.dofs()];
        model.add_internal_force(&c.expand(&v), 1.0, Some((&mut band, 1.0)), &mut sink);
        let kt = DMatrix::from_fn(free.len(), free.len(), |i, j| band.get(free[i], free[j]));
        let projected_tangent = basis.transpose() * kt * &basis;
        let tangent = tensors.tangent(s.as_slice());
        let tangent_error = (&tangent - &projected_tangent).amax() / projected_tangent.amax();
        eprintln!("state {seed}: force {error:.1e}, tangent {tangent_error:.1e}");
        assert!(error < 1e-11 && tangent_error < 1e-11);
    }
}

/// The cable's load: p(t) = sin(w1 t) + 3 sin(w2 t) N/m over the first half.
const W: [f64; 2] = [1.6004, 6.4014];

fn load(t: f64) -> f64 {
    (W[0] * t).sin() + 3.0 * (W[1] * t).sin()
}

/// The full model's midpoint deflection every `h` over `duration` (central
/// differences, as seed 002's reference).
fn full_midpoint(h: f64, duration: f64) -> Vec<f64> {
    let text = cable(&format!(
        "integrator = {{ kind = \"central_difference\" }}\nloads = [{{ from = 0.0, to = 10.0, z = {{ amplitude = 1.0, angular_frequency = {}, sines = [{{ amplitude = 3.0, angular_frequency = {} }}] }} }}]",
        W[0], W[1]
    ));
    let mut driver: Driver<_> = section(&text);
    let step = Time::from_secs(h).unwrap();
    let mut t = Time::ZERO;
    (0..(duration / h).round() as usize)
        .map(|_| {
            driver.do_step(t, step).expect("full step");
            t += step;
            driver.displacements()[3 * 10 + 1]
        })
        .collect()
}

/// A reduced model's midpoint deflection and coordinates every `h`.
fn reduced_run(
    c: &CubicSection,
    basis: DMatrix<f64>,
    h: f64,
    duration: f64,
) -> (Vec<f64>, Vec<Vec<f64>>) {
    let mid = c.free_dofs().iter().position(|&d| d == 3 * 10 + 1).unwrap();
    let mut pattern = vec![0.0; c.expand(&DVector::zeros(c.size())).len()];
    section(&cable(""))
        .model()
        .add_distributed([0.0, 1.0], (0.0, 10.0), &mut pattern);
    let pattern = DVector::from_iterator(c.size(), c.free_dofs().iter().map(|&d| pattern[d]));
    let mut system = ReducedSection::new(c, basis);
    let reduced_load = system.project(&pattern);
    let mut integrator = CentralDifference::new();
    let (mut midpoint, mut coordinates) = (Vec::new(), Vec::new());
    for k in 0..(duration / h).round() as usize {
        let t1 = (k + 1) as f64 * h;
        let f1 = &reduced_load * load(t1);
        integrator
            .step(&mut system, t1, h, f1.as_slice(), &[])
            .expect("reduced step");
        midpoint.push(system.displacements()[mid]);
        coordinates.push(system.coordinates().to_vec());
    }
    (midpoint, coordinates)
}

#[test]
fn crd3_reproduces_the_full_cable_and_its_coordinates_follow_the_taylor_relations() {
    let (h, duration) = (1e-4, 10.0);
    let full = full_midpoint(h, duration);
    let c = CubicSection::new(&section(&cable(""))).unwrap();
    let size = rms(full.iter().copied());
    let error = |reduced: &[f64]| rms(reduced.iter().zip(&full).map(|(r, f)| r - f)) / size;
    let (crd3_mid, s) = reduced_run(&c, crd3(&c, Derivative::Novel), h, duration);
    let modes = linear_modes(&c, 2, Normalisation::Stiffness).unwrap();
    let (cr2_mid, _) = reduced_run(&c, DMatrix::from_columns(&modes.shapes), h, duration);
    // At seed 002's step for CRD3 (3e-4 s, three times the full model's),
    // compared at the common instants.
    let (coarse, _) = reduced_run(&c, crd3(&c, Derivative::Novel), 3e-4, duration);
    let coarse_error = rms(coarse.iter().enumerate().map(|(k, r)| r - full[3 * k + 2])) / size;
    let (crd3_error, cr2_error) = (error(&crd3_mid), error(&cr2_mid));
    eprintln!(
        "midpoint rms {size:.4} m; CRD3 error {crd3_error:.2e} (at 3e-4 s: {coarse_error:.2e}), CR2 error {cr2_error:.2e}"
    );
    // Seed 002: CR2 deviates significantly, CRD3 is almost identical to the
    // full model (8.2e-4 and 0.71 measured).
    assert!(
        crd3_error < 2e-3 && coarse_error < 5e-3,
        "{crd3_error} {coarse_error}"
    );
    assert!(cr2_error > 0.3, "{cr2_error}");
    // s4 = s1^2 - s2^2 / 4 and s8 = s3^2 (notes sec. 4.6), novel against modified.
    let relation = |s: &[Vec<f64>]| {
        let predicted = rms(s.iter().map(|s| s[0] * s[0] - 0.25 * s[1] * s[1]));
        let mismatch = rms(s.iter().map(|s| s[3] - (s[0] * s[0] - 0.25 * s[1] * s[1])));
        (
            rms(s.iter().map(|s| s[3])) / predicted,
            mismatch / predicted,
        )
    };
    let (_, modified) = reduced_run(&c, crd3(&c, Derivative::Modified), h, duration);
    let (novel, modified) = (relation(&s), relation(&modified));
    eprintln!("s4 / (s1^2 - s2^2/4), mismatch: novel {novel:?}, modified {modified:?}");
    // The novel derivatives satisfy the relation (1.00007, mismatch 7.6e-5);
    // the modified ones have twice the amplitude, so their coordinate is half.
    assert!((novel.0 - 1.0).abs() < 1e-3 && novel.1 < 1e-3, "{novel:?}");
    assert!((modified.0 - 0.5).abs() < 0.01, "{modified:?}");
}
