//! The suspended span (seed 004 ch. 5) from the command line: Bode plots of the
//! exact transfer function against its rational approximations and the FE span,
//! and accuracy against cost of span units and FE spans under the same end motion.

use serde::Serialize;
use slender_units::UnitError;
use slender_units::beam::boundary::{Boundary, Condition, InputMarker, Quantity, TimeFunction};
use slender_units::beam::{Beam, BeamParams};
use slender_units::span::transfer::{C64, Span};
use slender_units::span::unit::{Approximation, SpanParams, SpanUnit};
use std::path::Path;

mod scenes;
use crate::study::{self, Design, Sweep};
pub(crate) use scenes::{
    Drive, StudyScene, UnitText, engine_rows, number, report_order, span_properties,
};

/// An FE span with the same boundary conditions as the span unit: y(0) = 0, the
/// rotation at x = 0 as input, a free lower end.
pub fn fe_span(span: &Span, elements: usize) -> Result<Beam, UnitError> {
    let cond = |quantity, value| Condition { quantity, value };
    let mut p = span_beam(
        span,
        elements,
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
    p.newton_max_iterations = 5;
    Beam::new(p)
}

/// The span's properties (length, EI, mass, damping, tension) as a beam of
/// `elements` elements under `boundary`.
pub(crate) fn span_beam(span: &Span, elements: usize, boundary: Boundary) -> BeamParams {
    let mut p = BeamParams::new(
        span.length,
        elements,
        span.flexural_rigidity,
        span.mass_per_length,
        boundary,
    );
    p.damping_per_length = span.damping_per_length;
    p.tension = span.tension;
    p
}

/// Why a span study could not run: the span's properties are refused, or the
/// plan does not fit or the study engine stopped (a scene not written, a step or
/// substeps that are no whole nanoseconds, a reference run that failed).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum StudyError {
    /// A unit could not be built or stepped.
    #[error(transparent)]
    Unit(#[from] UnitError),
    /// The plan is not valid.
    #[error("{0}")]
    Plan(String),
    /// A run or a file failed.
    #[error(transparent)]
    App(#[from] crate::AppError),
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
    /// The same for the step.
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
    /// Elements of the reference FE span.
    pub elements: usize,
    /// Its substeps per synchronisation step.
    pub substeps: usize,
    /// Largest change when the reference's substeps are halved, relative to its peak
    /// (sines, step): about three times the reference's own time error for a
    /// second-order integrator (e(m/2) - e(m) = 4e - e), so an upper bound on it.
    pub halving_change_sines: f64,
    /// The same for the step.
    pub halving_change_step: f64,
}

/// What the study measured.
#[derive(Clone, Debug, Serialize)]
pub struct StudyReport {
    /// Synchronisation step (s).
    pub step: f64,
    /// Simulated time of each run (s).
    pub duration: f64,
    /// The reference and its own error.
    pub reference: Reference,
    /// One row per model and size.
    pub rows: Vec<StudyRow>,
    /// Models whose runs failed (an approximation that does not form), with why.
    pub failed: Vec<String>,
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
    /// Substeps of the reference FE span.
    pub reference_substeps: usize,
    /// Simulated time of each run (s) and synchronisation step (s).
    pub duration: f64,
    /// Synchronisation step (s).
    pub step: f64,
}

/// Runs every span approximation and FE span of the plan under both end motions and
/// measures error against the continuum's response and cost per simulated second
/// (of the unit under study alone), through the general study engine: the scenes
/// go into `scenes` (`reference_<motion>.toml`, `span_<motion>.toml`,
/// `fe_<motion>.toml`), each motion's reference runs once. An approximation that
/// does not form (or whose run fails) is listed in `failed`.
pub fn study(span: &Span, plan: &StudyPlan, scenes: &Path) -> Result<StudyReport, StudyError> {
    span.validate()?;
    std::fs::create_dir_all(scenes)
        .map_err(|e| StudyError::Plan(format!("{}: {e}", scenes.display())))?;
    let third =
        (7.85476 / span.length).powi(2) * (span.flexural_rigidity / span.mass_per_length).sqrt();
    let mut runs = Vec::new();
    for motion in ["sines", "step"] {
        let write = |stem: &str, model: UnitText, (to, port): (&'static str, &'static str)| {
            let drives = [if motion == "sines" {
                sines(third, to)
            } else {
                step(to)
            }];
            let path = scenes.join(format!("{stem}_{motion}.toml"));
            let text = StudyScene {
                title: format!("Span study ({motion}): {stem}"),
                duration: plan.duration,
                step: plan.step,
                drives: &drives,
                model,
                indicators: &[("deflection", port)],
            }
            .text();
            crate::whole::write(&path, text)
                .map_err(|e| StudyError::Plan(format!("{}: {e}", path.display())))?;
            Ok::<_, StudyError>(path)
        };
        let fe = |name, elements, substeps| fe_unit(span, name, elements, substeps);
        let reference = write(
            "reference",
            fe(
                "reference",
                plan.reference_elements,
                plan.reference_substeps,
            ),
            FE_PORTS,
        )?;
        let span_scene = write(
            "span",
            span_unit(span, "span", ""),
            ("upper_rotation", "lower_deflection"),
        )?;
        let fe_scene = write("fe", fe("fe", 4, 1), FE_PORTS)?;
        runs.push(motion_runs(plan, &reference, &span_scene, &fe_scene)?);
    }
    let [sines, step] = <[MotionRuns; 2]>::try_from(runs)
        .map_err(|_| StudyError::Plan("two motions expected".into()))?;
    let (mut rows, failed) = combined_rows(span, &sines, &step);
    // Span units in the plan's order, then FE spans by substeps and elements.
    rows.sort_by_key(|r| report_order(&r.model, r.substeps, r.size));
    Ok(StudyReport {
        step: plan.step,
        duration: plan.duration,
        reference: Reference {
            elements: plan.reference_elements,
            substeps: plan.reference_substeps,
            halving_change_sines: sines.halving,
            halving_change_step: step.halving,
        },
        rows,
        failed,
    })
}

/// The FE span's driven input and compared output.
const FE_PORTS: (&str, &str) = ("left_rotation", "right_deflection");

/// The engine's rows of one motion: span units, FE spans, and the reference's
/// change when its substeps are halved.
struct MotionRuns {
    span: Vec<study::StudyRow>,
    fe: Vec<study::StudyRow>,
    halving: f64,
}

/// A sweep of `key` over `values` (as the plan gives them).
pub(crate) fn sweep<T: Into<toml::Value> + Copy>(
    key: &str,
    values: &[T],
) -> Result<Sweep, StudyError> {
    Ok(Sweep {
        setting: key.parse().map_err(StudyError::Plan)?,
        values: values.iter().map(|&v| v.into()).collect(),
    })
}

/// Runs one motion's three studies against its reference run.
fn motion_runs(
    plan: &StudyPlan,
    reference: &Path,
    span_scene: &Path,
    fe_scene: &Path,
) -> Result<MotionRuns, StudyError> {
    let against = study::run_reference(reference, None)?;
    let engine =
        |path: &Path, sweeps, design, cost: &str| engine_rows(path, sweeps, design, cost, &against);
    let orders: Vec<i64> = plan.orders.iter().map(|&n| n as i64).collect();
    let elements: Vec<i64> = plan.elements.iter().map(|&n| n as i64).collect();
    let substeps: Vec<i64> = plan.fe_substeps.iter().map(|&n| n as i64).collect();
    let span = engine(
        span_scene,
        vec![
            sweep("units.span.parameters.approximation", &APPROXIMATIONS)?,
            sweep("units.span.parameters.order", &orders)?,
        ],
        Design::Grid,
        "span",
    )?;
    let fe = engine(
        fe_scene,
        vec![
            sweep("units.fe.substeps", &substeps)?,
            sweep("units.fe.parameters.elements", &elements)?,
        ],
        Design::Grid,
        "fe",
    )?;
    let halved = (plan.reference_substeps / 2).max(1) as i64;
    let halving = engine(
        reference,
        vec![sweep("units.reference.substeps", &[halved])?],
        Design::OneAtATime,
        "",
    )?;
    Ok(MotionRuns {
        span,
        fe,
        halving: halving.first().map_or(f64::NAN, |r| r.errors[0].1),
    })
}

/// The span approximations a study compares, as the scene names them.
const APPROXIMATIONS: [&str; 4] = ["taylor", "term_pade", "function_pade", "fit"];

/// The report's rows from both motions' engine rows (same runs, same order), and
/// the models whose runs failed with why.
fn combined_rows(
    span: &Span,
    sines: &MotionRuns,
    step: &MotionRuns,
) -> (Vec<StudyRow>, Vec<String>) {
    let (mut rows, mut failed) = (Vec::new(), Vec::new());
    let value = |r: &study::StudyRow, i: usize| r.settings.get(i).map(|(_, v)| v.clone());
    let pairs = sines.span.iter().zip(&step.span).map(|p| (true, p));
    let fe_pairs = sines.fe.iter().zip(&step.fe).map(|p| (false, p));
    for (is_span, (a, b)) in pairs.chain(fe_pairs) {
        let count = |i| {
            value(a, i)
                .and_then(|v| v.parse::<usize>().ok())
                .unwrap_or(0)
        };
        let (model, size, substeps) = if is_span {
            (value(a, 0).unwrap_or_default(), count(1), 1)
        } else {
            ("fe".to_string(), count(1), count(0))
        };
        if let Some(e) = a.error.as_ref().or(b.error.as_ref()) {
            failed.push(format!("{model} {size}: {e}"));
            continue;
        }
        let repaired = if is_span {
            repaired_poles(span, &model, size)
        } else {
            0
        };
        rows.push(StudyRow {
            model,
            size,
            substeps,
            error_sines: a.errors[0].1,
            error_step: b.errors[0].1,
            cost_per_simulated_second: 0.5
                * (a.cost_per_simulated_second + b.cost_per_simulated_second),
            repaired,
        });
    }
    (rows, failed)
}

/// Poles the span unit of `approximation` and `order` reflects to be stable.
fn repaired_poles(span: &Span, approximation: &str, order: usize) -> usize {
    let approximation = match approximation {
        "taylor" => Approximation::Taylor,
        "term_pade" => Approximation::TermPade,
        "function_pade" => Approximation::FunctionPade,
        _ => Approximation::Fit,
    };
    SpanUnit::new(span_params(span, approximation, order)).map_or(0, |u| u.system().repaired)
}

/// The span unit's parameters for `span`, over seed 004's 10 Hz band.
fn span_params(span: &Span, approximation: Approximation, order: usize) -> SpanParams {
    SpanParams {
        flexural_rigidity: span.flexural_rigidity,
        mass_per_length: span.mass_per_length,
        damping_per_length: span.damping_per_length,
        length: span.length,
        tension: span.tension,
        approximation,
        order,
        band: 2.0 * std::f64::consts::PI * 10.0,
    }
}

/// A span unit of `kind` (`span` or `span_coupling`) as a scene writes it,
/// with the `extra` keys of its kind; the band of interest up to 10 Hz
/// (approximation, order and discretisation are what a study varies).
pub(crate) fn span_unit(span: &Span, kind: &'static str, extra: &str) -> UnitText {
    UnitText {
        name: "span",
        kind,
        substeps: 1,
        parameters: format!(
            "{}band = {}\n{extra}",
            span_properties(span),
            number(2.0 * std::f64::consts::PI * 10.0)
        ),
    }
}

/// The FE span of [`fe_span`] as a scene writes it.
fn fe_unit(span: &Span, name: &'static str, elements: usize, substeps: usize) -> UnitText {
    UnitText {
        name,
        kind: "beam",
        substeps,
        parameters: format!(
            "elements = {elements}\n{}newton_max_iterations = 5\n\
             boundary.left = [{{ quantity = \"deflection\", value = 0.0 }}, {{ quantity = \"rotation\", value = \"input\" }}]\n\
             boundary.right = [{{ quantity = \"moment\", value = 0.0 }}, {{ quantity = \"shear\", value = 0.0 }}]\n",
            span_properties(span)
        ),
    }
}

/// The in-band motion: a sum of three sines below the third resonance, faded in
/// over 20 s.
fn sines(third_resonance: f64, to: &'static str) -> Drive {
    let w = third_resonance;
    let sine = |a: f64, f: f64| {
        format!(
            "{{ amplitude = {}, angular_frequency = {} }}",
            number(a),
            number(f * w)
        )
    };
    Drive {
        name: "motion",
        quantity: "rotation",
        parameters: format!(
            "sines = [{}, {}, {}]\nfade_in = {{ shape = \"exponential\", time = 20.0 }}\n",
            sine(0.01, 0.03),
            sine(0.01 * 0.5, 0.11),
            sine(0.01 * 0.25, 0.32)
        ),
        to,
    }
}

/// A 0.01 rad step at 1 s (ramped over one step by the master's hold).
fn step(to: &'static str) -> Drive {
    Drive {
        name: "motion",
        quantity: "rotation",
        parameters: "steps = [{ time = 1.0, size = 0.01 }]\n".into(),
        to,
    }
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
    for failed in &report.failed {
        out += &format!("\nNot in the table (its run failed): {failed}\n");
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
