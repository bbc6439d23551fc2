//! Element-level checks: tangents against finite differences, rigid motion, the
//! small-displacement limit.

use super::element::{Element, Formulation};

fn sample() -> Element {
    let (s, c) = 0.4f64.sin_cos();
    Element::new(2.0, (c, s), 3.0e5, 2.0e3)
}

fn displacement() -> [f64; 6] {
    [0.01, -0.02, 0.05, 0.03, 0.04, -0.08]
}

#[test]
fn tangents_are_the_derivatives_of_the_forces() {
    for formulation in [Formulation::Corotational, Formulation::Seed002] {
        let e = sample();
        let p = displacement();
        let (_, k) = e.force(formulation, &p, true);
        for j in 0..6 {
            let h = 1e-7;
            let (mut a, mut b) = (p, p);
            a[j] += h;
            b[j] -= h;
            let (fa, _) = e.force(formulation, &a, false);
            let (fb, _) = e.force(formulation, &b, false);
            for i in 0..6 {
                let fd = (fa[i] - fb[i]) / (2.0 * h);
                let scale = 1.0 + k[i][j].abs() + fd.abs();
                assert!(
                    (fd - k[i][j]).abs() < 1e-5 * scale.max(1e3),
                    "{formulation:?} K[{i}][{j}]: {} vs {fd}",
                    k[i][j]
                );
                assert!(
                    (k[i][j] - k[j][i]).abs() < 1e-9 * (1.0 + k[i][j].abs()),
                    "symmetric"
                );
            }
        }
    }
}

#[test]
fn forces_are_the_gradient_of_the_strain_energy() {
    for formulation in [Formulation::Corotational, Formulation::Seed002] {
        let e = sample();
        let p = displacement();
        let (f, _) = e.force(formulation, &p, false);
        for j in 0..6 {
            let h = 1e-6;
            let (mut a, mut b) = (p, p);
            a[j] += h;
            b[j] -= h;
            let fd =
                (e.strain_energy(formulation, &a) - e.strain_energy(formulation, &b)) / (2.0 * h);
            assert!(
                (fd - f[j]).abs() < 1e-5 * (1.0 + f[j].abs()),
                "{formulation:?} f[{j}]: {} vs {fd}",
                f[j]
            );
        }
    }
}

#[test]
fn a_large_rigid_rotation_produces_no_corotational_force() {
    let e = sample();
    let phi = 2.5f64; // rad, about node 1
    let (x2, z2) = (e.length * e.cos0, e.length * e.sin0);
    let (s, c) = phi.sin_cos();
    let p = [
        0.3,
        -0.7,
        phi,
        0.3 + c * x2 - s * z2 - x2,
        -0.7 + s * x2 + c * z2 - z2,
        phi,
    ];
    let (f, _) = e.force(Formulation::Corotational, &p, false);
    assert!(f.iter().all(|v| v.abs() < 1e-6), "{f:?}");
    // Seed 002's element is not objective: a large rotation strains it.
    let (g, _) = e.force(Formulation::Seed002, &p, false);
    assert!(g.iter().any(|v| v.abs() > 1.0));
}

#[test]
fn both_formulations_agree_with_the_linear_element_for_small_displacements() {
    let e = sample();
    let p: [f64; 6] = displacement().map(|v| v * 1e-6);
    let (fa, k) = e.force(Formulation::Corotational, &[0.0; 6], true);
    assert!(fa.iter().all(|v| v.abs() < 1e-9));
    let linear: Vec<f64> = (0..6)
        .map(|i| (0..6).map(|j| k[i][j] * p[j]).sum())
        .collect();
    for formulation in [Formulation::Corotational, Formulation::Seed002] {
        let (f, _) = e.force(formulation, &p, false);
        for i in 0..6 {
            assert!(
                (f[i] - linear[i]).abs() < 1e-4 * (1e-6 * 1e5),
                "{formulation:?} {i}: {} vs {}",
                f[i],
                linear[i]
            );
        }
    }
}

/// A section's parameters written out as TOML (what `slender expand` prints
/// and what a structure hands the registry) read back as the same
/// parameters: every kind of end condition, time function, integrator,
/// contact law and surface, and a sea state whose sines are made when it is
/// read (written without them, so they are not added twice).
#[test]
fn parameters_written_out_read_back_the_same() {
    let text = r#"
        start = [1, -2.5]
        segments = [{ length = 30, elements = 6, axial_stiffness = 1e9, bending_stiffness = 1e5,
                      mass_per_length = 100, submerged_weight = 500, diameter = 0.3, drag_normal = 1.0 }]
        loads = [{ from = 2.0, x = 10.0 }]
        supports = [{ at = 10.0, x = true }]
        stations = [5.0]
        integrator = { kind = "hht", alpha = -0.1 }
        current = { z = [-100.0, 0.0], velocity = [0.2, 1.0] }
        contact = { method = { kind = "penalty", penalty = 1e6 }, surface = { shape = { kind = "flat", height = -100.0 } } }
        stinger = { method = { kind = "penalty", penalty = 1e6 }, surface = { shape = { kind = "rollers", positions = [1.0, 2.0], radius = 0.5 }, motion = { kind = "sine", amplitude = 0.1, angular_frequency = 0.5 } } }
        reduced_sampling = { training = 10.0 }
        [ends.start]
        kind = "fixed"
        [ends.end]
        x = { velocity_from = 0.25 }
        rotation = { force = "input" }
        z = { displacement = { offset = 2.0, amplitude = 1.0, angular_frequency = 0.6, fade_in = 20.0, sines = [{ amplitude = 0.2, angular_frequency = 0.9 }], sea = { spectrum = { kind = "jonswap", significant_height = 2.0, peak_period = 9.0, components = 40 } } } }
    "#;
    let params: super::NonlinearParams = toml::from_str(text).expect("parameters");
    let z = &params.ends.end.z;
    let Some(super::params::DofCondition::Displacement(
        crate::beam::boundary::TimeFunction::Expression(e),
    )) = z
    else {
        panic!("a displacement: {z:?}");
    };
    assert_eq!(
        e.sines.len(),
        41,
        "the sea's 40 sines after the one written"
    );
    let written = toml::to_string(&params).expect("written out");
    let again: super::NonlinearParams = toml::from_str(&written).expect(&written);
    assert_eq!(again, params, "{written}");
}
