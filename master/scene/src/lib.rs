//! Scenes: TOML files describing one run (units, effects, connections, master
//! scheme and tolerances, time window, outputs), turned into a ready [`Master`].
//!
//! Errors name the file, the line where known, the key and what was expected.
pub mod analysis;
mod draft;
mod expansion;
pub mod export;
pub mod mooring;
mod output_check;
pub mod spec;
pub mod ssp;
pub mod structure;
mod structure_lines;
#[cfg(test)]
mod tests;
mod timing;
mod uncertainty_check;

/// The unit-kind registry (its own crate, `slender-kinds`, so the FMU library
/// links it without the scene).
pub use slender_kinds as kinds;
pub use slender_kinds::{fields, words};

pub use draft::{Draft, texts_parsed};
pub use expansion::texts_written;
use slender_coupling::Master;
use slender_coupling::error::did_you_mean;
use slender_coupling::system::{Link, System};
use slender_units::{Causality, Time};
use spec::SceneSpec;
use std::fmt;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// A problem in a scene file.
#[derive(Debug, Error)]
pub struct SceneError {
    /// The scene file (or SSP) named in the message.
    pub file: PathBuf,
    /// 1-based line, where known.
    pub line: Option<usize>,
    /// Dotted key, e.g. `units[1].parameters`; empty for whole-file problems.
    pub key: String,
    /// What was wrong and what was expected.
    pub message: String,
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file.display())?;
        if let Some(line) = self.line {
            write!(f, ":{line}")?;
        }
        if !self.key.is_empty() {
            write!(f, ": {}", self.key)?;
        }
        // Numbers as the user wrote them, not 1e308's 309 digits.
        write!(
            f,
            ": {}",
            slender_kinds::words::shorten_numbers(&self.message)
        )
    }
}

/// A parsed and checked scene.
#[derive(Debug)]
pub struct Scene {
    /// The scene file: names it in messages and anchors relative output folders.
    pub path: PathBuf,
    /// The scene as read and checked (with a `[structure]` written out as units and connections).
    pub spec: SceneSpec,
    /// The text the scene was read from (errors name its lines).
    source: String,
    /// The changes made to that text (`Draft`), named by an error about a
    /// changed value.
    changes: draft::Changes,
    /// With a `[structure]`: the units and connections it writes out, as the
    /// tables of the scene's text.
    written: Option<structure::Written>,
    /// That text, made when first asked for (`source`).
    expanded: std::sync::OnceLock<String>,
    /// The simulation's start.
    pub start: Time,
    /// The synchronisation step.
    pub step: Time,
    /// The synchronisation steps of the run.
    pub steps: i64,
    /// Keys set on the command line over the file (`slender run --set
    /// KEY=VALUE`), as given; empty for a scene as written.
    pub overrides: Vec<String>,
    /// An SSP's unpacked archive (its FMUs), kept as long as the scene.
    pub resources: Option<tempfile::TempDir>,
    /// What the scene's models follow poorly (a `[structure]` section's model
    /// that keeps its contact state where the touchdown point moves): said by
    /// `slender check` and among a run's warnings.
    pub advisories: Vec<String>,
}

