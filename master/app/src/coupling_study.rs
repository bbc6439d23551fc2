//! Accuracy against cost of the span between two sections (`span_coupling`, the
//! 4x4 transfer matrix) and of FE spans with the same four end conditions, all
//! driven by the same end motions and loads sampled at the synchronisation step.
//!
//! The reference is the continuum's response to the smooth end history: a fine FE
//! span stepped at a fraction of the step with the history evaluated at every
//! substep. (A reference under the ramped samples would not do: a ramped
//! deflection has a kink at every sample, and the continuum answers a kink with an
//! impulsive shear at the driven end.)

use crate::span_study::{StudyError, cheapest_as_accurate, relative_error, respond};
use serde::Serialize;
use slender_units::UnitError;
use slender_units::beam::boundary::{Boundary, Condition, InputMarker, Quantity, TimeFunction};
use slender_units::beam::{Beam, BeamParams};
use slender_units::span::coupling::{
    Discretization, Orientation, SpanCoupling, SpanCouplingParams,
};
use slender_units::span::transfer::Span;

/// The outputs compared, in the span unit's order for `upper_motion`.
pub const OUTPUTS: [&str; 4] = [
    "upper moment",
    "upper shear",
    "lower deflection",
    "lower rotation",
];

/// An FE span with the span unit's four end conditions as inputs (upper deflection
/// and rotation, lower moment and shear), starting in static equilibrium, with
/// HHT-alpha `alpha` (0: trapezoidal rule). Outputs 2..=5 of the beam are the four
/// compared quantities.
pub fn fe_span(span: &Span, elements: usize, alpha: f64) -> Result<Beam, UnitError> {
    let cond = |quantity| Condition {
        quantity,
        value: TimeFunction::Input(InputMarker::Input),
    };
    let mut p = BeamParams::new(
        span.length,
        elements,
        span.flexural_rigidity,
        span.mass_per_length,
        Boundary {
            left: [cond(Quantity::Deflection), cond(Quantity::Rotation)],
            right: [cond(Quantity::Moment), cond(Quantity::Shear)],
        },
    );
    p.damping_per_length = span.damping_per_length;
    p.tension = span.tension;
    p.static_start = true;
    p.alpha = alpha;
    Beam::new(p)
}

const FE_OUTPUTS: [usize; 4] = [2, 3, 4, 5];

/// End history: a static part plus four sines (1.3 to 29 rad/s, inside the band)
/// on every input, faded in smoothly over 2 s, at sizes typical of a pipe span end
/// (1 cm, 1 mrad, 100 N m, 20 N).
pub fn motion(t: f64) -> [f64; 4] {
    let x = (t / 2.0).min(1.0);
    let fade = x * x * x * (10.0 - 15.0 * x + 6.0 * x * x);
    let sines = |a: f64, phase: f64| {
        a * fade
            * [(1.3, 0.0), (7.1, 1.0), (19.0, 2.0), (29.0, 0.5)]
                .iter()
                .map(|(w, p)| (w * t + p + phase).sin())
                .sum::<f64>()
    };
    [
        0.01 + sines(0.01, 0.0),
        0.002 + sines(0.001, 0.3),
        50.0 + sines(100.0, 0.7),
        -10.0 + sines(20.0, 1.1),
    ]
}

/// One model of the study.
#[derive(Clone, Debug, Serialize)]
pub struct CouplingRow {
    /// "exact", "trapezoidal" (span_coupling stepping) or "fe".
    pub model: String,
    /// Order of the fit, or number of elements.
    pub size: usize,
    /// Steps per synchronisation step (FE only; 1 otherwise).
    pub substeps: usize,
    /// Largest error of each output (see [`OUTPUTS`]) relative to its peak.
    pub errors: [f64; 4],
    /// Wall time per simulated second (s/s).
    pub cost_per_simulated_second: f64,
}

/// What the study compares: the same kind of plan as the SISO span study.
pub type CouplingPlan = crate::span_study::StudyPlan;

/// Orders of `slender span coupling`.
pub const ORDERS: [usize; 3] = [16, 24, 32];
/// FE span elements of `slender span coupling`.
pub const ELEMENTS: [usize; 5] = [8, 16, 32, 64, 128];

/// What the study measured.
#[derive(Clone, Debug, Serialize)]
pub struct CouplingReport {
    pub step: f64,
    pub duration: f64,
    pub reference_elements: usize,
    pub reference_substeps: usize,
    /// Change of each output when the reference's substeps are halved, relative to
    /// its peak: about three times the reference's own time error.
    pub reference_halving_change: [f64; 4],
    pub rows: Vec<CouplingRow>,
}

fn errors(y: &[Vec<f64>], r: &[Vec<f64>]) -> [f64; 4] {
    std::array::from_fn(|j| {
        let column = |v: &[Vec<f64>]| v.iter().map(|x| x[j]).collect::<Vec<f64>>();
        relative_error(&column(y), &column(r))
    })
}

