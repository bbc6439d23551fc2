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
        /// The FMU's file.
        fmu: String,
        /// What could not be done.
        problem: &'static str,
        /// Why.
        reason: String,
    },
    /// `modelDescription.xml` does not parse or lacks what a master relies on.
    #[error("{fmu}: {source}")]
    Description {
        /// The FMU's file.
        fmu: String,
        /// Where and why it does not parse.
        source: DescriptionError,
    },
    /// The FMU offers model exchange only.
    #[error(
        "{fmu}: the FMU does not offer co-simulation (no <CoSimulation> element); only co-simulation FMUs (FMI 2.0 or 3.0) can be units"
    )]
    NotCoSimulation {
        /// The FMU's file.
        fmu: String,
    },
    /// FMI 3.0 clocks: slender's master has no clock or event mode.
    #[error(
        "{fmu}: the FMU declares clocks or clocked variables ({names}); slender does not run clocked FMUs (no clock or event mode in its master)"
    )]
    Clocked {
        /// The FMU's file.
        fmu: String,
        /// The clocks and clocked variables.
        names: String,
    },
    /// No binary for 64-bit Linux; `found` says what the FMU has instead.
    #[error(
        "{fmu}: no binary for this platform: expected binaries/{identifier}.so; the FMU has {found}"
    )]
    NoBinary {
        /// The FMU's file.
        fmu: String,
        /// Its model identifier.
        identifier: String,
        /// The binaries it has.
        found: String,
    },
    /// The binary (or a library to preload) does not load, or lacks an FMI entry
    /// point; `message` says which and how to fix it.
    #[error("{fmu}: {message}")]
    Library {
        /// The FMU's file.
        fmu: String,
        /// Which library or entry point, and how to fix it.
        message: String,
    },
    /// A start value for a variable the FMU does not have.
    #[error("{fmu}: start.{name}: the FMU has no variable `{name}`{hint}")]
    UnknownStart {
        /// The FMU's file.
        fmu: String,
        /// The name given.
        name: String,
        /// A close name, when there is one.
        hint: String,
    },
    /// A start value for a variable that is neither a parameter nor an input.
    #[error(
        "{fmu}: start.{name}: `{name}` is not a parameter or an input (its causality is {causality:?})"
    )]
    NotSettable {
        /// The FMU's file.
        fmu: String,
        /// The variable.
        name: String,
        /// Its causality.
        causality: VariableCausality,
    },
    /// A start value of the wrong type.
    #[error("{fmu}: start.{name} = {value}: expected a {expected} value")]
    WrongStartType {
        /// The FMU's file.
        fmu: String,
        /// The variable.
        name: String,
        /// The value given.
        value: String,
        /// The variable's type.
        expected: &'static str,
    },
    /// A text passed to the FMU contains a NUL character.
    #[error("{fmu}: `{text}` contains a NUL character")]
    Nul {
        /// The FMU's file.
        fmu: String,
        /// The text.
        text: String,
    },
    /// Instantiation returned null; `log` holds the FMU's last log lines.
    #[error("{fmu}: {call} failed{log}")]
    Instantiate {
        /// The FMU's file.
        fmu: String,
        /// The FMI call.
        call: &'static str,
        /// The FMU's last log lines.
        log: String,
    },
}
