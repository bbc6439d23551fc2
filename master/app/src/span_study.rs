//! The suspended span (seed 004 ch. 5) from the command line: Bode plots of the
//! exact transfer function against its rational approximations and the FE span,
//! and accuracy against cost of span units and FE spans under the same end motion.

use serde::Serialize;
use slender_units::beam::boundary::{Boundary, Condition, InputMarker, Quantity, TimeFunction};
use slender_units::beam::{Beam, BeamParams};
use slender_units::span::transfer::{C64, Span};
use slender_units::span::unit::{Approximation, SpanParams, SpanUnit};
use slender_units::{Driver, Time, Unit, UnitError};
use std::time::Instant;

/// An FE span with the same boundary conditions as the span unit: y(0) = 0, the
/// rotation at x = 0 as input, a free lower end.
pub fn fe_span(span: &Span, elements: usize) -> Result<Beam, UnitError> {
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
    p.tension = span.tension;
    p.newton_max_iterations = 5;
    Beam::new(p)
}

/// Why a span study could not run: a unit refused its parameters or inputs, or
/// the plan does not fit (a step or substeps that are no whole nanoseconds).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum StudyError {
    #[error(transparent)]
    Unit(#[from] UnitError),
    #[error("{0}")]
    Plan(String),
}

/// Outputs `outputs` of a unit at every synchronisation step (h, s) for the input
/// `samples` at the steps (samples[k] at t = k h, k = 0..=steps) ramped between
/// them (as a master passes them), stepping the unit `substeps` times per step;
/// and the wall time spent stepping (s). Only the unit's work is timed.
pub(crate) fn respond(
    unit: &mut dyn Unit,
    outputs: &[usize],
    samples: &[Vec<f64>],
    h: f64,
    substeps: usize,
) -> Result<(Vec<Vec<f64>>, f64), StudyError> {
    let first = samples
        .first()
        .ok_or_else(|| StudyError::Plan("no input samples".into()))?;
    let mut unit = Driver::new(unit);
    unit.set_inputs(first)?;
    unit.initialize(Time::ZERO)?;
    let ht = Time::from_secs(h)
        .ok_or_else(|| StudyError::Plan(format!("step {h} s: not a representable time")))?;
    let hs = Time::from_secs(h / substeps as f64)
        .filter(|hs| *hs * substeps as i64 == ht)
        .ok_or_else(|| {
            StudyError::Plan(format!(
                "{substeps} substeps do not divide the step {h} s into whole nanoseconds"
            ))
        })?;
    let mut out = vec![0.0; unit.description().outputs.len()];
    let mut u = first.clone();
    // Outputs go into one buffer allocated up front: the timed loop allocates nothing.
    let mut flat = Vec::with_capacity(samples.len() * outputs.len());
    let started = Instant::now();
    for (k, pair) in samples.windows(2).enumerate() {
        for j in 1..=substeps {
            let inputs = if j == substeps {
                &pair[1]
            } else {
                let f = j as f64 / substeps as f64;
                for (ui, (a, b)) in u.iter_mut().zip(pair[0].iter().zip(&pair[1])) {
                    *ui = a + f * (b - a);
                }
                &u
            };
            unit.set_inputs(inputs)?;
            unit.do_step(ht * k as i64 + hs * (j - 1) as i64, hs)?;
        }
        unit.outputs(&mut out)?;
        flat.extend(outputs.iter().map(|&o| out[o]));
    }
    let wall = started.elapsed().as_secs_f64();
    let y = flat
        .chunks(outputs.len().max(1))
        .map(<[f64]>::to_vec)
        .collect();
    Ok((y, wall))
}

/// The lower-end deflection of a SISO span (first output of the list) over time.
fn respond_siso(
    unit: &mut dyn Unit,
    output: usize,
    u: &dyn Fn(f64) -> f64,
    h: f64,
    steps: usize,
    substeps: usize,
) -> Result<(Vec<f64>, f64), StudyError> {
    let samples: Vec<Vec<f64>> = (0..=steps).map(|k| vec![u(k as f64 * h)]).collect();
    let (y, wall) = respond(unit, &[output], &samples, h, substeps)?;
    Ok((y.into_iter().map(|v| v[0]).collect(), wall))
}

/// One model of the study.
#[derive(Clone, Debug, Serialize)]
pub struct StudyRow {
    /// "taylor", "term_pade", "function_pade", "fit" or "fe".
    pub model: String,
    /// Order in s, or number of elements.
    pub size: usize,
    /// Steps the model takes per synchronisation step (FE spans only; 1 otherwise).
    pub substeps: usize,
    /// Largest error against the reference, relative to the reference's peak, for
    /// the sum of sines and for the step.
    pub error_sines: f64,
    pub error_step: f64,
    /// Wall time per simulated second (s/s), mean of the two runs.
    pub cost_per_simulated_second: f64,
    /// Poles reflected to make the approximation stable.
    pub repaired: usize,
}

