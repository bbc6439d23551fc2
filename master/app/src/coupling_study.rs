//! Accuracy against cost of the span between two sections (`span_coupling`, the
//! 4x4 transfer matrix) and of FE spans with the same four end conditions, all
//! driven by the same end motions and loads sampled at the synchronisation step.
//!
//! The reference is the continuum's response to the smooth end history: a fine FE
//! span stepped at a fraction of the step with the history evaluated at every
//! substep. (A reference under the ramped samples would not do: a ramped
//! deflection has a kink at every sample, and the continuum answers a kink with an
//! impulsive shear at the driven end.)

use crate::span_study::{
    Drive, StudyError, StudyScene, UnitText, cheapest_as_accurate, engine_rows, number,
    report_order, span_beam, span_properties, span_unit, sweep,
};
use crate::study::{self, Design};
use serde::Serialize;
use slender_units::UnitError;
use slender_units::beam::Beam;
use slender_units::beam::boundary::{Boundary, Condition, InputMarker, Quantity, TimeFunction};
use slender_units::span::transfer::Span;
use std::path::{Path, PathBuf};

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
    let mut p = span_beam(
        span,
        elements,
        Boundary {
            left: [cond(Quantity::Deflection), cond(Quantity::Rotation)],
            right: [cond(Quantity::Moment), cond(Quantity::Shear)],
        },
    );
    p.static_start = true;
    p.alpha = alpha;
    Beam::new(p)
}

