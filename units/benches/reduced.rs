//! Criterion benchmark of reduced sections (issue 15, seed 002's LRBF):
//! - the cable: one simulated second of the full 59-DOF model by central
//!   differences at 1e-4 s (seed 002's reference) against its 3 modes + 5
//!   derivatives reduction at 3e-4 s (the source: 0.8 s against 129 s of CPU
//!   for 10 s, MATLAB);
//! - the real-time capacity at 1 ms: one central-difference step of an LRBF
//!   model of N coordinates on the frame (118 DOFs; the first N linear modes,
//!   since the cost depends on N only), N up to 70 (the source: 44 at 1 ms);
//! - the same with sampled elements (ECSW) on a 200-element cable (599 free
//!   DOFs), N up to 400, with all 200 elements and with 50 of them (the cost
//!   depends on the sample's size, not on which elements it holds).
//!
//! Run with `cargo bench -p slender-units --bench reduced`.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use nalgebra::{DMatrix, DVector};
use slender_units::integrators::central_difference::CentralDifference;
use slender_units::nonlinear::{NonlinearParams, NonlinearSection};
use slender_units::reduced::basis::{Derivative, Normalisation, derivative_columns, linear_modes};
use slender_units::reduced::ecsw::SampledForce;
use slender_units::reduced::polynomial::CubicSection;
use slender_units::reduced::system::ReducedSection;
use slender_units::reduced::taylor::TaylorSection;
use slender_units::{Driver, Time};
use std::hint::black_box;

const STEEL: &str =
    "axial_stiffness = 4.1233e8, bending_stiffness = 6.4427e4, mass_per_length = 15.315";

fn section(text: &str) -> Driver<NonlinearSection> {
    let params: NonlinearParams = toml::from_str(text).expect("parameters");
    let mut driver = Driver::new(NonlinearSection::new(params).expect("section"));
    driver.initialize(Time::ZERO).expect("initialize");
    driver
}

fn cable(extra: &str) -> String {
    format!(
        "formulation = \"seed002\"\nsegments = [{{ length = 20.0, elements = 20, {STEEL} }}]\nends.start = {{ kind = \"pinned\" }}\nends.end = {{ kind = \"pinned\" }}\n{extra}"
    )
}

fn frame() -> String {
    format!(
        "formulation = \"seed002\"\nsegments = [{{ length = 10.0, angle_deg = 90.0, elements = 20, {STEEL} }}, {{ length = 10.0, elements = 20, {STEEL} }}]\nends.start = {{ kind = \"pinned\" }}\nends.end = {{ kind = \"pinned\" }}\nsupports = [{{ at = 10.0, x = true }}]"
    )
}

/// A reduced model with its load pattern and integrator, at rest.
fn reduced(
    c: &CubicSection,
    basis: DMatrix<f64>,
) -> (ReducedSection, DVector<f64>, CentralDifference) {
    let system = ReducedSection::new(c, basis);
    let load = system.project(&DVector::from_element(c.size(), 1.0));
    (system, load, CentralDifference::new())
}

fn cable_second(c: &mut Criterion) {
    let mut group = c.benchmark_group("cable_one_simulated_second");
    group.sample_size(10);
    let load = "loads = [{ from = 0.0, to = 10.0, z = { amplitude = 1.0, angular_frequency = 1.6004, sines = [{ amplitude = 3.0, angular_frequency = 6.4014 }] } }]";
    let text = cable(&format!(
        "integrator = {{ kind = \"central_difference\" }}\n{load}"
    ));
    group.bench_function("full_59_dofs_cd_1e-4", |b| {
        b.iter(|| {
            let mut driver = section(&text);
            let h = Time::from_secs(1e-4).expect("step");
            let mut t = Time::ZERO;
            for _ in 0..10_000 {
                driver.do_step(t, h).expect("step");
                t += h;
            }
            black_box(driver.displacements()[31])
        })
    });
    let cubic = CubicSection::new(&section(&cable(""))).expect("cubic");
    let modes = linear_modes(&cubic, 3, Normalisation::Stiffness).expect("modes");
    let mds = derivative_columns(&cubic, &modes, Derivative::Novel, 3).expect("derivatives");
    let mut columns = modes.shapes.clone();
    columns.extend([0, 1, 3, 4, 5].map(|k| mds[k].clone()));
    let basis = DMatrix::from_columns(&columns);
    group.bench_function("crd3_8_coordinates_cd_3e-4", |b| {
        b.iter(|| {
            let (mut system, load, mut cd) = reduced(&cubic, basis.clone());
            let h = 3e-4;
            for k in 0..3334 {
                let t1 = (k + 1) as f64 * h;
                let f = &load * ((1.6004 * t1).sin() + 3.0 * (6.4014 * t1).sin());
                cd.step(&mut system, t1, h, f.as_slice(), &[])
                    .expect("step");
            }
            black_box(system.coordinates()[0])
        })
    });
    group.finish();
}

