//! Criterion benchmark: one synchronisation step (inputs set, step, outputs read) of
//! the SISO span unit H_{U2 -> U5} by approximation and order, against the FE span
//! with the same boundary conditions by element count. Inputs come from a table
//! computed beforehand, so only the unit's work is timed. Run with
//! `cargo bench -p slender-units --bench span`.

use criterion::{Criterion, criterion_group, criterion_main};
use slender_units::beam::boundary::{Boundary, Condition, InputMarker, Quantity, TimeFunction};
use slender_units::beam::{Beam, BeamParams};
use slender_units::span::unit::{Approximation, SpanParams, SpanUnit};
use slender_units::{Driver, Time, Unit};
use std::hint::black_box;

const EI: f64 = 1.0e4;
const MU: f64 = 1.0e2;
const CD: f64 = 5.0;
const L: f64 = 10.0;

fn fe_span(elements: usize) -> Beam {
    let cond = |quantity, value| Condition { quantity, value };
    let mut p = BeamParams::new(
        L,
        elements,
        EI,
        MU,
        Boundary {
            left: [
                cond(Quantity::Deflection, TimeFunction::Constant(0.0)),
                cond(Quantity::Rotation, TimeFunction::Input(InputMarker::Input)),
            ],
            right: [
                cond(Quantity::Moment, TimeFunction::Constant(0.0)),
                cond(Quantity::Shear, TimeFunction::Constant(0.0)),
            ],
        },
    );
    p.damping_per_length = CD;
    Beam::new(p).expect("beam")
}

fn span(approximation: Approximation, order: usize) -> SpanUnit {
    SpanUnit::new(SpanParams {
        flexural_rigidity: EI,
        mass_per_length: MU,
        damping_per_length: CD,
        length: L,
        tension: 0.0,
        approximation,
        order,
        band: 2.0 * std::f64::consts::PI * 10.0,
    })
    .expect("span")
}

fn step(c: &mut Criterion) {
    let mut group = c.benchmark_group("span_siso");
    let mut units: Vec<(String, Box<dyn Unit>)> = Vec::new();
    for order in [8, 12] {
        units.push((
            format!("function_pade/{order}"),
            Box::new(span(Approximation::FunctionPade, order)),
        ));
    }
    units.push(("fit/16".into(), Box::new(span(Approximation::Fit, 16))));
    for elements in [8, 16, 32] {
        units.push((format!("fe/{elements}"), Box::new(fe_span(elements))));
    }
    let h = Time::from_secs(0.01).expect("step");
    let table: Vec<f64> = (0..4096)
        .map(|k| 0.01 * (0.3 * k as f64 * 0.01).sin())
        .collect();
    for (name, unit) in units {
        let mut unit = Driver::new(unit);
        unit.set_inputs(&[0.0]).expect("inputs");
        unit.initialize(Time::ZERO).expect("initialises");
        let mut out = vec![0.0; unit.description().outputs.len()];
        let mut k = 0_i64;
        group.bench_function(name, |b| {
            b.iter(|| {
                let u = table[k as usize % table.len()];
                unit.set_inputs(black_box(&[u])).expect("inputs");
                unit.do_step(h * k, h).expect("steps");
                unit.outputs(&mut out).expect("outputs");
                k += 1;
            })
        });
    }
    group.finish();
}

criterion_group!(benches, step);
criterion_main!(benches);
