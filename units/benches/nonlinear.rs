//! Criterion benchmark of the nonlinear section: one 1 ms HHT-alpha step (Newton
//! to 1e-8) of seed 002's steel cable (pinned-pinned, 20 m, moderate-rotation
//! element) driven near its first frequency by a harmonic line load large
//! enough to make it membrane-dominated, against element count. The real-time
//! capacity is the largest DOF count whose step takes less than 1 ms.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use slender_units::nonlinear::{NonlinearParams, NonlinearSection};
use slender_units::{Driver, Time};
use std::hint::black_box;

fn cable(elements: usize, formulation: &str) -> Driver<NonlinearSection> {
    let text = format!(
        r#"
formulation = "{formulation}"
segments = [{{ length = 20.0, elements = {elements}, axial_stiffness = 4.1233e8, bending_stiffness = 6.4427e4, mass_per_length = 15.315 }}]
ends.start = {{ kind = "pinned" }}
ends.end = {{ kind = "pinned" }}
integrator = {{ kind = "hht", alpha = 0.05, tolerance = 1e-8 }}
loads = [{{ z = {{ amplitude = 300.0, angular_frequency = 1.6 }} }}]
"#
    );
    let params: NonlinearParams = toml::from_str(&text).expect("parameters");
    let mut driver = Driver::new(NonlinearSection::new(params).expect("section"));
    driver.initialize(Time::ZERO).expect("initialize");
    // Into the motion: 2 s of response first.
    let h = Time::from_secs(1e-3).expect("step");
    let mut t = Time::ZERO;
    for _ in 0..2000 {
        driver.do_step(t, h).expect("step");
        t += h;
    }
    driver
}

fn steps(c: &mut Criterion) {
    let mut group = c.benchmark_group("nonlinear_step_1ms");
    group.sample_size(20);
    for formulation in ["corotational", "seed002"] {
        for elements in [10, 100, 1000, 10_000] {
            let mut driver = cable(elements, formulation);
            let h = Time::from_secs(1e-3).expect("step");
            let mut t = Time::from_secs(2.0).expect("t");
            let id = BenchmarkId::new(formulation, 3 * (elements + 1) - 4);
            group.bench_function(id, |b| {
                b.iter(|| {
                    black_box(driver.do_step(t, h).expect("step"));
                    t += h;
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, steps);
criterion_main!(benches);
