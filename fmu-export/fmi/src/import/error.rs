//! Why an FMU could not become a unit. Every message starts with the FMU's file.

use crate::model_description::{DescriptionError, VariableCausality};
use thiserror::Error;

/// A failure to load an FMU as a unit (`FmuUnit::load`).
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum LoadError {
    /// The file is not a readable FMU archive (open, unzip, temporary folder, no
    /// model description at its root).
    #[error("{fmu}: {problem} ({reason})")]
    Archive {
        fmu: String,
        problem: &'static str,
        reason: String,
    },
    /// `modelDescription.xml` does not parse or lacks what a master relies on.
    #[error("{fmu}: {source}")]
    Description {
        fmu: String,
        source: DescriptionError,
    },
    #[error(
        "{fmu}: the FMU does not offer co-simulation (no <CoSimulation> element); only co-simulation FMUs (FMI 2.0 or 3.0) can be units"
    )]
    NotCoSimulation { fmu: String },
    /// FMI 3.0 clocks: slender's master has no clock or event mode.
    #[error(
        "{fmu}: the FMU declares clocks or clocked variables ({names}); slender does not run clocked FMUs (no clock or event mode in its master)"
    )]
    Clocked { fmu: String, names: String },
    /// No binary for 64-bit Linux; `found` says what the FMU has instead.
    #[error(
        "{fmu}: no binary for this platform: expected binaries/{identifier}.so; the FMU has {found}"
    )]
    NoBinary {
        fmu: String,
        identifier: String,
        found: String,
    },
    /// The binary (or a library to preload) does not load, or lacks an FMI entry
    /// point; `message` says which and how to fix it.
    #[error("{fmu}: {message}")]
    Library { fmu: String, message: String },
    #[error("{fmu}: start.{name}: the FMU has no variable `{name}`{hint}")]
    UnknownStart {
        fmu: String,
        name: String,
        hint: String,
    },
    #[error(
        "{fmu}: start.{name}: `{name}` is not a parameter or an input (its causality is {causality:?})"
    )]
    NotSettable {
        fmu: String,
        name: String,
        causality: VariableCausality,
    },
    #[error("{fmu}: start.{name} = {value}: expected a {expected} value")]
    WrongStartType {
        fmu: String,
        name: String,
        value: String,
        expected: &'static str,
    },
    #[error("{fmu}: `{text}` contains a NUL character")]
    Nul { fmu: String, text: String },
    /// Instantiation returned null; `log` holds the FMU's last log lines.
    #[error("{fmu}: {call} failed{log}")]
    Instantiate {
        fmu: String,
        call: &'static str,
        log: String,
    },
}