fn lrbf_step(c: &mut Criterion) {
    let mut group = c.benchmark_group("lrbf_cd_step");
    group.sample_size(20);
    let cubic = CubicSection::new(&section(&frame())).expect("cubic");
    let modes = linear_modes(&cubic, 70, Normalisation::Mass).expect("modes");
    for n in [10, 20, 30, 40, 44, 50, 60, 70] {
        let basis = DMatrix::from_columns(&modes.shapes[..n]);
        let (mut system, load, mut cd) = reduced(&cubic, basis);
        let h = 1e-5;
        let mut k = 0usize;
        group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
            b.iter(|| {
                k += 1;
                let t1 = k as f64 * h;
                let f = &load * (3.0 * (6.401 * t1).sin());
                cd.step(&mut system, t1, h, f.as_slice(), &[])
                    .expect("step");
            })
        });
    }
    group.finish();
}

fn ecsw_step(c: &mut Criterion) {
    let mut group = c.benchmark_group("ecsw_cd_step");
    group.sample_size(20);
    let long = format!(
        "formulation = \"seed002\"\nsegments = [{{ length = 20.0, elements = 200, {STEEL} }}]\nends.start = {{ kind = \"pinned\" }}\nends.end = {{ kind = \"pinned\" }}"
    );
    let cubic = CubicSection::new(&section(&long)).expect("cubic");
    let modes = linear_modes(&cubic, 400, Normalisation::Mass).expect("modes");
    for n in [100, 200, 300, 400] {
        let basis = DMatrix::from_columns(&modes.shapes[..n]);
        for (label, force) in [
            ("all_200_elements", SampledForce::all(&cubic, &basis)),
            ("50_elements", SampledForce::every(&cubic, &basis, 4)),
        ] {
            let mut system = ReducedSection::sampled(&cubic, basis.clone(), force);
            let load = system.project(&DVector::from_element(cubic.size(), 1.0));
            let mut cd = CentralDifference::new();
            let h = 1e-6;
            let mut k = 0usize;
            group.bench_with_input(BenchmarkId::new(label, n), &n, |b, _| {
                b.iter(|| {
                    k += 1;
                    let t1 = k as f64 * h;
                    let f = &load * (3.0 * (6.401 * t1).sin());
                    cd.step(&mut system, t1, h, f.as_slice(), &[])
                        .expect("step");
                })
            });
        }
    }
    group.finish();
}