/// Runs the span unit (each order, exact and trapezoidal stepping) and the FE spans
/// (each element count and substep count) and measures them against the reference.
pub fn coupling_study(span: &Span, plan: &CouplingPlan) -> Result<CouplingReport, StudyError> {
    span.validate()?;
    let h = plan.step;
    let steps = (plan.duration / h).round() as usize;
    let sampled = |dt: f64, n: usize| -> Vec<Vec<f64>> {
        (0..=n).map(|k| motion(k as f64 * dt).to_vec()).collect()
    };
    let samples = sampled(h, steps);
    // The reference: the smooth history at every substep, read at every step.
    let reference = |substeps: usize| -> Result<Vec<Vec<f64>>, StudyError> {
        let dt = h / substeps as f64;
        let mut fe = fe_span(span, plan.reference_elements, 0.0)?;
        let (y, _) = respond(&mut fe, &FE_OUTPUTS, &sampled(dt, steps * substeps), dt, 1)?;
        Ok(y.into_iter().skip(substeps - 1).step_by(substeps).collect())
    };
    let fine = reference(plan.reference_substeps)?;
    let coarse = reference((plan.reference_substeps / 2).max(1))?;
    let mut rows = Vec::new();
    for (discretization, name) in [
        (Discretization::Exact, "exact"),
        (Discretization::Trapezoidal, "trapezoidal"),
    ] {
        for &order in &plan.orders {
            let mut unit = SpanCoupling::new(SpanCouplingParams {
                flexural_rigidity: span.flexural_rigidity,
                mass_per_length: span.mass_per_length,
                damping_per_length: span.damping_per_length,
                length: span.length,
                tension: span.tension,
                orientation: Orientation::UpperMotion,
                order,
                band: 2.0 * std::f64::consts::PI * 10.0,
                discretization,
                alpha: 0.0,
            })?;
            let (y, wall) = respond(&mut unit, &[0, 1, 2, 3], &samples, h, 1)?;
            rows.push(CouplingRow {
                model: name.into(),
                size: order,
                substeps: 1,
                errors: errors(&y, &fine),
                cost_per_simulated_second: wall / plan.duration,
            });
        }
    }
    for &substeps in &plan.fe_substeps {
        for &n in &plan.elements {
            let mut fe = fe_span(span, n, 0.0)?;
            let (y, wall) = respond(&mut fe, &FE_OUTPUTS, &samples, h, substeps)?;
            rows.push(CouplingRow {
                model: "fe".into(),
                size: n,
                substeps,
                errors: errors(&y, &fine),
                cost_per_simulated_second: wall / plan.duration,
            });
        }
    }
    Ok(CouplingReport {
        step: h,
        duration: plan.duration,
        reference_elements: plan.reference_elements,
        reference_substeps: plan.reference_substeps,
        reference_halving_change: errors(&coarse, &fine),
        rows,
    })
}

/// For a span-unit row: the cheapest FE span at least as accurate on the outputs
/// `which`, and how many times cheaper the span unit is.
pub fn cheapest_equal_fe<'a>(
    report: &'a CouplingReport,
    row: &CouplingRow,
    which: &[usize],
) -> Option<(&'a CouplingRow, f64)> {
    cheapest_as_accurate(
        &report.rows,
        row,
        |r| r.model == "fe" && which.iter().all(|&j| r.errors[j] <= row.errors[j]),
        |r| r.cost_per_simulated_second,
    )
}

/// The report as Markdown, with the cheapest FE span as accurate on every output
/// and on the lower end's motion (the outputs a section below uses).
pub fn to_markdown(report: &CouplingReport) -> String {
    let show = |e: &[f64; 4]| e.map(|v| format!("{v:.1e}")).join(" / ");
    let mut out = format!(
        "Step {} s, {} s. Errors ({}) relative to each output's peak, against an FE span with {} \
         elements and {} substeps per step under the smooth end history; halving its substeps \
         changes it by {}.\n\n",
        report.step,
        report.duration,
        OUTPUTS.join(" / "),
        report.reference_elements,
        report.reference_substeps,
        show(&report.reference_halving_change)
    );
    out += "| model | order / elements | substeps | errors | cost (s per simulated s) | cheapest FE as accurate on all four | on the lower end |\n|---|---|---|---|---|---|---|\n";
    for row in &report.rows {
        let equal = |which: &[usize]| match cheapest_equal_fe(report, row, which) {
            Some((fe, ratio)) => format!("{} el x {}: {ratio:.0}x", fe.size, fe.substeps),
            None => "none in the study".into(),
        };
        let (all, lower) = if row.model == "fe" {
            (String::new(), String::new())
        } else {
            (equal(&[0, 1, 2, 3]), equal(&[2, 3]))
        };
        out += &format!(
            "| {} | {} | {} | {} | {:.2e} | {all} | {lower} |\n",
            row.model,
            row.size,
            row.substeps,
            show(&row.errors),
            row.cost_per_simulated_second
        );
    }
    out
}
