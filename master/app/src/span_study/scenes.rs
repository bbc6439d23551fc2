//! The span studies as scenes: a prescribed end motion (`signal` units) driving
//! the model under study (a span unit or an FE span), and the reference (a fine
//! FE span) as a scene of its own. The studies write these scenes into their
//! results folder and run them through the general study engine, so each row can
//! be run again with `slender run` or `slender study`.

use super::StudyError;
use crate::study::{self, Design, ReferenceRun, StudyRow, Sweep};
use slender_units::span::transfer::Span;
use std::fmt::Write;
use std::path::Path;

/// A unit of a generated scene: name, kind, substeps, parameters as TOML lines.
pub(crate) struct UnitText {
    pub name: &'static str,
    pub kind: &'static str,
    pub substeps: usize,
    pub parameters: String,
}

/// One prescribed input: a `signal` unit of `quantity` with `parameters`,
/// driving the model's input port `to`.
pub(crate) struct Drive {
    pub name: &'static str,
    pub quantity: &'static str,
    pub parameters: String,
    pub to: &'static str,
}

/// A study scene: its title, time window, what drives the model and the
/// indicators (name, the model's output port), all measured by the peak norm.
pub(crate) struct StudyScene<'a> {
    pub title: String,
    pub duration: f64,
    pub step: f64,
    pub drives: &'a [Drive],
    pub model: UnitText,
    pub indicators: &'a [(&'static str, &'static str)],
}

/// A float as TOML writes it (Rust's shortest round-trip form).
pub(crate) fn number(x: f64) -> String {
    format!("{x:?}")
}

impl StudyScene<'_> {
    /// The scene as TOML text.
    pub(crate) fn text(&self) -> String {
        let m = &self.model;
        let mut t = format!(
            "title = {:?}\n\n[simulation]\nduration = {}\nstep = {}\n\n[master]\nscheme = \"gauss_seidel\"\n",
            self.title,
            number(self.duration),
            number(self.step)
        );
        let mut order: Vec<&str> = self.drives.iter().map(|d| d.name).collect();
        order.push(m.name);
        let _ = writeln!(t, "order = {order:?}");
        for d in self.drives {
            let _ = write!(
                t,
                "\n[[units]]\nname = {:?}\nkind = \"signal\"\n[units.parameters]\nquantity = {:?}\n{}",
                d.name, d.quantity, d.parameters
            );
        }
        let _ = write!(t, "\n[[units]]\nname = {:?}\nkind = {:?}\n", m.name, m.kind);
        if m.substeps > 1 {
            let _ = writeln!(t, "substeps = {}", m.substeps);
        }
        let _ = write!(t, "[units.parameters]\n{}", m.parameters);
        for d in self.drives {
            let _ = write!(
                t,
                "\n[[connections]]\nfrom = \"{}.value\"\nto = \"{}.{}\"\n",
                d.name, m.name, d.to
            );
        }
        let signals: Vec<String> = self
            .indicators
            .iter()
            .map(|(_, port)| format!("{}.{port}", m.name))
            .collect();
        let _ = write!(t, "\n[output]\nsignals = {signals:?}\n");
        for ((name, _), signal) in self.indicators.iter().zip(&signals) {
            let _ = write!(
                t,
                "\n[[output.indicators]]\nname = {name:?}\nsignals = [{signal:?}]\nnorm = \"peak\"\n"
            );
        }
        t
    }
}

/// The span's properties as parameter lines (EI, mu, c_d, L, T), shared by the
/// span units and the FE spans of a study.
pub(crate) fn span_properties(span: &Span) -> String {
    format!(
        "flexural_rigidity = {}\nmass_per_length = {}\ndamping_per_length = {}\nlength = {}\ntension = {}\n",
        number(span.flexural_rigidity),
        number(span.mass_per_length),
        number(span.damping_per_length),
        number(span.length),
        number(span.tension)
    )
}

/// Runs the scene at `path` through the study engine against `reference`, one
/// run at a time (so costs do not share the cores), the cost that of unit
/// `cost` alone (the whole run when empty).
pub(crate) fn engine_rows(
    path: &Path,
    sweeps: Vec<Sweep>,
    design: Design,
    cost: &str,
    reference: &ReferenceRun,
) -> Result<Vec<StudyRow>, StudyError> {
    let plan = study::StudyPlan {
        overrides: Vec::new(),
        max_runs: crate::DEFAULT_MAX_RUNS,
        sweeps,
        design,
        duration: None,
        jobs: 1,
        cost_units: if cost.is_empty() {
            Vec::new()
        } else {
            vec![cost.into()]
        },
        reference: None,
        repeats: 1,
    };
    Ok(study::run_study_against(
        path,
        &plan,
        Some(reference),
        |_| {},
    )?)
}

/// The order rows of a span study are reported in: span units as the plan
/// gives them, then FE spans by substeps and elements.
pub(crate) fn report_order(model: &str, substeps: usize, size: usize) -> (bool, usize, usize) {
    let fe = model == "fe";
    (fe, substeps, if fe { size } else { 0 })
}
