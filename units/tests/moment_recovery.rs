//! Bending moments of the co-rotational section against closed forms and a
//! converged mesh (issue 48): the element's end moments with the fixed-end
//! moments of the load along it removed, and the end elements' load moments
//! at free-rotation ends (`units/src/nonlinear/moments.rs`).

use slender_units::nonlinear::{NonlinearParams, NonlinearSection};
use slender_units::{Driver, Time, Unit};

/// The section of `text`, at its static start.
fn started(text: &str) -> Driver<NonlinearSection> {
    let params: NonlinearParams = toml::from_str(text).expect("parameters parse");
    let mut driver = Driver::new(NonlinearSection::new(params).expect("valid parameters"));
    driver.initialize(Time::ZERO).expect("initialize");
    driver
}

/// The `moment` field (N m at each node).
fn nodal_moments(section: &NonlinearSection) -> Vec<f64> {
    let k = (section.fields().iter())
        .position(|f| f.name == "moment")
        .expect("a moment field");
    let mut m = vec![0.0; section.model().reference.len()];
    section.field_values(k, &mut m).expect("moments");
    m
}

/// A stiff horizontal 20 m beam under 1 kN/m of weight with `ends` (TOML).
fn horizontal_beam(elements: usize, ends: &str) -> Driver<NonlinearSection> {
    started(&format!(
        r#"
static_start = true
segments = [{{ length = 20.0, elements = {elements}, axial_stiffness = 1e10, bending_stiffness = 1e9, mass_per_length = 100.0, submerged_weight = 1000.0 }}]
{ends}
"#
    ))
}

#[test]
fn a_simply_supported_beam_under_its_weight_has_the_closed_form_moments_at_its_nodes() {
    let ends = "ends.start = { kind = \"pinned\" }\nends.end = { kind = \"pinned\", x = \"free\" }";
    for elements in [2, 4, 10] {
        let beam = horizontal_beam(elements, ends);
        let m = nodal_moments(beam.unit());
        for (j, v) in m.iter().enumerate() {
            let x = 20.0 * j as f64 / elements as f64;
            let exact = 1000.0 * x * (20.0 - x) / 2.0;
            // Sagging is positive (the tangent turns counter-clockwise).
            assert!(
                (v - exact).abs() < 1e-5 * 50_000.0,
                "{elements} elements, node {j}: {v} N m, closed form {exact}"
            );
        }
    }
}

#[test]
fn a_clamped_beam_under_its_weight_has_the_fixed_end_moments() {
    let ends = "ends.start = { kind = \"fixed\" }\nends.end = { kind = \"fixed\", x = \"free\" }";
    let (w, l) = (1000.0, 20.0);
    for elements in [1, 2, 4] {
        let beam = horizontal_beam(elements, ends);
        let m = nodal_moments(beam.unit());
        for (j, v) in m.iter().enumerate() {
            let x = l * j as f64 / elements as f64;
            // w (6 l x - 6 x^2 - l^2) / 12: -w l^2 / 12 at the ends.
            let exact = w * (6.0 * l * x - 6.0 * x * x - l * l) / 12.0;
            assert!(
                (v - exact).abs() < 1e-5 * w * l * l / 12.0,
                "{elements} elements, node {j}: {v} N m, closed form {exact}"
            );
        }
    }
}

/// The steel catenary riser of `examples/structure_riser.toml` as one
/// section, its top at the hang-off the 200-element scene finds, in statics.
fn riser(elements: usize) -> Driver<NonlinearSection> {
    riser_moving(
        elements,
        "{ displacement = -376.4749167409535 }",
        "\"held\"",
    )
}

/// The riser with its top's x and z conditions (TOML).
fn riser_moving(elements: usize, x: &str, z: &str) -> Driver<NonlinearSection> {
    started(&format!(
        r#"
static_start = true
start = [0.0, -1000.0]
segments = [{{ length = 2000.0, angle_deg = 30.0, elements = {elements}, axial_stiffness = 4.0631e9, bending_stiffness = 4.6937e7, mass_per_length = 154.08, submerged_weight = 683.05, diameter = 0.3239, drag_normal = 1.0, added_mass_normal = 1.0 }}]
ends.start = {{ kind = "pinned" }}
ends.end = {{ kind = "pinned", x = {x}, z = {z} }}
contact = {{ method = {{ kind = "penalty", penalty = 1.0e6 }}, surface = {{ shape = {{ kind = "flat", height = -1000.0 }} }} }}
integrator = {{ kind = "hht", alpha = 0.1 }}
"#
    ))
}