impl Scene {
    /// Reads and checks a scene file (or an SSP archive, `.ssp`, or description,
    /// `.ssd`), and builds it once to check units and connections.
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        if ssp::is_ssp(path) {
            return ssp::load(path);
        }
        Draft::read(path)?.scene()
    }

    /// Checks a scene given as text; `path` names it in messages and anchors
    /// relative output folders. A `[structure]` is written out as typed units
    /// and connections appended to the scene's own (`expansion`): the text is
    /// read once, and every error names a line of it.
    pub fn parse(path: &Path, source: String) -> Result<Scene, SceneError> {
        Draft::parse(path, source)?.scene()
    }

    /// The scene typed from `document`, the spanned keys of the text
    /// `source` with the changes `origins` made (`Draft`; spans past the
    /// text's end mark a change's values) and the keys as changed
    /// (`edited`, None for the file as written).
    fn from_document(
        path: &Path,
        source: &str,
        document: toml::Spanned<toml::de::DeTable<'_>>,
        changes: draft::Changes,
    ) -> Result<Scene, SceneError> {
        let deserializer = toml::de::Deserializer::from(document.clone());
        let mut spec = <SceneSpec as serde::Deserialize>::deserialize(deserializer)
            .map_err(|e| spec_error(path, source, &changes.origins, document, e))?;
        // An error about a key a change made names the change.
        let named = |mut e: SceneError, top: &str| {
            let about = (structure_lines::named_keys(&e.message, top))
                .find(|k| !changes.origins_of(k).is_empty())
                .map(str::to_owned);
            // A changed value is not on the user's line.
            if about.is_some() {
                e.line = None;
            }
            changes.name_in(e, about.as_deref().unwrap_or(top))
        };
        let expansion = (spec.structure.take())
            .map(|s| expansion::expand(path, source, &s, spec.simulation.start))
            .transpose()
            .map_err(|e| named(e, "structure"))?;
        let structure = expansion.as_ref().map(|x| x.name.clone());
        let mooring = (spec.mooring.take())
            .map(|m| expansion::expand_mooring(path, source, &m, spec.simulation.start))
            .transpose()
            .map_err(|e| named(e, "mooring"))?;
        let (written, advisories) =
            expansion::append(&mut spec, expansion.into_iter().chain(mooring));
        let mut scene = Scene {
            path: path.to_owned(),
            spec,
            source: source.to_owned(),
            changes,
            written,
            expanded: std::sync::OnceLock::new(),
            start: Time::ZERO,
            step: Time::ZERO,
            steps: 0,
            overrides: Vec::new(),
            resources: None,
            advisories,
        };
        // An error in the units a structure writes out names the model
        // parameter or the section it is about.
        let name = structure.as_deref();
        if let Err(e) = scene.check_time() {
            return Err(expansion::locate(&scene.source, name, e));
        }
        scene.build().map_err(|e| {
            let generated = name.is_some_and(|n| e.key.contains(&format!("(\"{n}_")));
            let e = expansion::locate(&scene.source, name, e);
            match generated {
                true => scene.changes.name_in(e, "structure"),
                false => e,
            }
        })?;
        Ok(scene)
    }

    /// The scene's keys as they run: the file's, with the changes
    /// (`--set`, a study's) made; what a tool that reads a table of the
    /// scene (`[mooring]`, the structure's layout) reads. The error names
    /// the file.
    pub fn keys(&self) -> Result<std::borrow::Cow<'_, toml::Table>, SceneError> {
        match &self.changes.table {
            Some(table) => Ok(std::borrow::Cow::Borrowed(table)),
            None => toml::from_str(&self.source)
                .map(std::borrow::Cow::Owned)
                .map_err(|e| SceneError {
                    file: self.path.clone(),
                    line: None,
                    key: String::new(),
                    message: e.to_string(),
                }),
        }
    }

    /// The scene as it runs, as TOML text: the file's, with a `[structure]`
    /// written out as plain units and connections (what `slender expand`
    /// prints; that text is made when first asked for, for showing and
    /// exporting, and never read again).
    pub fn source(&self) -> Result<&str, SceneError> {
        if self.written.is_none() && self.changes.table.is_none() {
            return Ok(&self.source);
        }
        if let Some(text) = self.expanded.get() {
            return Ok(text);
        }
        let text = expansion::expanded_text(
            &self.source,
            self.changes.table.as_ref(),
            self.written.as_ref(),
        )
        .map_err(|message| self.error(None, "structure", message))?;
        Ok(self.expanded.get_or_init(|| text))
    }

    /// An error about `key`, at `span` of the text or of a change's values
    /// (then named by what made the change, without a line); in a changed
    /// scene, any other says which changes it was made with.
    fn error(
        &self,
        span: Option<std::ops::Range<usize>>,
        key: &str,
        message: impl fmt::Display,
    ) -> SceneError {
        let origin = (span.as_ref())
            .and_then(|s| draft::origin_of(&self.source, s))
            .and_then(|k| self.changes.origins.get(k));
        let e = SceneError {
            file: self.path.clone(),
            line: span
                .filter(|_| origin.is_none())
                .map(|s| line_of(&self.source, s.start)),
            key: key.to_owned(),
            message: match origin {
                Some(origin) => format!("{origin}: {message}"),
                None => message.to_string(),
            },
        };
        match origin {
            Some(_) => e,
            None => self.changes.name_in(e, key),
        }
    }

    /// Changes the synchronisation step (s), e.g. for a convergence study; the
    /// duration must stay a whole number of steps.
    pub fn set_step(&mut self, step: f64) -> Result<(), SceneError> {
        self.spec.simulation.step = step;
        self.check_time()
    }

    /// Changes the simulated time (s), e.g. a shorter look at a long scene; it
    /// must stay a whole number of steps.
    pub fn set_duration(&mut self, duration: f64) -> Result<(), SceneError> {
        self.spec.simulation.duration = duration;
        self.check_time()
    }

    /// Start time plus duration.
    pub fn end(&self) -> Time {
        self.start + self.step * self.steps
    }

    /// Builds a fresh master for this scene, with every unit in its initial state
    /// (not initialised yet).
    pub fn build(&self) -> Result<Master, SceneError> {
        let mut system = System::new();
        for (i, u) in self.spec.units.iter().enumerate() {
            self.add_unit(&mut system, i, u)?;
        }
        for (i, c) in self.spec.connections.iter().enumerate() {
            let link = Link {
                gain: c.gain,
                offset: c.offset,
                tolerance: c.tolerance,
            };
            system
                .connect(c.from.get_ref(), c.to.get_ref(), link)
                .map_err(|m| self.error(Some(c.from.span()), &format!("connections[{i}]"), m))?;
        }
        for (i, s) in self.spec.output.signals.iter().enumerate() {
            system
                .resolve(s, Causality::Output)
                .map_err(|m| self.error(None, &format!("output.signals[{i}]"), m))?;
        }
        self.check_indicators(&system)?;
        if self.spec.output.every == 0 {
            return Err(self.error(None, "output.every", "0: expected at least 1"));
        }
        // A window past the end (a run shortened by --duration) is said in
        // the run's warnings, not refused.
        self.check_analysis(&system)?;
        if let Err((key, message)) = self.spec.output.watch.check() {
            return Err(self.error(None, key, message));
        }
        self.check_outputs(&system)?;
        let mut master = Master::new(system, self.spec.master.clone(), self.step)
            .map_err(|e| self.error(None, "master", e.to_string()))?;
        for (u, spec) in self.spec.units.iter().enumerate() {
            if let Some(hold) = spec.hold {
                master
                    .set_hold(u, hold)
                    .map_err(|e| self.error(None, &format!("units[{u}].hold"), e.to_string()))?;
            }
            if let Some(n) = spec.substeps {
                self.check_substeps(u, n)?;
                master.set_substeps(u, n).map_err(|e| {
                    self.error(None, &format!("units[{u}].substeps"), e.to_string())
                })?;
            }
        }
        Ok(master)
    }

    /// A unit's `substeps`: at least 1, and the step splits into that many
    /// whole nanoseconds.
    fn check_substeps(&self, u: usize, n: u32) -> Result<(), SceneError> {
        if self.step.split(n).is_none() {
            return Err(self.error(
                self.spec.units[u].name.span().into(),
                &format!("units[{u}].substeps"),
                format!(
                    "{n}: expected a whole number >= 1 that splits the step ({}) into whole nanoseconds",
                    self.step
                ),
            ));
        }
        Ok(())
    }

    /// Builds unit `i` of the scene and adds it with its start inputs.
    fn add_unit(
        &self,
        system: &mut System,
        i: usize,
        u: &spec::UnitSpec,
    ) -> Result<(), SceneError> {
        let key = format!("units[{i}]");
        let kind = kinds::find(u.kind.get_ref()).ok_or_else(|| {
            self.error(
                Some(u.kind.span()),
                &format!("{key}.kind"),
                format!(
                    "unknown unit kind `{}`{}; known kinds: {}",
                    u.kind.get_ref(),
                    did_you_mean(u.kind.get_ref(), kinds::KINDS.iter().map(|k| k.name)),
                    kinds::KINDS
                        .iter()
                        .map(|k| k.name)
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            )
        })?;
        let (parameters, span) = match (&u.written, &u.parameters) {
            (Some(written), _) => (written.clone().given(), u.name.span()),
            (None, Some(p)) => (kinds::Given::Table(p.get_ref().clone()), p.span()),
            (None, None) => (kinds::Given::Table(toml::Table::new()), u.name.span()),
        };
        let base_dir = self.path.parent().unwrap_or(Path::new("."));
        let context = kinds::BuildContext {
            effects: &u.effects,
            base_dir,
        };
        let unit = kind.build(parameters, &context).map_err(|m| {
            self.error(
                Some(span),
                &format!("{key} (\"{}\").parameters", u.name.get_ref()),
                m,
            )
        })?;
        system
            .add_unit(u.name.get_ref(), unit)
            .map_err(|m| self.error(Some(u.name.span()), &format!("{key}.name"), m))?;
        for (port, value) in &u.inputs {
            system
                .set_start_input(&format!("{}.{port}", u.name.get_ref()), *value)
                .map_err(|m| self.error(Some(u.name.span()), &format!("{key}.inputs.{port}"), m))?;
        }
        Ok(())
    }

    /// The recorded signals: those listed in `[output]`, or every output.
    pub fn signals(&self, master: &Master) -> Vec<String> {
        if !self.spec.output.signals.is_empty() {
            return self.spec.output.signals.clone();
        }
        let mut all = Vec::new();
        for (u, name) in master.unit_names().enumerate() {
            for p in &master.description(u).outputs {
                all.push(format!("{name}.{}", p.name));
            }
        }
        all
    }

    /// Where results go unless the CLI says otherwise.
    pub fn default_output_dir(&self) -> PathBuf {
        match &self.spec.output.directory {
            Some(d) => PathBuf::from(d),
            None => {
                let stem = self
                    .path
                    .file_stem()
                    .map(|s| s.to_string_lossy().into_owned());
                Path::new("results").join(stem.unwrap_or_else(|| "scene".into()))
            }
        }
    }
}

