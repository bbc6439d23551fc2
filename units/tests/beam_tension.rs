//! The beam with a constant axial tension (issue 13: a small-deflection section
//! that carries tension, EI y'''' - T y'' + c_d y' + mu y'' = w): frequencies of a
//! pinned-pinned tensioned beam against the exact ones, the taut-string limit
//! (EI -> 0) n pi / L sqrt(T / mu), and the static deflection under a uniform
//! load against the closed form.

use crate::support::beams::{cond, params};
use slender_units::beam::Beam;
use slender_units::beam::boundary::{Boundary, Quantity};
use slender_units::{Driver, Time};
use std::f64::consts::PI;

fn pinned() -> Boundary {
    Boundary {
        left: [cond(Quantity::Deflection, 0.0), cond(Quantity::Moment, 0.0)],
        right: [cond(Quantity::Deflection, 0.0), cond(Quantity::Moment, 0.0)],
    }
}

fn omegas(ei: f64, tension: f64, elements: usize) -> Vec<f64> {
    let mut p = params(elements, pinned());
    p.flexural_rigidity = ei;
    p.tension = tension;
    let mut beam = Driver::new(Beam::new(p).expect("valid"));
    beam.initialize(Time::ZERO).expect("initialize");
    beam.modes(4)
        .expect("modes")
        .modes
        .iter()
        .map(|m| 2.0 * PI / m.period)
        .collect()
}

#[test]
fn a_pinned_tensioned_beam_has_the_exact_frequencies_and_tends_to_the_taut_string() {
    let (l, mu) = (10.0, 10.0);
    for (ei, tension, tolerance) in [(1e4, 1e4, 1e-5), (1e-3, 1e4, 1e-5), (1e4, 0.0, 1e-5)] {
        let got = omegas(ei, tension, 80);
        for (n, w) in got.iter().enumerate() {
            let k = (n + 1) as f64 * PI / l;
            let exact = ((ei * k.powi(4) + tension * k * k) / mu).sqrt();
            println!(
                "EI {ei}, T {tension}: mode {} {w:.6} rad/s, exact {exact:.6}",
                n + 1
            );
            assert!(
                ((w - exact) / exact).abs() < tolerance,
                "mode {}: {w} against {exact}",
                n + 1
            );
        }
    }
    // The string limit n pi / L sqrt(T / mu) at EI = 1e-3 N m^2.
    let string = omegas(1e-3, 1e4, 80);
    for (n, w) in string.iter().enumerate() {
        let limit = (n + 1) as f64 * PI / l * (1e4 / mu).sqrt();
        assert!(
            ((w - limit) / limit).abs() < 1e-5,
            "mode {}: {w} against {limit}",
            n + 1
        );
    }
}

#[test]
fn a_tensioned_beam_under_a_uniform_load_deflects_as_the_closed_form() {
    // y = w x (L - x) / (2 T) + (w EI / T^2) (cosh(k (x - L/2)) / cosh(k L / 2) - 1),
    // k^2 = T / EI, for pinned ends.
    let (l, ei, tension, w) = (10.0, 1e4, 5e4, -100.0);
    let mut p = params(40, pinned());
    p.tension = tension;
    p.distributed_load = vec![w];
    p.static_start = true;
    let mut beam = Driver::new(Beam::new(p).expect("valid"));
    beam.initialize(Time::ZERO).expect("static");
    let k = (tension / ei).sqrt();
    let exact = |x: f64| {
        w * x * (l - x) / (2.0 * tension)
            + w * ei / (tension * tension)
                * ((k * (x - l / 2.0)).cosh() / (k * l / 2.0).cosh() - 1.0)
    };
    let q = beam.unit().deflections();
    let mut worst = 0.0f64;
    for (node, d) in q.iter().enumerate() {
        let x = l * node as f64 / 40.0;
        worst = worst.max((d[0] - exact(x)).abs());
    }
    let mid = exact(l / 2.0).abs();
    println!(
        "midspan {:.6e} m (exact {:.6e}), worst nodal difference {worst:.2e} m",
        q[20][0],
        exact(l / 2.0)
    );
    assert!(
        worst < 1e-6 * mid,
        "worst {worst} against a midspan deflection of {mid}"
    );
}