/// The sag-bend moment (N m) the section reports, and the largest concave
/// moment of the elements' ends from their stiffness alone.
fn sag_bend(driver: &Driver<NonlinearSection>) -> (f64, f64) {
    let index = (driver.description().outputs.iter())
        .position(|p| p.name == "sagbend_moment")
        .expect("a sagbend_moment output");
    let mut out = vec![0.0; driver.description().outputs.len()];
    driver.outputs(&mut out).expect("outputs");
    let section = driver.unit();
    let (model, q) = (section.model(), section.displacements());
    let mut stiffness_only = 0.0f64;
    for e in 0..model.elements.len() {
        let local = model.local_forces(q, e);
        for m in [-local.moments[0], local.moments[1]] {
            if m * local.angle.cos() > 0.0 {
                stiffness_only = stiffness_only.max(m.abs());
            }
        }
    }
    (out[index], stiffness_only)
}

#[test]
fn the_riser_sag_bend_moment_at_ten_metre_elements_is_within_half_a_percent_of_a_converged_mesh() {
    let (converged, _) = sag_bend(&riser(3200));
    let mut table = Vec::new();
    for elements in [100, 200, 400, 800] {
        let (recovered, stiffness_only) = sag_bend(&riser(elements));
        table.push((
            elements,
            recovered / converged - 1.0,
            stiffness_only / converged - 1.0,
        ));
    }
    for (elements, recovered, stiffness_only) in &table {
        println!("{elements} elements: {recovered:+.2e} (stiffness only {stiffness_only:+.2e})");
    }
    let (_, at_ten_metres, before) = table[1];
    assert!(
        at_ten_metres.abs() < 5e-3,
        "{at_ten_metres:e} at 10 m elements"
    );
    // What the recovery removes: the stiffness-only end moments are 3 % high.
    assert!(before > 2e-2, "stiffness-only moments {before:e} off");
    // And the error falls with the mesh.
    assert!(table[3].1.abs() < table[1].1.abs());
}

/// The concave peak of the `moment` field (N m) every 0.05 s over 20-200 s of
/// the riser under the example's heave and surge, stepped at `step` (s).
fn dynamic_sag_bend(elements: usize, step: f64) -> Vec<f64> {
    let x = "{ displacement = { offset = -376.4749167409535, amplitude = 5.0, angular_frequency = 0.06283185307179587, fade_in = 20.0 } }";
    let z = "{ displacement = { amplitude = 2.0, angular_frequency = 0.6283185307179586, fade_in = 20.0 } }";
    let mut driver = riser_moving(elements, x, z);
    let every = (0.05 / step).round() as usize;
    let h = Time::from_secs(step).expect("a step");
    let mut peaks = Vec::new();
    for k in 0..(200.0 / step).round() as usize {
        driver
            .do_step(Time::from_secs(k as f64 * step).expect("a time"), h)
            .expect("a step");
        if (k + 1) % every == 0 && (k + 1) as f64 * step > 20.0 {
            let m = nodal_moments(driver.unit());
            peaks.push(m.iter().copied().fold(f64::NEG_INFINITY, f64::max));
        }
    }
    peaks
}

#[test]
#[ignore = "on demand (about two minutes): the dynamic figures in docs/nonlinear-section.md"]
fn the_riser_dynamic_sag_bend_moment_at_ten_metre_elements_is_within_half_a_percent() {
    let reference = dynamic_sag_bend(1600, 0.0125);
    let mean = |x: &[f64]| x.iter().sum::<f64>() / x.len() as f64;
    let rms = |x: &[f64]| (x.iter().map(|v| v * v).sum::<f64>() / x.len() as f64).sqrt();
    for elements in [100, 200, 400] {
        let run = dynamic_sag_bend(elements, 0.05);
        let difference: Vec<f64> = run.iter().zip(&reference).map(|(a, b)| a - b).collect();
        let (offset, spread) = (
            mean(&run) / mean(&reference) - 1.0,
            rms(&difference) / rms(&reference),
        );
        println!("{elements} elements: mean {offset:+.2e}, RMS difference {spread:.2e}");
        if elements == 200 {
            assert!(offset.abs() < 5e-3, "mean {offset:e} at 10 m elements");
        }
    }
}
