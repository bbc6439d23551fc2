//! Criterion benchmark of the 3D line (`line3d`) against the planar section
//! (`nonlinear`) on the same problem and mesh: seed 000's polyester line
//! (1934 m, drag and added mass) hanging from a top force of 2.5 MN with a
//! 250 kN surge force at 0.6 rad/s, one 0.1 s HHT-alpha step (alpha 0.3),
//! against element count. The 3D line lies in a vertical plane at 37 deg.
//! Cost per simulated second = time per step x 10.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use slender_units::line3d::{Line3d, Line3dParams};
use slender_units::nonlinear::{NonlinearParams, NonlinearSection};
use slender_units::{Driver, Time};
use std::hint::black_box;

const STEP: f64 = 0.1;

/// The top force (N) at `t` (s), turned to the plane at 37 deg.
fn top_force(t: f64) -> [f64; 3] {
    let (s, c) = 37f64.to_radians().sin_cos();
    let fx = 1.9151e6 + 2.5e5 * (0.6 * t).sin();
    [c * fx, s * fx, 1.6070e6]
}

fn line3d(elements: usize) -> Driver<Line3d> {
    let (s, c) = 37f64.to_radians().sin_cos();
    let text = format!(
        r#"
length = 1934.0
elements = {elements}
axial_stiffness = 4.6598e8
bending_stiffness = 100.0
mass_per_length = 44.7
submerged_weight = 93.2
diameter = 0.264
drag_normal = 1.6
added_mass_normal = 1.0
start = {{ position = [0.0, 0.0, -1200.11] }}
end = {{ position = [{x}, {y}, 0.0], condition = "force" }}
"#,
        x = 1529.11 * c,
        y = 1529.11 * s
    );
    let params: Line3dParams = toml::from_str(&text).expect("parameters");
    let mut driver = Driver::new(Line3d::new(params).expect("line"));
    driver.set_inputs(&top_force(0.0)).expect("inputs");
    driver.initialize(Time::ZERO).expect("initialize");
    driver
}

fn planar(elements: usize) -> Driver<NonlinearSection> {
    let text = format!(
        r#"
static_start = true
segments = [{{ length = 1934.0, angle_deg = 39.4, elements = {elements}, axial_stiffness = 4.6598e8, bending_stiffness = 100.0, mass_per_length = 44.7, submerged_weight = 93.2, diameter = 0.264, drag_normal = 1.6, added_mass_normal = 1.0 }}]
ends.start = {{ kind = "pinned" }}
ends.end = {{ x = {{ force = {{ offset = 1.9151e6, amplitude = 2.5e5, angular_frequency = 0.6 }} }}, z = {{ force = 1.6070e6 }} }}
integrator = {{ kind = "hht", alpha = 0.3 }}
"#
    );
    let params: NonlinearParams = toml::from_str(&text).expect("parameters");
    let mut driver = Driver::new(NonlinearSection::new(params).expect("section"));
    driver.initialize(Time::ZERO).expect("initialize");
    driver
}

fn steps(c: &mut Criterion) {
    let mut group = c.benchmark_group("line_step_100ms");
    group.sample_size(10);
    let h = Time::from_secs(STEP).expect("step");
    for elements in [40, 80, 160, 320, 640] {
        let mut driver = line3d(elements);
        let mut t = Time::ZERO;
        let mut k = 0u32;
        group.bench_function(BenchmarkId::new("line3d", elements), |b| {
            b.iter(|| {
                k += 1;
                driver
                    .set_inputs(&top_force(f64::from(k) * STEP))
                    .expect("inputs");
                black_box(driver.do_step(t, h).expect("step"));
                t += h;
            })
        });
        let mut driver = planar(elements);
        let mut t = Time::ZERO;
        group.bench_function(BenchmarkId::new("nonlinear", elements), |b| {
            b.iter(|| {
                black_box(driver.do_step(t, h).expect("step"));
                t += h;
            })
        });
    }
    group.finish();
}

criterion_group!(benches, steps);
criterion_main!(benches);