impl StudyRow {
    /// The model's name with its substeps, as plotted.
    pub fn label(&self) -> String {
        if self.substeps > 1 {
            format!("{} ({} substeps)", self.model, self.substeps)
        } else {
            self.model.clone()
        }
    }
}

/// The reference the errors are measured against: the continuum's response to the
/// same sampled-and-ramped end motion, from a fine FE span with fine substeps.
#[derive(Clone, Debug, Serialize)]
pub struct Reference {
    pub elements: usize,
    pub substeps: usize,
    /// Largest change when the reference's substeps are halved, relative to its peak
    /// (sines, step): about three times the reference's own time error for a
    /// second-order integrator (e(m/2) - e(m) = 4e - e), so an upper bound on it.
    pub halving_change_sines: f64,
    pub halving_change_step: f64,
}

/// What the study measured.
#[derive(Clone, Debug, Serialize)]
pub struct StudyReport {
    pub step: f64,
    pub duration: f64,
    pub reference: Reference,
    pub rows: Vec<StudyRow>,
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

/// Largest difference relative to the reference's peak.
pub(crate) fn relative_error(y: &[f64], r: &[f64]) -> f64 {
    let peak = r.iter().fold(0.0f64, |a, v| a.max(v.abs())).max(1e-300);
    y.iter()
        .zip(r)
        .fold(0.0f64, |a, (y, r)| a.max((y - r).abs()))
        / peak
}

/// Orders of `slender span study`.
pub const ORDERS: [usize; 8] = [2, 4, 6, 8, 10, 12, 14, 16];
/// FE span elements of `slender span study`.
pub const ELEMENTS: [usize; 5] = [4, 8, 16, 32, 64];

/// What a span study compares, and how (the SISO span study and the coupling
/// study alike).
#[derive(Clone, Debug)]
pub struct StudyPlan {
    /// Orders of the rational approximations.
    pub orders: Vec<usize>,
    /// Elements of the FE spans.
    pub elements: Vec<usize>,
    /// Substeps per synchronisation step of the FE spans (1: the FE span steps with
    /// the master).
    pub fe_substeps: Vec<usize>,
    /// Elements and substeps of the reference FE span.
    pub reference_elements: usize,
    pub reference_substeps: usize,
    /// Simulated time of each run (s) and synchronisation step (s).
    pub duration: f64,
    pub step: f64,
}

/// Runs every span approximation and FE span of the plan under both end motions and
/// measures error against the continuum's response and cost per simulated second.
pub fn study(span: &Span, plan: &StudyPlan) -> Result<StudyReport, StudyError> {
    span.validate()?;
    let h = plan.step;
    let steps = (plan.duration / h).round() as usize;
    let third =
        (7.85476 / span.length).powi(2) * (span.flexural_rigidity / span.mass_per_length).sqrt();
    let motions = inputs(third);
    let fe_output = |fe: &Beam| {
        fe.description()
            .output_index("right_deflection")
            .ok_or_else(|| StudyError::Plan("the FE span has no right_deflection".into()))
    };
    let mut references = Vec::new();
    let mut halving = Vec::new();
    for u in &motions {
        let run = |substeps| -> Result<Vec<f64>, StudyError> {
            let mut fe = fe_span(span, plan.reference_elements)?;
            let out = fe_output(&fe)?;
            Ok(respond_siso(&mut fe, out, u.as_ref(), h, steps, substeps)?.0)
        };
        let fine = run(plan.reference_substeps)?;
        let coarse = run((plan.reference_substeps / 2).max(1))?;
        halving.push(relative_error(&coarse, &fine));
        references.push(fine);
    }
    let mut rows = span_unit_rows(span, plan, &motions, &references, steps)?;
    for &substeps in &plan.fe_substeps {
        for &n in &plan.elements {
            let (mut errs, mut costs) = (Vec::new(), Vec::new());
            for (u, r) in motions.iter().zip(&references) {
                let mut fe = fe_span(span, n)?;
                let out = fe_output(&fe)?;
                let (y, wall) = respond_siso(&mut fe, out, u.as_ref(), h, steps, substeps)?;
                errs.push(relative_error(&y, r));
                costs.push(wall / plan.duration);
            }
            rows.push(StudyRow {
                model: "fe".into(),
                size: n,
                substeps,
                error_sines: errs[0],
                error_step: errs[1],
                cost_per_simulated_second: 0.5 * (costs[0] + costs[1]),
                repaired: 0,
            });
        }
    }
    Ok(StudyReport {
        step: h,
        duration: plan.duration,
        reference: Reference {
            elements: plan.reference_elements,
            substeps: plan.reference_substeps,
            halving_change_sines: halving[0],
            halving_change_step: halving[1],
        },
        rows,
    })
}

/// The rows of every span approximation and order of the plan that forms, each
/// against the references under both motions.
fn span_unit_rows(
    span: &Span,
    plan: &StudyPlan,
    motions: &[Box<dyn Fn(f64) -> f64>; 2],
    references: &[Vec<f64>],
    steps: usize,
) -> Result<Vec<StudyRow>, StudyError> {
    let (h, mut rows) = (plan.step, Vec::new());
    let approximations = [
        (Approximation::Taylor, "taylor"),
        (Approximation::TermPade, "term_pade"),
        (Approximation::FunctionPade, "function_pade"),
        (Approximation::Fit, "fit"),
    ];
    for (a, name) in approximations {
        for &order in &plan.orders {
            let params = SpanParams {
                flexural_rigidity: span.flexural_rigidity,
                mass_per_length: span.mass_per_length,
                damping_per_length: span.damping_per_length,
                length: span.length,
                tension: span.tension,
                approximation: a,
                order,
                band: 2.0 * std::f64::consts::PI * 10.0,
            };
            let Ok(unit) = SpanUnit::new(params.clone()) else {
                continue;
            };
            let repaired = unit.system().repaired;
            let (mut errs, mut costs) = (Vec::new(), Vec::new());
            for (u, r) in motions.iter().zip(references) {
                let mut fresh = SpanUnit::new(params.clone())?;
                let (y, wall) = respond_siso(&mut fresh, 0, u.as_ref(), h, steps, 1)?;
                errs.push(relative_error(&y, r));
                costs.push(wall / plan.duration);
            }
            rows.push(StudyRow {
                model: name.into(),
                size: order,
                substeps: 1,
                error_sines: errs[0],
                error_step: errs[1],
                cost_per_simulated_second: 0.5 * (costs[0] + costs[1]),
                repaired,
            });
        }
    }
    Ok(rows)
}

/// For a span-unit row: the cheapest FE span of the report at least as accurate under
/// the sum of sines (the in-band motion), and how many times cheaper the span unit is.
pub fn cheapest_equal_fe<'a>(
    report: &'a StudyReport,
    row: &StudyRow,
) -> Option<(&'a StudyRow, f64)> {
    cheapest_as_accurate(
        &report.rows,
        row,
        |r| r.model == "fe" && r.error_sines <= row.error_sines,
        |r| r.cost_per_simulated_second,
    )
}

