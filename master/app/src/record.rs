//! Recording a run: time series at synchronisation points, written as CSV while the
//! run goes (so a failed run leaves readable partial results, under the
//! partial name until the run ends) and kept in memory for plots.

use crate::run::RunError;
use slender_coupling::coupler::Master;
use slender_units::Causality;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

/// Recorded signals: names, and one column of values per signal.
pub struct Recorder {
    /// The signals' names (`unit.port`).
    pub names: Vec<String>,
    /// Each signal's unit of measure (`""` where it has none).
    pub units: Vec<String>,
    ports: Vec<(usize, usize)>,
    /// Recorded times (s).
    pub time: Vec<f64>,
    /// One column of values per signal, one value per recorded time.
    pub columns: Vec<Vec<f64>>,
    /// The CSV as it is written (its partial name) and its final path.
    csv: Option<(BufWriter<File>, std::path::PathBuf)>,
    every: u32,
    counter: u32,
    /// With `[output] envelopes`: the units' fields, every step.
    envelopes: Option<crate::envelopes::Envelopes>,
}

/// The CSV header: `time [s]`, then each signal with its unit of measure in
/// brackets (`line.top_force [N]`; a dimensionless one bare), so that the file
/// says its units to any reader (summary.json lists them too).
pub fn header(signals: &[String], units: &[String]) -> String {
    let column = |name: &str, unit: &str| match unit {
        "" => name.to_owned(),
        unit => format!("{name} [{unit}]"),
    };
    std::iter::once(column("time", "s"))
        .chain(signals.iter().zip(units).map(|(s, u)| column(s, u)))
        .collect::<Vec<_>>()
        .join(",")
}

/// A header column's signal name and unit (`""` when it gives none): the
/// inverse of [`header`].
pub fn split_column(column: &str) -> (&str, &str) {
    match column.strip_suffix(']').and_then(|c| c.rsplit_once(" [")) {
        Some((name, unit)) => (name, unit),
        None => (column, ""),
    }
}

impl Recorder {
    /// Records `signals` ("unit.port" outputs) every `every` steps, writing CSV to
    /// `csv_path` when given.
    pub fn new(
        master: &Master,
        signals: Vec<String>,
        every: u32,
        csv_path: Option<&Path>,
    ) -> Result<Recorder, RunError> {
        let ports = signals
            .iter()
            .map(|s| master.find(s, Causality::Output).map_err(RunError::from))
            .collect::<Result<Vec<_>, _>>()?;
        let units = signals
            .iter()
            .map(|s| {
                master
                    .output_unit(s)
                    .map(str::to_owned)
                    .map_err(RunError::from)
            })
            .collect::<Result<Vec<_>, _>>()?;
        let csv = match csv_path {
            Some(p) => {
                let partial = crate::whole::partial(p);
                let f = File::create(&partial).map_err(|e| RunError::file(&partial, &e))?;
                let mut w = BufWriter::new(f);
                writeln!(w, "{}", header(&signals, &units))
                    .map_err(|e| RunError::file(&partial, &e))?;
                Some((w, p.to_owned()))
            }
            None => None,
        };
        Ok(Recorder {
            units,
            columns: vec![Vec::new(); signals.len()],
            names: signals,
            ports,
            time: Vec::new(),
            csv,
            every: every.max(1),
            counter: 0,
            envelopes: None,
        })
    }

    /// Records the master's current outputs, honouring `every` (the first call, at
    /// the initial time, is always recorded); an error names the CSV file.
    pub fn observe(&mut self, master: &Master) -> Result<(), RunError> {
        if let Some(e) = &mut self.envelopes {
            e.observe(master, master.time().as_secs());
        }
        let due = self.counter % self.every == 0;
        self.counter += 1;
        if !due {
            return Ok(());
        }
        let t = master.time().as_secs();
        self.time.push(t);
        for (col, &(u, p)) in self.columns.iter_mut().zip(&self.ports) {
            col.push(master.outputs(u)[p]);
        }
        if let Some((w, path)) = &mut self.csv {
            let row = |w: &mut BufWriter<File>| {
                write!(w, "{t}")?;
                for col in &self.columns {
                    write!(w, ",{:e}", col.last().copied().unwrap_or(f64::NAN))?;
                }
                writeln!(w)
            };
            row(w).map_err(|e| RunError::file(&crate::whole::partial(path), &e))?;
        }
        Ok(())
    }

    /// Flushes the CSV file and gives it its name (`timeseries.csv`): it was
    /// `timeseries.csv.partial` while the run went, so a run killed outright
    /// leaves no CSV that looks finished. Called on every end of a run
    /// (completed, failed, interrupted).
    pub fn finish(&mut self) -> Result<(), RunError> {
        match self.csv.take() {
            Some((mut w, path)) => {
                let partial = crate::whole::partial(&path);
                w.flush().map_err(|e| RunError::file(&partial, &e))?;
                drop(w);
                std::fs::rename(&partial, &path).map_err(|e| RunError::file(&path, &e))
            }
            None => Ok(()),
        }
    }

    /// Keeps the envelopes of the units' fields from `from` (s) on, every
    /// step whatever `every` says.
    pub fn envelope_from(&mut self, from: f64) {
        self.envelopes = Some(crate::envelopes::Envelopes::new(from));
    }

    /// The envelopes kept (none unless asked for).
    pub fn take_envelopes(&mut self) -> Vec<crate::envelopes::Envelope> {
        self.envelopes.take().map_or(Vec::new(), |e| e.finish())
    }

    /// The unit of the signal `name`, if recorded.
    pub fn unit(&self, name: &str) -> Option<&str> {
        let i = self.names.iter().position(|n| n == name)?;
        Some(&self.units[i])
    }

    /// The recorded column of `name`, if recorded.
    pub fn column(&self, name: &str) -> Option<&[f64]> {
        self.names
            .iter()
            .position(|n| n == name)
            .map(|i| self.columns[i].as_slice())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_header_carries_units_and_splits_back() {
        let signals = ["a.displacement".to_owned(), "a.ratio".to_owned()];
        let units = ["m".to_owned(), String::new()];
        let header = header(&signals, &units);
        assert_eq!(header, "time [s],a.displacement [m],a.ratio");
        let split: Vec<(&str, &str)> = header.split(',').map(split_column).collect();
        assert_eq!(
            split,
            [("time", "s"), ("a.displacement", "m"), ("a.ratio", "")]
        );
        assert_eq!(split_column("x [N m]"), ("x", "N m"));
    }
}
