//! Criterion benchmarks: cost of the coupling benchmarks per scheme, and the
//! master's own overhead per connection per iteration.
//!
//! Run with `cargo bench -p slender-master`; figures go to BENCHMARKS.md.

use criterion::{Criterion, criterion_group, criterion_main};
use slender_coupling::settings::{Acceleration, MasterSettings, Scheme};
use slender_coupling::{Link, Master, System};
use slender_scene::Scene;
use slender_units::benchmark::algebraic_loop::{LinearPair, LinearPairParams};
use slender_units::{Driver, Time, Unit};
use std::hint::black_box;
use std::path::Path;

fn scene(name: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name);
    Scene::load(&path).expect("example scene loads")
}

fn run(scene: &Scene) -> u64 {
    let mut master = scene.build().expect("builds");
    master.initialize(scene.start).expect("initialises");
    for _ in 0..scene.steps {
        master.step().expect("steps");
    }
    master.counters().iterations
}

/// B1-B3, each scheme: one whole run (1 s, 10 s, 2 s simulated).
fn schemes(c: &mut Criterion) {
    let mut group = c.benchmark_group("scheme");
    for (file, name) in [
        ("b1_two_masses.toml", "b1"),
        ("b2_stiff_oscillator.toml", "b2"),
        ("b3_force_displacement.toml", "b3"),
    ] {
        for scheme in [
            Scheme::Jacobi,
            Scheme::GaussSeidel,
            Scheme::IterativeJacobi,
            Scheme::IterativeGaussSeidel,
        ] {
            let mut s = scene(file);
            s.spec.master.scheme = scheme;
            if !scheme.is_iterative() {
                s.spec.master.acceleration = Acceleration::None;
            }
            group.bench_function(format!("{name}/{}", scheme.name()), |b| {
                b.iter(|| black_box(run(&s)))
            });
        }
    }
    group.finish();
}

/// A chain of `n` stateless units (a cheap `do_step`) joined by n - 1 connections
/// and one loop back, stepped with plain iterative Jacobi for 1000 steps: the
/// time per connection per iteration is almost all master overhead.
fn overhead(c: &mut Criterion) {
    let n = 64;
    let build = || {
        let mut system = System::new();
        for i in 0..n {
            let unit: Box<dyn Unit> = Box::new(LinearPair::new(LinearPairParams {}));
            system.add_unit(&format!("u{i}"), unit).unwrap();
        }
        for i in 0..n {
            let link = Link {
                gain: 0.0, // keeps values bounded: one iteration converges
                ..Link::default()
            };
            system
                .connect(&format!("u{i}.a"), &format!("u{}.c", (i + 1) % n), link)
                .unwrap();
        }
        let settings = MasterSettings::new(Scheme::IterativeJacobi);
        Master::new(system, settings, Time::from_nanos(1_000_000)).unwrap()
    };
    c.bench_function("master_overhead/64_units_64_connections_1000_steps", |b| {
        b.iter_batched(
            || {
                let mut m = build();
                m.initialize(Time::ZERO).unwrap();
                m
            },
            |mut m| {
                for _ in 0..1000 {
                    m.step().unwrap();
                }
                black_box(m.counters().iterations)
            },
            criterion::BatchSize::LargeInput,
        )
    });
}

/// The same 64 units stepped directly, without the master: subtracting this from
/// `master_overhead` leaves the master's own cost.
fn baseline(c: &mut Criterion) {
    let n = 64;
    let h = Time::from_nanos(1_000_000);
    c.bench_function("master_overhead/baseline_64_units_direct_1000_steps", |b| {
        b.iter_batched(
            || {
                let mut units: Vec<Driver<LinearPair>> = (0..n)
                    .map(|_| Driver::new(LinearPair::new(LinearPairParams {})))
                    .collect();
                for u in &mut units {
                    u.set_inputs(&[0.0]).unwrap();
                    u.initialize(Time::ZERO).unwrap();
                }
                units
            },
            |mut units| {
                let mut out = [0.0; 2];
                let mut t = Time::ZERO;
                for _ in 0..1000 {
                    for u in &mut units {
                        u.set_inputs(&[0.0 * out[0]]).unwrap();
                        u.do_step(t, h).unwrap();
                        u.outputs(&mut out).unwrap();
                    }
                    t += h;
                }
                black_box(out)
            },
            criterion::BatchSize::LargeInput,
        )
    });
}

criterion_group!(benches, schemes, overhead, baseline);
criterion_main!(benches);