/// End history: a static part plus four sines (1.3 to 29 rad/s, inside the band)
/// on every input, faded in smoothly over 2 s, at sizes typical of a pipe span end
/// (1 cm, 1 mrad, 100 N m, 20 N).
pub fn motion(t: f64) -> [f64; 4] {
    let x = (t / 2.0).min(1.0);
    let fade = x * x * x * (10.0 - 15.0 * x + 6.0 * x * x);
    let sines = |a: f64, phase: f64| {
        a * fade
            * COMPONENTS
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

/// The end history's sines: angular frequency (rad/s) and phase (rad).
const COMPONENTS: [(f64, f64); 4] = [(1.3, 0.0), (7.1, 1.0), (19.0, 2.0), (29.0, 0.5)];

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
    /// Synchronisation step (s).
    pub step: f64,
    /// Simulated time of each run (s).
    pub duration: f64,
    /// Elements of the reference FE span.
    pub reference_elements: usize,
    /// Its substeps per synchronisation step.
    pub reference_substeps: usize,
    /// Change of each output when the reference's substeps are halved, relative to
    /// its peak: about three times the reference's own time error.
    pub reference_halving_change: [f64; 4],
    /// One row per model and size.
    pub rows: Vec<CouplingRow>,
}

/// Runs the span unit (each order, exact and trapezoidal stepping) and the FE spans
/// (each element count and substep count) and measures them against the reference,
/// through the general study engine: the scenes go into `scenes`
/// (`coupling_reference.toml`, stepped at a fraction of the step so the end history
/// is evaluated at every substep; `coupling_span.toml`, `coupling_fe.toml`).
pub fn coupling_study(
    span: &Span,
    plan: &CouplingPlan,
    scenes: &Path,
) -> Result<CouplingReport, StudyError> {
    span.validate()?;
    let [reference, span_scene, fe_scene] = write_scenes(span, plan, scenes)?;
    let against = study::run_reference(&reference, None)?;
    let engine =
        |path: &Path, sweeps, cost: &str| engine_rows(path, sweeps, Design::Grid, cost, &against);
    let counts = |v: &[usize]| v.iter().map(|&n| n as i64).collect::<Vec<i64>>();
    let span_rows = engine(
        &span_scene,
        vec![
            sweep(
                "units.span.parameters.discretization",
                &["exact", "trapezoidal"],
            )?,
            sweep("units.span.parameters.order", &counts(&plan.orders))?,
        ],
        "span",
    )?;
    let fe_rows = engine(
        &fe_scene,
        vec![
            sweep("units.fe.substeps", &counts(&plan.fe_substeps))?,
            sweep("units.fe.parameters.elements", &counts(&plan.elements))?,
        ],
        "fe",
    )?;
    let coarse = plan.step / (plan.reference_substeps / 2).max(1) as f64;
    let halving = engine(&reference, vec![sweep("simulation.step", &[coarse])?], "")?;
    let mut rows = span_rows
        .iter()
        .chain(&fe_rows)
        .map(coupling_row)
        .collect::<Result<Vec<_>, _>>()?;
    rows.sort_by_key(|r| report_order(&r.model, r.substeps, r.size));
    Ok(CouplingReport {
        step: plan.step,
        duration: plan.duration,
        reference_elements: plan.reference_elements,
        reference_substeps: plan.reference_substeps,
        reference_halving_change: halving.first().map_or([f64::NAN; 4], errors_of),
        rows,
    })
}

/// A report row from the engine's row of a span unit (its discretisation and
/// order varied) or of an FE span (substeps and elements); a failed run fails
/// the study, as a unit error did before.
fn coupling_row(r: &study::StudyRow) -> Result<CouplingRow, StudyError> {
    if let Some(e) = &r.error {
        return Err(StudyError::Plan(format!("{:?}: {e}", r.settings)));
    }
    let value = |i: usize| {
        r.settings
            .get(i)
            .map(|(_, v)| v.clone())
            .unwrap_or_default()
    };
    let count = |i| value(i).parse::<usize>().unwrap_or(0);
    let is_fe = r
        .settings
        .first()
        .is_some_and(|(k, _)| k.ends_with("substeps"));
    let (model, substeps) = if is_fe {
        ("fe".into(), count(0))
    } else {
        (value(0), 1)
    };
    Ok(CouplingRow {
        model,
        size: count(1),
        substeps,
        errors: errors_of(r),
        cost_per_simulated_second: r.cost_per_simulated_second,
    })
}

/// Writes the study's three scenes into `scenes`: reference, span unit, FE span.
fn write_scenes(
    span: &Span,
    plan: &CouplingPlan,
    scenes: &Path,
) -> Result<[PathBuf; 3], StudyError> {
    span.validate()?;
    std::fs::create_dir_all(scenes)
        .map_err(|e| StudyError::Plan(format!("{}: {e}", scenes.display())))?;
    let write = |stem: &str, step: f64, model: UnitText, ports: &[&'static str; 8]| {
        let drives = drives(ports);
        let indicators: Vec<(&'static str, &'static str)> = INDICATORS
            .iter()
            .copied()
            .zip(ports[4..].iter().copied())
            .collect();
        let path = scenes.join(format!("coupling_{stem}.toml"));
        let text = StudyScene {
            title: format!("Span coupling study: {stem}"),
            duration: plan.duration,
            step,
            drives: &drives,
            model,
            indicators: &indicators,
        }
        .text();
        crate::whole::write(&path, text)
            .map_err(|e| StudyError::Plan(format!("{}: {e}", path.display())))?;
        Ok::<_, StudyError>(path)
    };
    let fine = plan.step / plan.reference_substeps as f64;
    let reference = write(
        "reference",
        fine,
        fe_unit(span, "reference", plan.reference_elements, 1),
        &FE_PORTS,
    )?;
    let span_scene = write(
        "span",
        plan.step,
        span_unit(
            span,
            "span_coupling",
            "orientation = \"upper_motion\"\nalpha = 0.0\n",
        ),
        &SPAN_PORTS,
    )?;
    let fe_scene = write("fe", plan.step, fe_unit(span, "fe", 8, 1), &FE_PORTS)?;
    Ok([reference, span_scene, fe_scene])
}

/// The four compared outputs' names as indicators, in [`OUTPUTS`]' order.
const INDICATORS: [&str; 4] = [
    "upper_moment",
    "upper_shear",
    "lower_deflection",
    "lower_rotation",
];

/// The span unit's four driven inputs and four compared outputs.
const SPAN_PORTS: [&str; 8] = [
    "upper_deflection",
    "upper_rotation",
    "lower_moment",
    "lower_shear",
    "upper_moment",
    "upper_shear",
    "lower_deflection",
    "lower_rotation",
];

/// The FE span's, in the same order.
const FE_PORTS: [&str; 8] = [
    "left_deflection",
    "left_rotation",
    "right_moment",
    "right_shear",
    "left_moment",
    "left_shear",
    "right_deflection",
    "right_rotation",
];

/// A row's four errors, in [`OUTPUTS`]' order.
fn errors_of(row: &study::StudyRow) -> [f64; 4] {
    std::array::from_fn(|j| row.errors.get(j).map_or(f64::NAN, |e| e.1))
}

/// The end history of [`motion`] as four `signal` units driving `ports[..4]`.
fn drives(ports: &[&'static str; 8]) -> Vec<Drive> {
    let channels = [
        ("upper_deflection", "displacement", 0.01, 0.01, 0.0),
        ("upper_rotation", "rotation", 0.002, 0.001, 0.3),
        ("lower_moment", "moment", 50.0, 100.0, 0.7),
        ("lower_shear", "force", -10.0, 20.0, 1.1),
    ];
    channels
        .iter()
        .zip(ports)
        .map(|(&(name, quantity, offset, amplitude, phase), &to)| {
            let sines: Vec<String> = COMPONENTS
                .iter()
                .map(|(w, p)| {
                    format!(
                        "{{ amplitude = {}, angular_frequency = {}, phase = {} }}",
                        number(amplitude),
                        number(*w),
                        number(p + phase)
                    )
                })
                .collect();
            Drive {
                name,
                quantity,
                parameters: format!(
                    "offset = {}\nsines = [{}]\nfade_in = {{ shape = \"smoothstep\", time = 2.0 }}\n",
                    number(offset),
                    sines.join(", ")
                ),
                to,
            }
        })
        .collect()
}

/// The FE span of [`fe_span`] (trapezoidal rule) as a scene writes it.
fn fe_unit(span: &Span, name: &'static str, elements: usize, substeps: usize) -> UnitText {
    let input = |q: &str| format!("{{ quantity = \"{q}\", value = \"input\" }}");
    UnitText {
        name,
        kind: "beam",
        substeps,
        parameters: format!(
            "elements = {elements}\n{}static_start = true\nalpha = 0.0\nboundary.left = [{}, {}]\nboundary.right = [{}, {}]\n",
            span_properties(span),
            input("deflection"),
            input("rotation"),
            input("moment"),
            input("shear")
        ),
    }
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