/// Seed 002's frame, one simulated second: the full 118 DOFs by central
/// differences at 4.5e-5 s, the linear basis of 6 modes + 21 derivatives (LRBF)
/// at 1e-4 s, and the Taylor basis with 6 unknowns at 1e-3 s (the source: 559.5
/// s, 13.4 s and 0.7 s of MATLAB for 10 s).
fn frame_second(c: &mut Criterion) {
    let mut group = c.benchmark_group("frame_one_simulated_second");
    group.sample_size(10);
    let load =
        "loads = [{ from = 10.0, to = 20.0, z = { amplitude = 3.0, angular_frequency = 6.401 } }]";
    let text = format!(
        "{}\nintegrator = {{ kind = \"central_difference\" }}\n{load}",
        frame()
    );
    group.bench_function("full_118_dofs_cd_4.5e-5", |b| {
        b.iter(|| {
            let mut driver = section(&text);
            let h = Time::from_secs(4.5e-5).expect("step");
            let mut t = Time::ZERO;
            for _ in 0..22_222 {
                driver.do_step(t, h).expect("step");
                t += h;
            }
            black_box(driver.displacements()[91])
        })
    });
    let full = section(&frame());
    let cubic = CubicSection::new(&full).expect("cubic");
    let modes = linear_modes(&cubic, 6, Normalisation::Mass).expect("modes");
    let mds = derivative_columns(&cubic, &modes, Derivative::Novel, 6).expect("derivatives");
    let phi_l = DMatrix::from_columns(&modes.shapes);
    let phi_h = DMatrix::from_columns(&mds);
    let mut columns = modes.shapes.clone();
    columns.extend(mds);
    let basis = DMatrix::from_columns(&columns);
    let mut pattern = vec![0.0; full.model().dofs()];
    full.model()
        .add_distributed([0.0, 1.0], (10.0, 20.0), &mut pattern);
    let pattern =
        DVector::from_iterator(cubic.size(), cubic.free_dofs().iter().map(|&d| pattern[d]));
    group.bench_function("lrbf_27_coordinates_cd_1e-4", |b| {
        b.iter(|| {
            let mut system = ReducedSection::new(&cubic, basis.clone());
            let load = system.project(&pattern);
            let mut cd = CentralDifference::new();
            for k in 0..10_000 {
                let t1 = (k + 1) as f64 * 1e-4;
                let f = &load * (3.0 * (6.401 * t1).sin());
                cd.step(&mut system, t1, 1e-4, f.as_slice(), &[])
                    .expect("step");
            }
            black_box(system.coordinates()[0])
        })
    });
    group.bench_function("taylor_6_unknowns_cd_1e-3", |b| {
        b.iter(|| {
            let mut taylor = TaylorSection::new(&cubic, &phi_l, &phi_h).expect("taylor");
            let load = taylor.project(&pattern);
            for k in 0..1000 {
                let t1 = (k + 1) as f64 * 1e-3;
                taylor
                    .step(1e-3, &(&load * (3.0 * (6.401 * t1).sin())))
                    .expect("step");
            }
            black_box(taylor.coordinates()[0])
        })
    });
    group.finish();
}

/// The Taylor basis's step against N on the 200-element cable (599 free DOFs):
/// N unknowns carrying N modes and their N (N + 1) / 2 derivatives, the force
/// through all 200 elements. Seed 002 counts the basis size N_S = N (N + 3) / 2.
fn taylor_step(c: &mut Criterion) {
    let mut group = c.benchmark_group("taylor_cd_step");
    group.sample_size(20);
    let long = format!(
        "formulation = \"seed002\"\nsegments = [{{ length = 20.0, elements = 200, {STEEL} }}]\nends.start = {{ kind = \"pinned\" }}\nends.end = {{ kind = \"pinned\" }}"
    );
    let cubic = CubicSection::new(&section(&long)).expect("cubic");
    for n in [6, 10, 14, 18, 22, 26, 30, 34] {
        let modes = linear_modes(&cubic, n, Normalisation::Mass).expect("modes");
        let mds = derivative_columns(&cubic, &modes, Derivative::Novel, n).expect("derivatives");
        let mut taylor = TaylorSection::new(
            &cubic,
            &DMatrix::from_columns(&modes.shapes),
            &DMatrix::from_columns(&mds),
        )
        .expect("taylor");
        let load = taylor.project(&DVector::from_element(cubic.size(), 1.0));
        let h = 1e-6;
        let mut k = 0usize;
        let size = n * (n + 3) / 2;
        group.bench_with_input(BenchmarkId::new("n_s", size), &n, |b, _| {
            b.iter(|| {
                k += 1;
                let f = &load * (3.0 * (6.401 * k as f64 * h).sin());
                taylor.step(h, &f).expect("step");
            })
        });
    }
    group.finish();
}

criterion_group!(
    benches,
    cable_second,
    lrbf_step,
    ecsw_step,
    frame_second,
    taylor_step
);
criterion_main!(benches);
