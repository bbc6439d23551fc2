//! Sea states (issue 28): a wave elevation from a Pierson-Moskowitz or JONSWAP
//! spectrum ([`spectrum`]) and a vessel motion from it through a response
//! amplitude operator ([`rao`]), as sines added to a `signal` unit or to any
//! prescribed end motion (`sea = { spectrum = {...}, rao = {...} }`), so a
//! structure's top can follow an irregular sea.

pub mod rao;
pub mod spectrum;

use crate::contract::UnitError;
use crate::signal::sine::Sine;
use serde::{Deserialize, Serialize};

/// A sea state, and the motion it makes when a RAO is given (else the
/// elevation itself, m).
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SeaState {
    /// The wave spectrum and how its components are drawn.
    pub spectrum: spectrum::Spectrum,
    /// The vessel's motion RAO, to turn waves into motion.
    #[serde(default)]
    pub rao: Option<rao::Rao>,
}

impl SeaState {
    /// Checks the spectrum and the RAO; `key` is where the sea state is
    /// (e.g. `sea` or `ends.end.z.displacement.sea`), for the message.
    pub fn validate(&self, key: &str) -> Result<(), UnitError> {
        if let Err((k, value, expected)) = self.spectrum.validate() {
            return Err(UnitError::parameter(
                &format!("{key}.spectrum.{k}"),
                value,
                expected,
            ));
        }
        if let Some(Err((k, value, expected))) = self.rao.as_ref().map(rao::Rao::validate) {
            return Err(UnitError::parameter(
                &format!("{key}.rao.{k}"),
                value,
                expected,
            ));
        }
        Ok(())
    }

    /// The sines of the sea state (empty where it does not validate: the
    /// unit's own check refuses it then).
    pub fn sines(&self) -> Vec<Sine> {
        if self.validate("sea").is_err() {
            return Vec::new();
        }
        let waves = self.spectrum.sines();
        match &self.rao {
            Some(rao) => rao.apply(&waves),
            None => waves,
        }
    }
}

#[cfg(test)]
mod tests;
