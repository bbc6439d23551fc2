//! Criterion benchmark of the beam unit: one 10 ms HHT-alpha step of the seed 004
//! pipe lying down on the seabed (penalty contact, p = 1e4, support end heaving)
//! against element count.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use slender_units::beam::boundary::{Boundary, Condition, Expression, Quantity, TimeFunction};
use slender_units::beam::{Beam, BeamParams, ContactIntegration, ContactParams};
use slender_units::contact::Law;
use slender_units::contact::surface::{Motion, Shape, Surface};
use slender_units::{Driver, Time};
use std::hint::black_box;

fn pipe(elements: usize) -> Driver<Beam> {
    let c = |quantity, value| Condition { quantity, value };
    let mut p = BeamParams::new(
        10.0,
        elements,
        1e4,
        10.0,
        Boundary {
            left: [
                c(
                    Quantity::Deflection,
                    TimeFunction::Expression(Expression {
                        offset: 1.0,
                        amplitude: 0.25,
                        angular_frequency: 0.3,
                        ..Default::default()
                    }),
                ),
                c(Quantity::Rotation, TimeFunction::Constant(-0.5)),
            ],
            right: [
                c(Quantity::Moment, TimeFunction::Constant(0.0)),
                c(Quantity::Shear, TimeFunction::Constant(0.0)),
            ],
        },
    );
    p.static_start = true;
    p.alpha = 0.05;
    p.newton_tolerance = 1e-8;
    p.contact = Some(ContactParams {
        method: Law::Penalty { penalty: 1e4 },
        surface: Surface {
            shape: Shape::Flat { height: 0.0 },
            motion: Motion::None,
        },
        integration: ContactIntegration::Gauss,
        damping: 0.0,
        gap_band: 0.0,
    });
    let mut b = Driver::new(Beam::new(p).unwrap());
    b.initialize(Time::ZERO).unwrap();
    b
}

fn step(c: &mut Criterion) {
    let h = Time::from_nanos(10_000_000);
    let mut group = c.benchmark_group("beam_contact_step_10ms");
    for elements in [12, 25, 50, 100] {
        let mut beam = pipe(elements);
        let mut k = 0i64;
        group.bench_with_input(BenchmarkId::from_parameter(elements), &elements, |b, _| {
            b.iter(|| {
                beam.do_step(h * k, h).unwrap();
                k += 1;
                black_box(beam.unit().last_newton_iterations())
            })
        });
    }
    group.finish();
}

criterion_group!(benches, step);
criterion_main!(benches);
