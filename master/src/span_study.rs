//! The suspended span (seed 004 ch. 5) from the command line: Bode plots of the
//! exact transfer function against its rational approximations and the FE span,
//! and accuracy against cost of span units and FE spans under the same end motion.

use serde::Serialize;
use slender_units::beam::boundary::{Boundary, Condition, InputMarker, Quantity, TimeFunction};
use slender_units::beam::{Beam, BeamParams};
use slender_units::span::transfer::{C64, Span};
use slender_units::span::unit::{Approximation, SpanParams, SpanUnit};
use slender_units::{Time, Unit};
use std::time::Instant;

/// An FE span with the same boundary conditions as the span unit: y(0) = 0, the
/// rotation at x = 0 as input, a free lower end.
pub fn fe_span(span: &Span, elements: usize) -> Result<Beam, String> {
    let cond = |quantity, value| Condition { quantity, value };
    let mut p = BeamParams::new(
        span.length,
        elements,
        span.flexural_rigidity,
        span.mass_per_length,
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
    p.damping_per_length = span.damping_per_length;
    p.newton_max_iterations = 5;
    Beam::new(p).map_err(|e| e.to_string())
}

/// Deflection (m) at the span's lower end over time for input `u(t)` (rad), and the
/// wall time spent stepping (s).
fn respond(
    unit: &mut dyn Unit,
    output: usize,
    u: &dyn Fn(f64) -> f64,
    h: f64,
    steps: usize,
) -> Result<(Vec<f64>, f64), String> {
    unit.set_inputs(&[u(0.0)]).map_err(|e| e.to_string())?;
    unit.initialize(Time::ZERO).map_err(|e| e.to_string())?;
    let ht = Time::from_secs(h).ok_or("bad step")?;
    let mut out = vec![0.0; unit.description().outputs.len()];
    let mut y = Vec::with_capacity(steps);
    let started = Instant::now();
    for k in 0..steps {
        unit.set_inputs(&[u((k + 1) as f64 * h)])
            .map_err(|e| e.to_string())?;
        unit.do_step(ht * k as i64, ht).map_err(|e| e.to_string())?;
        unit.outputs(&mut out);
        y.push(out[output]);
    }
    Ok((y, started.elapsed().as_secs_f64()))
}

/// One model of the study.
#[derive(Clone, Debug, Serialize)]
pub struct StudyRow {
    /// "taylor", "term_pade", "function_pade", "fit" or "fe".
    pub model: String,
    /// Order in s, or number of elements.
    pub size: usize,
    /// Largest error against the reference, relative to the reference's peak, for
    /// the sum of sines and for the step.
    pub error_sines: f64,
    pub error_step: f64,
    /// Wall time per simulated second (s/s), median of the two runs.
    pub cost_per_simulated_second: f64,
    /// Poles reflected to make the approximation stable.
    pub repaired: usize,
}

/// The two end motions: a faded-in sum of sines below the third resonance, and a
/// 0.01 rad step at 1 s ramped over one step.
fn inputs(third_resonance: f64) -> [Box<dyn Fn(f64) -> f64>; 2] {
    let w = third_resonance;
    [
        Box::new(move |t: f64| {
            (1.0 - (-t / 20.0f64).exp())
                * 0.01
                * ((0.03 * w * t).sin() + 0.5 * (0.11 * w * t).sin() + 0.25 * (0.32 * w * t).sin())
        }),
        Box::new(|t: f64| if t >= 1.0 { 0.01 } else { 0.0 }),
    ]
}

/// Runs every span approximation for `orders` and the FE span for `elements`
/// against a fine FE reference (`reference_elements`), over `duration` at step h.
pub fn study(
    span: &Span,
    orders: &[usize],
    elements: &[usize],
    reference_elements: usize,
    duration: f64,
    h: f64,
) -> Result<Vec<StudyRow>, String> {
    span.validate().map_err(|e| e.to_string())?;
    let steps = (duration / h).round() as usize;
    let third =
        (7.85476 / span.length).powi(2) * (span.flexural_rigidity / span.mass_per_length).sqrt();
    let motions = inputs(third);
    let mut references = Vec::new();
    for u in &motions {
        let mut fe = fe_span(span, reference_elements)?;
        let out = fe
            .description()
            .output_index("right_deflection")
            .ok_or("no right_deflection")?;
        references.push(respond(&mut fe, out, u.as_ref(), h, steps)?.0);
    }
    let error = |y: &[f64], r: &[f64]| {
        let peak = r.iter().fold(0.0f64, |a, v| a.max(v.abs())).max(1e-300);
        y.iter()
            .zip(r)
            .fold(0.0f64, |a, (y, r)| a.max((y - r).abs()))
            / peak
    };
    let mut rows = Vec::new();
    let approximations = [
        (Approximation::Taylor, "taylor"),
        (Approximation::TermPade, "term_pade"),
        (Approximation::FunctionPade, "function_pade"),
        (Approximation::Fit, "fit"),
    ];
    for (a, name) in approximations {
        for &order in orders {
            let params = SpanParams {
                flexural_rigidity: span.flexural_rigidity,
                mass_per_length: span.mass_per_length,
                damping_per_length: span.damping_per_length,
                length: span.length,
                approximation: a,
                order,
                band: 2.0 * std::f64::consts::PI * 10.0,
            };
            let Ok(unit) = SpanUnit::new(params.clone()) else {
                continue;
            };
            let repaired = unit.system().repaired;
            let (mut errs, mut costs) = (Vec::new(), Vec::new());
            for (u, r) in motions.iter().zip(&references) {
                let mut fresh = SpanUnit::new(params.clone()).map_err(|e| e.to_string())?;
                let (y, wall) = respond(&mut fresh, 0, u.as_ref(), h, steps)?;
                errs.push(error(&y, r));
                costs.push(wall / duration);
            }
            rows.push(StudyRow {
                model: name.into(),
                size: order,
                error_sines: errs[0],
                error_step: errs[1],
                cost_per_simulated_second: 0.5 * (costs[0] + costs[1]),
                repaired,
            });
        }
    }
    for &n in elements {
        let (mut errs, mut costs) = (Vec::new(), Vec::new());
        for (u, r) in motions.iter().zip(&references) {
            let mut fe = fe_span(span, n)?;
            let out = fe
                .description()
                .output_index("right_deflection")
                .ok_or("no right_deflection")?;
            let (y, wall) = respond(&mut fe, out, u.as_ref(), h, steps)?;
            errs.push(error(&y, r));
            costs.push(wall / duration);
        }
        rows.push(StudyRow {
            model: "fe".into(),
            size: n,
            error_sines: errs[0],
            error_step: errs[1],
            cost_per_simulated_second: 0.5 * (costs[0] + costs[1]),
            repaired: 0,
        });
    }
    Ok(rows)
}

/// The rows as a Markdown table.
pub fn to_markdown(rows: &[StudyRow]) -> String {
    let mut out = String::from(
        "| model | order / elements | error, sines | error, step | cost (s per simulated s) | poles reflected |\n|---|---|---|---|---|---|\n",
    );
    for r in rows {
        out += &format!(
            "| {} | {} | {:.2e} | {:.2e} | {:.2e} | {} |\n",
            r.model, r.size, r.error_sines, r.error_step, r.cost_per_simulated_second, r.repaired
        );
    }
    out
}

/// Frequency responses for a Bode plot: (omega, exact, each approximation, FE).
pub fn bode_series(
    span: &Span,
    order: usize,
    fe_elements: usize,
    omegas: &[f64],
) -> Result<Vec<(String, Vec<C64>)>, String> {
    use slender_units::span::rational::{function_pade_u2_u5, taylor_u2_u5, term_pade_u2_u5};
    let mut series = vec![(
        "analytic".to_string(),
        omegas
            .iter()
            .map(|&w| {
                span.transfer(C64::new(0.0, w), [1, 2, 7, 8], [3, 4, 5, 6])
                    .map(|h| h[2][1])
            })
            .collect::<Result<Vec<_>, _>>()
            .map_err(|e| e.to_string())?,
    )];
    for (name, approx) in [
        ("Taylor", taylor_u2_u5(order)),
        ("term Pade", term_pade_u2_u5(order)),
        ("function Pade", function_pade_u2_u5(order)),
    ] {
        if let Ok(a) = approx {
            series.push((
                format!("{name} (order {order})"),
                omegas
                    .iter()
                    .map(|&w| a.eval(span, C64::new(0.0, w)))
                    .collect(),
            ));
        }
    }
    series.push((
        format!("FE ({fe_elements} el)"),
        omegas
            .iter()
            .map(|&w| fe_response(span, fe_elements, w))
            .collect(),
    ));
    Ok(series)
}

/// FE frequency response of y(L) to a unit rotation at x = 0 (y(0) = 0, free end).
pub fn fe_response(span: &Span, elements: usize, omega: f64) -> C64 {
    use slender_units::beam::elements as el;
    let lengths = vec![span.length / elements as f64; elements];
    let m = el::mass(span.mass_per_length, &lengths).to_dense();
    let k = el::stiffness(span.flexural_rigidity, &lengths).to_dense();
    let n = m.nrows();
    let i = C64::new(0.0, 1.0);
    let cd = span.damping_per_length / span.mass_per_length;
    let a = nalgebra::DMatrix::from_fn(n - 2, n - 2, |r, c| {
        C64::from(k[(r + 2, c + 2)]) + i * omega * cd * m[(r + 2, c + 2)]
            - C64::from(omega * omega * m[(r + 2, c + 2)])
    });
    let rhs = nalgebra::DVector::from_fn(n - 2, |r, _| {
        -(C64::from(k[(r + 2, 1)]) + i * omega * cd * m[(r + 2, 1)]
            - C64::from(omega * omega * m[(r + 2, 1)]))
    });
    a.lu()
        .solve(&rhs)
        .map(|q| q[n - 4])
        .unwrap_or(C64::new(f64::NAN, f64::NAN))
}
