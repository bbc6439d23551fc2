//! Criterion benchmark: one step of the 4x4 span between two sections
//! (`span_coupling`) by order, against an FE span with the same four end
//! conditions by element count. Run with
//! `cargo bench -p slender-units --bench span_coupling`.

use criterion::{Criterion, criterion_group, criterion_main};
use slender_units::beam::boundary::{Boundary, Condition, InputMarker, Quantity, TimeFunction};
use slender_units::beam::{Beam, BeamParams};
use slender_units::span::coupling::{Orientation, SpanCoupling, SpanCouplingParams};
use slender_units::{Driver, Time, Unit};
use std::hint::black_box;

fn fe_span(elements: usize) -> Beam {
    let cond = |quantity| Condition {
        quantity,
        value: TimeFunction::Input(InputMarker::Input),
    };
    let mut p = BeamParams::new(
        10.0,
        elements,
        1.0e4,
        1.0e2,
        Boundary {
            left: [cond(Quantity::Deflection), cond(Quantity::Rotation)],
            right: [cond(Quantity::Moment), cond(Quantity::Shear)],
        },
    );
    p.damping_per_length = 5.0;
    p.alpha = 0.05;
    Beam::new(p).expect("beam")
}

fn step(c: &mut Criterion) {
    let mut group = c.benchmark_group("span_between_sections");
    let mut units: Vec<(String, Box<dyn Unit>)> = Vec::new();
    for order in [16, 24, 32] {
        let params = SpanCouplingParams {
            flexural_rigidity: 1.0e4,
            mass_per_length: 1.0e2,
            damping_per_length: 5.0,
            length: 10.0,
            tension: 0.0,
            orientation: Orientation::UpperMotion,
            order,
            band: 2.0 * std::f64::consts::PI * 10.0,
            discretization: Default::default(),
            alpha: 0.0,
        };
        units.push((
            format!("span_coupling/{order}"),
            Box::new(SpanCoupling::new(params).expect("fit")),
        ));
    }
    for elements in [8, 16, 32, 64] {
        units.push((format!("fe/{elements}"), Box::new(fe_span(elements))));
    }
    let h = Time::from_secs(0.001).expect("step");
    // Inputs from a table computed beforehand, so only the unit's work is timed.
    let table: Vec<[f64; 4]> = (0..4096)
        .map(|k| {
            let t = k as f64 * 1e-3;
            [
                0.01 * t.sin(),
                0.001 * t.cos(),
                10.0 * t.sin(),
                2.0 * t.cos(),
            ]
        })
        .collect();
    for (name, unit) in units {
        let mut unit = Driver::new(unit);
        unit.set_inputs(&[0.0; 4]).expect("inputs");
        unit.initialize(Time::ZERO).expect("initialises");
        let mut out = vec![0.0; unit.description().outputs.len()];
        let mut k = 0_i64;
        group.bench_function(name, |b| {
            b.iter(|| {
                let u = &table[k as usize % table.len()];
                unit.set_inputs(black_box(u)).expect("inputs");
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