/// A scene that does not type as `SceneSpec`: the error at the line of the
/// text `source` it points at, or naming the change (of `origins`) whose
/// value it is about; the key from the spanned `document` where the line
/// does not start with it.
fn spec_error(
    path: &Path,
    source: &str,
    origins: &[String],
    document: toml::Spanned<toml::de::DeTable<'_>>,
    e: toml::de::Error,
) -> SceneError {
    // A key missing from the whole file: no line or key to blame.
    let span = e
        .span()
        .filter(|s| !(s.start == 0 && (s.end == 0 || s.end >= source.trim_end().len())));
    let origin = (span.as_ref())
        .and_then(|s| draft::origin_of(source, s))
        .and_then(|k| origins.get(k));
    let key_path = || {
        let deserializer = toml::de::Deserializer::from(document);
        let error = serde_path_to_error::deserialize::<_, SceneSpec>(deserializer).err()?;
        let path = error.path().to_string();
        (!path.is_empty() && path != ".").then(|| format!("`{path}`"))
    };
    let message = migration_hint(e.message().trim());
    match origin {
        Some(origin) => SceneError {
            file: path.to_owned(),
            line: None,
            key: key_path().unwrap_or_default(),
            message: format!("{origin}: {message}"),
        },
        None => SceneError {
            file: path.to_owned(),
            line: span.clone().map(|s| line_of(source, s.start)),
            key: span
                .map(|s| key_at(source, s.start))
                .filter(|key| !key.starts_with("`{"))
                .or_else(key_path)
                .unwrap_or_default(),
            message,
        },
    }
}

/// A message with a hint where a scene uses a form slender no longer reads.
fn migration_hint(message: &str) -> String {
    let message = &words::in_words(message);
    if message.contains("unknown variant `newton`") {
        format!(
            "{message}; Newton is not a fixed-point acceleration: write `newton = {{}}` (or `newton = {{ perturbation = 1e-7, jacobian = \"every_iteration\" }}`) in [master] instead"
        )
    } else {
        message.to_owned()
    }
}

/// The key or table header on the line of `offset`, to name where a type error is
/// (toml's messages give the expected type but not the key).
fn key_at(source: &str, offset: usize) -> String {
    let start = source[..offset.min(source.len())]
        .rfind('\n')
        .map_or(0, |i| i + 1);
    let line = source[start..].lines().next().unwrap_or("").trim();
    let key = line.split('=').next().unwrap_or("").trim();
    if key.is_empty() {
        String::new()
    } else {
        format!("`{}`", key.chars().take(80).collect::<String>())
    }
}

fn line_of(source: &str, offset: usize) -> usize {
    source[..offset.min(source.len())].matches('\n').count() + 1
}
