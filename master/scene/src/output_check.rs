//! `[output]` checked against the built system: indicators name recorded
//! outputs with as many references as signals, plots and the other keys name
//! what is there.

use crate::{Scene, SceneError, spec, uncertainty_check};
use slender_coupling::system::System;
use slender_units::Causality;
use slender_units::contract::names::check_name;

impl Scene {
    /// Indicators name existing outputs, recorded ones, with as many references as
    /// signals or none.
    pub(crate) fn check_indicators(&self, system: &System) -> Result<(), SceneError> {
        for (i, ind) in self.spec.output.indicators.iter().enumerate() {
            let key = format!("output.indicators[{i}]");
            if let Some(from) = ind.from
                && !(from.is_finite() && from >= self.start.as_secs())
            {
                return Err(self.error(
                    None,
                    &format!("{key}.from"),
                    format!(
                        "{from}: expected a time (s) at or after the run's start, {}",
                        self.start.as_secs()
                    ),
                ));
            }
            let paired = ind.reference.is_empty()
                || ind.signals.len() == ind.reference.len()
                || ind.combine == spec::Combine::Largest;
            if ind.signals.is_empty() || !paired {
                return Err(self.error(None, &key, format!(
                    "expected at least one signal, and as many reference signals as signals or none (got {} and {}; `combine = \"largest\"` compares the largest of each side)",
                    ind.signals.len(),
                    ind.reference.len()
                )));
            }
            for s in ind.signals.iter().chain(&ind.reference) {
                system
                    .resolve(s, Causality::Output)
                    .map_err(|m| self.error(None, &key, m))?;
                if !self.spec.output.signals.is_empty() && !self.spec.output.signals.contains(s) {
                    return Err(self.error(
                        None,
                        &key,
                        format!("`{s}` is not among output.signals"),
                    ));
                }
            }
        }
        Ok(())
    }

    /// Signals listed once each; plots and indicators named by the name rules,
    /// uniquely, drawing recorded signals only: checked before a run, so a run
    /// never fails at its plotting stage.
    pub(crate) fn check_outputs(&self, system: &System) -> Result<(), SceneError> {
        let out = &self.spec.output;
        for (i, s) in out.signals.iter().enumerate() {
            if out.signals[..i].contains(s) {
                return Err(self.error(
                    None,
                    &format!("output.signals[{i}]"),
                    format!("`{s}` is listed twice"),
                ));
            }
        }
        let recorded = |s: &String| {
            if out.signals.is_empty() {
                system
                    .resolve(s, Causality::Output)
                    .map(|_| ())
                    .map_err(|e| e.to_string())
            } else if out.signals.contains(s) {
                Ok(())
            } else {
                Err(format!("`{s}` is not among output.signals"))
            }
        };
        if let Some((key, message)) = uncertainty_check::problem(&self.spec) {
            return Err(self.error(None, &key, message));
        }
        if let Some(from) = out
            .quantities_from
            .filter(|f| !(f.is_finite() && *f >= 0.0))
        {
            return Err(self.error(
                None,
                "output.quantities_from",
                format!("{from}: expected a time (s) from 0 on"),
            ));
        }
        for (i, p) in out.plots.iter().enumerate() {
            let key = format!("output.plots[{i}]");
            if p.panels.is_empty() || p.panels.iter().any(Vec::is_empty) {
                return Err(self.error(
                    None,
                    &format!("{key}.panels"),
                    "expected at least one panel, each with at least one signal (an empty one draws a blank figure)".to_owned(),
                ));
            }
            check_name("plot name", &p.name)
                .map_err(|m| self.error(None, &format!("{key}.name"), m))?;
            if out.plots[..i].iter().any(|q| q.name == p.name) {
                return Err(self.error(
                    None,
                    &format!("{key}.name"),
                    format!(
                        "`{}` is used by an earlier plot: each plot writes <name>.svg",
                        p.name
                    ),
                ));
            }
            for s in p.panels.iter().flatten() {
                recorded(s).map_err(|m| self.error(None, &format!("{key}.panels"), m))?;
            }
        }
        for (i, ind) in out.indicators.iter().enumerate() {
            let key = format!("output.indicators[{i}].name");
            check_name("indicator name", &ind.name).map_err(|m| self.error(None, &key, m))?;
            if out.indicators[..i].iter().any(|j| j.name == ind.name) {
                return Err(self.error(None, &key, format!("`{}` is used twice", ind.name)));
            }
        }
        Ok(())
    }
}
