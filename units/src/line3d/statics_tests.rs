//! The 3D line's statics against closed forms: the elastic catenary hanging
//! and on the seabed, MoorPy's catenary regression values, and a taut line
//! across a current.

use super::Line3d;
use super::catenary::CatenaryLine;
use super::tests::{laid_line, line, output, started};
use crate::contract::Driver;

/// Fairlead force (H, V) the line exerts on what holds it (N).
fn fairlead_force(d: &Driver<Line3d>) -> [f64; 2] {
    let h = output(d, "end_force_x").hypot(output(d, "end_force_y"));
    [h, -output(d, "end_force_z")]
}

#[test]
fn a_hanging_line_converges_to_the_elastic_catenary_at_second_order() {
    let exact = CatenaryLine {
        length: 350.0,
        axial_stiffness: 1e8,
        weight: 50.0,
        seabed: false,
    }
    .solve(300.0, 100.0)
    .unwrap();
    let errors: Vec<[f64; 2]> = [80, 160, 320]
        .iter()
        .map(|&n| {
            let [h, v] = fairlead_force(&started(line(n, 0.0, "")));
            [h / exact.horizontal - 1.0, v / exact.vertical - 1.0]
        })
        .collect();
    for k in 0..2 {
        let order = (errors[1][k] / errors[2][k]).log2();
        assert!(
            (order - 2.0).abs() < 0.05,
            "observed order {order} ({errors:?})"
        );
        // Richardson from 160 and 320 elements.
        let extrapolated = errors[2][k] + (errors[2][k] - errors[1][k]) / 3.0;
        assert!(extrapolated.abs() < 1e-7, "{extrapolated:e} ({errors:?})");
    }
    assert!(errors[2][0].abs() < 5e-6, "{errors:?}");
}

#[test]
fn a_line_lying_on_the_seabed_approaches_the_catenary_with_its_touchdown_node() {
    let exact = CatenaryLine {
        length: 380.0,
        axial_stiffness: 1e8,
        weight: 50.0,
        seabed: true,
    }
    .solve(300.0, 100.0)
    .unwrap();
    // Nodal contact puts the touchdown at a node: the error falls with the
    // element but not smoothly (first order in the touchdown's position).
    let mut previous = f64::INFINITY;
    for n in [76, 304] {
        let d = started(laid_line(n, 0.0, ""));
        let [h, v] = fairlead_force(&d);
        let element = 380.0 / n as f64;
        let touchdown = output(&d, "touchdown_arc");
        assert!(
            (touchdown - exact.laid_length()).abs() <= element,
            "{touchdown} {}",
            exact.laid_length()
        );
        let error = (h / exact.horizontal - 1.0)
            .abs()
            .max((v / exact.vertical - 1.0).abs());
        assert!(error < previous / 2.0, "{n}: {error:e} after {previous:e}");
        previous = error;
    }
    assert!(previous < 1e-3, "{previous:e}");
}

#[test]
fn a_taut_vertical_line_across_a_current_carries_its_drag_at_its_ends() {
    // 99.9 m between points 100 m apart: 1e5 N of tension; 1 m/s across.
    let text = r#"
length = 99.9
elements = 50
axial_stiffness = 1.0e8
mass_per_length = 8.0
diameter = 0.1
drag_normal = 1.2
start = { position = [0.0, 0.0, -100.0] }
end = { position = [0.0, 0.0, 0.0] }
current = [{ depth = 0.0, speed = 1.0, heading_deg = 90.0 }]
"#;
    let d = started(toml::from_str(text).unwrap());
    let drag_per_length = 0.5 * 1025.0 * 0.1 * 1.2;
    let total = drag_per_length * 99.9;
    let held = output(&d, "start_force_y") + output(&d, "end_force_y");
    // The line leans by ~1/30 rad: the normal speed falls by ~1e-3 of it.
    assert!((held / total - 1.0).abs() < 2e-3, "{held} against {total}");
    assert!(output(&d, "start_force_x").abs() < 1e-6 * total);
    // Its sag at mid-depth: q L^2 / (8 T), with the tension the sag itself
    // raised (by ~12 % over the 1e5 N of the straight line).
    let mut tensions = vec![0.0; 50];
    d.unit().write_field(3, &mut tensions).unwrap();
    let tension = tensions[25];
    assert!(tension > 1.05e5, "{tension}");
    let mut y = vec![0.0; 51];
    d.unit().write_field(1, &mut y).unwrap();
    let sag = drag_per_length * 100.0f64.powi(2) / (8.0 * tension);
    assert!((y[25] / sag - 1.0).abs() < 1e-2, "{} against {sag}", y[25]);
}

/// MoorPy's catenary cases: (x, z, L, EA, w), a seabed, (H, V, laid).
const MOORPY_CASES: [([f64; 5], bool, [f64; 3]); 6] = [
    (
        [400.0, 200.0, 500.0, 7.51e12, 800.0],
        true,
        [96643.43501616362, 237751.75997440016, 202.81030003199982],
    ),
    (
        [400.0, 200.0, 500.0, 7.51e12, 200.0],
        false,
        [43694.580989249596, 77634.40064978378, 0.0],
    ),
    (
        [89.9, 59.2, 130.0, 7.51e8, 881.05],
        false,
        [31373.229006023103, 87886.15872988368, 0.0],
    ),
    (
        [
            246.22420940032947,
            263.55766330843164,
            360.63566262396927 - 0.01,
            700e6,
            3.08735,
        ],
        true,
        [71116.8, 76680.6, 0.0],
    ),
    (
        [
            246.22420940032947,
            263.55766330843164,
            360.63566262396927 + 0.01,
            700e6,
            3.08735,
        ],
        true,
        [46077.1, 49878.6, 0.0],
    ),
    (
        [
            119.3237383002058,
            52.49668849178113,
            130.36140355177318,
            7e8,
            34.91060469991227,
        ],
        true,
        [72694.145, 34266.168, 0.0],
    ),
];

#[test]
fn the_catenary_reproduces_moorpys_regression_values() {
    // MoorPy's tests/test_catenary.py (NREL/MoorPy): inputs x, z, L, EA, w
    // and its seabed (CB = 0: on the seabed without friction; CB < 0: a
    // seabed the line does not reach), and the fairlead's H and V and the
    // laid length it gives (rtol 1e-5 there; the near-taut cases' values
    // are rounded to 0.1 N). Its friction (CB > 0) and buoyant (w < 0)
    // cases are left out: the catenary here has neither.
    // Left out too: its "hardest" near-taut case (L = 360.63566262396927),
    // whose values (H 56804.6, V 60803.4) put the line's end 1.6 m from the
    // fairlead in Irvine's equations (247.43, 262.42 against 246.22,
    // 263.56); the solution here puts it there to 1e-10 m.
    for ([x, z, length, ea, w], seabed, [h, v, laid]) in MOORPY_CASES {
        let line = CatenaryLine {
            length,
            axial_stiffness: ea,
            weight: w,
            seabed,
        };
        let c = line
            .solve(x, z)
            .unwrap_or_else(|e| panic!("{x} {z} {length}: {e}"));
        let close = |got: f64, want: f64| (got - want).abs() <= 1e-5 * want.abs().max(1.0);
        assert!(
            close(c.horizontal, h) && close(c.vertical, v),
            "{x} {z} {length}: H {} V {} against {h} {v}",
            c.horizontal,
            c.vertical
        );
        assert!(
            (c.laid_length() - laid).abs() < 1e-5 * length,
            "{x} {z} {length}: laid {} against {laid}",
            c.laid_length()
        );
    }
}