/// The cheapest of `rows` that `qualifies` (an FE span at least as accurate as
/// `row`), and its cost over `row`'s: how many times cheaper `row` is.
pub(crate) fn cheapest_as_accurate<'a, R>(
    rows: &'a [R],
    row: &R,
    qualifies: impl Fn(&R) -> bool,
    cost: impl Fn(&R) -> f64,
) -> Option<(&'a R, f64)> {
    rows.iter()
        .filter(|r| qualifies(r))
        .min_by(|a, b| cost(a).total_cmp(&cost(b)))
        .map(|fe| (fe, cost(fe) / cost(row)))
}

/// The report as Markdown: the reference, every row, and for each span unit the
/// cheapest FE span of equal in-band accuracy.
pub fn to_markdown(report: &StudyReport) -> String {
    let r = &report.reference;
    let mut out = format!(
        "Step {} s, {} s per run. Reference: FE span with {} elements and {} substeps per step \
         under the same ramped end motion; halving its substeps changes it by {:.1e} (sines) \
         and {:.1e} (step) of its peak.\n\n",
        report.step,
        report.duration,
        r.elements,
        r.substeps,
        r.halving_change_sines,
        r.halving_change_step
    );
    out += "| model | order / elements | substeps | error, sines | error, step | cost (s per simulated s) | poles reflected | cheapest FE as accurate (sines) | cost ratio |\n|---|---|---|---|---|---|---|---|---|\n";
    for row in &report.rows {
        let equal = if row.model == "fe" {
            "| |".to_string()
        } else {
            match cheapest_equal_fe(report, row) {
                Some((fe, ratio)) => {
                    format!("| {} el, {} substeps | {ratio:.0}x |", fe.size, fe.substeps)
                }
                None => "| none in the study | |".to_string(),
            }
        };
        out += &format!(
            "| {} | {} | {} | {:.2e} | {:.2e} | {:.2e} | {} {equal}\n",
            row.model,
            row.size,
            row.substeps,
            row.error_sines,
            row.error_step,
            row.cost_per_simulated_second,
            row.repaired
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
) -> Result<Vec<(String, Vec<C64>)>, StudyError> {
    use slender_units::span::rational::{function_pade_u2_u5, taylor_u2_u5, term_pade_u2_u5};
    let mut series = vec![(
        "analytic".to_string(),
        omegas
            .iter()
            .map(|&w| {
                span.transfer(C64::new(0.0, w), [1, 2, 7, 8], [3, 4, 5, 6])
                    .map(|h| h[2][1])
            })
            .collect::<Result<Vec<_>, _>>()?,
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
