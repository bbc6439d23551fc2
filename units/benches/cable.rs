//! Criterion benchmarks of the cable unit: one synchronisation step of the whole
//! polyester line (seed 000, all effects, 10 ms) against element count.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use slender_units::cable::{Cable, CableParams, Effects};
use slender_units::{Driver, Time};
use std::hint::black_box;

fn line(elements: usize) -> Driver<Cable> {
    let p = CableParams::seed000_polyester(elements);
    let mut c = Driver::new(Cable::new(p, Effects::all()).unwrap());
    let a = 50f64.to_radians();
    c.set_inputs(&[2.5e6 * a.sin(), 2.5e6 * a.cos(), 0.0, 0.0])
        .unwrap();
    c.initialize(Time::ZERO).unwrap();
    c
}

fn step(c: &mut Criterion) {
    let h = Time::from_nanos(10_000_000);
    let mut group = c.benchmark_group("cable_step_10ms");
    for elements in [20, 80, 320] {
        let mut cable = line(elements);
        let a = 50f64.to_radians();
        let mut k = 0i64;
        group.bench_with_input(BenchmarkId::from_parameter(elements), &elements, |b, _| {
            b.iter(|| {
                k += 1;
                let t = k as f64 * 0.01;
                // A 0.1 Hz, 250 kN wave load on top of the static tension.
                let f = 2.5e6 + 2.5e5 * (0.6 * t).sin();
                cable
                    .set_inputs(&[f * a.sin(), f * a.cos(), 0.0, 0.0])
                    .unwrap();
                cable.do_step(h * (k - 1), h).unwrap();
                let mut out = [0.0; 8];
                cable.outputs(&mut out).unwrap();
                black_box(out)
            })
        });
    }
    group.finish();
}

criterion_group!(benches, step);
criterion_main!(benches);
