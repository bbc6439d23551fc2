//! Eigenperiods of the 1934 m polyester line (seed 000 Table 3) from the cable
//! unit's modal analysis at its static state.

use crate::support::published;
use slender_units::Driver;
use slender_units::Time;
use slender_units::cable::CableParams;
use slender_units::cable::{Cable, Effects};

/// Periods of the first 15 modes with the given stiffness factor, effects, top
/// force angle from the vertical (deg) and element count.
fn periods(stiffness_factor: f64, effects: Effects, angle_deg: f64, elements: usize) -> Vec<f64> {
    let mut p = CableParams::seed000_polyester(elements);
    p.youngs_modulus *= stiffness_factor;
    let mut cable = Driver::new(Cable::new(p, effects).unwrap());
    let a = angle_deg.to_radians();
    cable
        .set_inputs(&[2.5e6 * a.sin(), 2.5e6 * a.cos(), 0.0, 0.0])
        .unwrap();
    cable.initialize(Time::ZERO).unwrap();
    cable
        .modes(15)
        .unwrap()
        .modes
        .iter()
        .map(|m| m.period)
        .collect()
}

fn weightless() -> Effects {
    Effects {
        added_mass: true,
        geometric_stiffness: true,
        ..Effects::default()
    }
}

/// Compares with published periods printed to 0.01 s: allowed deviation is
/// `tolerance` (relative) plus half a unit of the last printed digit.
fn compare(label: &str, ours: &[f64], reference: &[f64], modes: usize, tolerance: f64) {
    eprintln!("{label}");
    let mut worst: f64 = 0.0;
    for (i, (o, r)) in ours.iter().zip(reference).enumerate().take(modes) {
        let e = (o - r) / r;
        worst = worst.max(e.abs());
        eprintln!(
            "  mode {:>2}: {o:>7.3} s  published {r:>6.2} s  {:>+7.3} %",
            i + 1,
            100.0 * e
        );
        assert!(
            (o - r).abs() <= tolerance * r + 0.005,
            "{label} mode {}: {o} vs {r}",
            i + 1
        );
    }
    eprintln!("  largest deviation {:.3} %", 100.0 * worst);
}

#[test]
fn stiff_weightless_vertical_line_matches_the_analytical_string() {
    let table = published();
    let analytical = &table["eigenperiods"]["analytical_string"];
    let ours = periods(10.0, weightless(), 0.0, 500);
    for (i, (t, exact)) in ours.iter().zip(string_periods()).enumerate() {
        assert!(
            ((t - exact) / exact).abs() < 5e-4,
            "mode {}: {t} vs {exact}",
            i + 1
        );
    }
    compare(
        "10x stiffness, weightless, vertical, 500 elements vs analytical string (Table 3 col. 2)",
        &ours,
        &as_vec(analytical),
        15,
        1e-3,
    );
}

#[test]
fn eighty_elements_are_within_one_percent_of_the_string_for_thirteen_modes() {
    let analytical = string_periods();
    let ours = periods(10.0, weightless(), 0.0, 80);
    for i in 0..13 {
        let e = (ours[i] - analytical[i]) / analytical[i];
        assert!(
            e.abs() < 0.01,
            "mode {}: {} vs {}",
            i + 1,
            ours[i],
            analytical[i]
        );
    }
    // Beyond, fewer than 12 elements per wavelength: the error grows past 1 %.
    assert!(((ours[14] - analytical[14]) / analytical[14]).abs() > 0.01);
}

#[test]
fn eighty_elements_match_the_published_fe_columns() {
    let t = &published()["eigenperiods"];
    let cases = [
        (
            "10x stiffness, weightless, vertical, 80 el (col. 4)",
            10.0,
            weightless(),
            0.0,
            "stiff10_weightless_vertical_80el",
            15,
        ),
        (
            "nominal, weightless, vertical, 80 el (col. 5)",
            1.0,
            weightless(),
            0.0,
            "nominal_weightless_vertical_80el",
            15,
        ),
        (
            "nominal, weight, vertical, 80 el (col. 6)",
            1.0,
            Effects {
                weight: true,
                ..weightless()
            },
            0.0,
            "nominal_weight_vertical_80el",
            15,
        ),
        (
            "nominal, weight, oblique, 80 el (col. 7)",
            1.0,
            Effects {
                weight: true,
                ..weightless()
            },
            50.0,
            "nominal_weight_oblique_80el",
            15,
        ),
        (
            "nominal, weight, oblique, current, 80 el (col. 8)",
            1.0,
            Effects {
                weight: true,
                drag: true,
                current: true,
                ..weightless()
            },
            50.0,
            "nominal_weight_oblique_current_80el",
            15,
        ),
    ];
    for (label, factor, effects, angle, column, modes) in cases {
        let ours = periods(factor, effects, angle, 80);
        compare(label, &ours, &as_vec(&t[column]), modes, 1e-2);
    }
}

/// Seed 000 eq. 9 with our parameters (rho = 1025): T_i = 4L / (2i - 1) sqrt(m / T0),
/// m = structural + added mass per length.
fn string_periods() -> Vec<f64> {
    let line = CableParams::seed000_polyester(80);
    let area = std::f64::consts::PI * line.diameter.powi(2) / 4.0;
    let m = line.mass_per_length + line.water_density * area * line.added_mass_normal;
    (0..15)
        .map(|i| 4.0 * line.length / (2 * i + 1) as f64 * (m / 2.5e6).sqrt())
        .collect()
}

fn as_vec(v: &toml::Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_float().unwrap())
        .collect()
}

#[test]
fn the_truncation_point_of_the_nominal_line() {
    use slender_units::cable::Section;
    let mut p = CableParams::seed000_polyester(80);
    let a = 50f64.to_radians();
    p.static_top_force = Some([2.5e6 * a.sin(), 2.5e6 * a.cos()]);
    p.section = Section::Lower {
        truncation_ratio: 0.8,
    };
    let lower = Driver::new(Cable::new(p, Effects::all()).unwrap());
    let k = lower.element_count();
    let top = lower.bottom_position();
    assert_eq!(top, [0.0, 0.0]);
    let mut full =
        Driver::new(Cable::new(CableParams::seed000_polyester(80), Effects::all()).unwrap());
    full.set_inputs(&[2.5e6 * a.sin(), 2.5e6 * a.cos(), 0.0, 0.0])
        .unwrap();
    full.initialize(Time::ZERO).unwrap();
    let x = &full.static_state().unwrap().positions;
    let (e0, e1) = (x[k - 1], x[k + 1]);
    let angle = (e1[1] - e0[1]).atan2(e1[0] - e0[0]).to_degrees();
    eprintln!(
        "truncation node {k} of 80 at ({:.1}, {:.1}) m, line at {angle:.2} deg from the horizontal (paper: 39.2); top at ({:.1}, {:.1}) m",
        x[k][0], x[k][1], x[80][0], x[80][1]
    );
    assert!((x[k][1] - 960.0).abs() < 0.5 * 1934.0 / 80.0);
    assert!((angle - 39.2).abs() < 1.0);
}
