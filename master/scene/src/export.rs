//! Exporting a scene's units as FMUs: the half of FMI export that needs the kind
//! registry (building a unit from an FMU's configuration, settling a scene for its
//! start inputs, wrapping a whole scene). The FMU layout and packaging themselves
//! are in `slender_fmi::export`.

use crate::kinds::BuildError;
use crate::{Scene, SceneError};
use slender_coupling::Master;
use slender_coupling::MasterError;
pub use slender_fmi::export::FmiVersion;
use slender_fmi::export::{ExportConfig, Layout, PackageError, input_variable_name};
pub use slender_kinds::exported::ExportedUnit;
use slender_units::UnitError;
use std::collections::BTreeMap;
use std::path::Path;

/// Why a scene's unit could not be exported (or a scene wrapped).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ExportError {
    /// The scene has no unit of that name.
    #[error("{scene}: no unit `{unit}`; its units are: {units}")]
    NoUnit {
        /// The scene file.
        scene: String,
        /// The unit asked for.
        unit: String,
        /// The units it has, listed.
        units: String,
    },
    /// The scene does not read or build.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// The scene's start could not be settled before export.
    #[error("{scene}: initialisation: {source}")]
    Initialization {
        /// The scene file.
        scene: String,
        /// Why the master's initialisation failed.
        source: Box<MasterError>,
    },
    /// A unit could not be built from its parameters.
    #[error(transparent)]
    Build(#[from] BuildError),
    /// A unit refused a call while settling.
    #[error(transparent)]
    Unit(#[from] UnitError),
    /// Writing the FMU.
    #[error(transparent)]
    Write(#[from] PackageError),
    /// The scene file cannot be read or rewritten as a wrapped scene.
    #[error("{path}: {problem}")]
    SceneFile {
        /// The file or folder.
        path: String,
        /// What went wrong.
        problem: String,
    },
}

/// An exported unit's configuration from a scene (building the unit from it is
/// [`ExportedUnit`], in `slender-kinds` with the registry; the configuration is
/// in `slender-fmi`).
pub trait SceneExport: Sized {
    /// The section of unit `unit` of a loaded scene.
    fn from_scene(scene: &Scene, unit: &str) -> Result<Self, ExportError>;

    /// The section of unit `unit`, with the start inputs of `master`, the scene
    /// already initialised (see [`settle`]).
    fn from_settled(scene: &Scene, master: &Master, unit: &str) -> Result<Self, ExportError>;
}

impl SceneExport for ExportConfig {
    fn from_scene(scene: &Scene, unit: &str) -> Result<ExportConfig, ExportError> {
        Self::from_settled(scene, &settle(scene)?, unit)
    }

    fn from_settled(
        scene: &Scene,
        master: &Master,
        unit: &str,
    ) -> Result<ExportConfig, ExportError> {
        let spec = scene
            .spec
            .units
            .iter()
            .find(|u| u.name.get_ref() == unit)
            .ok_or_else(|| {
                let names: Vec<&str> = scene
                    .spec
                    .units
                    .iter()
                    .map(|u| u.name.get_ref().as_str())
                    .collect();
                ExportError::NoUnit {
                    scene: scene.path.display().to_string(),
                    unit: unit.to_owned(),
                    units: names.join(", "),
                }
            })?;
        let index =
            master
                .unit_names()
                .position(|n| n == unit)
                .ok_or_else(|| ExportError::NoUnit {
                    scene: scene.path.display().to_string(),
                    unit: unit.to_owned(),
                    units: master.unit_names().collect::<Vec<_>>().join(", "),
                })?;
        let inputs = master
            .description(index)
            .inputs
            .iter()
            .zip(master.inputs(index))
            .map(|(p, v)| (p.name.clone(), *v))
            .collect();
        // A written-out unit's typed parameters become the FMU's table here.
        let parameters = match (&spec.written, &spec.parameters) {
            (Some(written), _) => written.to_table().map_err(|e| {
                BuildError::Parameters(format!("unit `{unit}`: its parameters as TOML: {e}"))
            })?,
            (None, Some(p)) => p.get_ref().clone(),
            (None, None) => toml::Table::new(),
        };
        let mut config = ExportConfig {
            name: unit.to_owned(),
            kind: spec.kind.get_ref().clone(),
            effects: spec.effects.clone(),
            hold: spec.hold,
            inputs,
            parameters,
            start_time: scene.start.as_secs(),
            stop_time: scene.end().as_secs(),
            step: scene.step.as_secs(),
            guid: String::new(),
        };
        config.guid = config.fingerprint();
        Ok(config)
    }
}

/// Writes the FMI 2.0 FMU for `config` to `out` (see
/// `slender_fmi::export::package`) and returns its layout.
pub fn package(config: &ExportConfig, binary: &Path, out: &Path) -> Result<Layout, ExportError> {
    package_version(config, binary, out, FmiVersion::Two)
}

/// Writes the FMU for `config` to `out` as FMI `version` and returns its layout.
pub fn package_version(
    config: &ExportConfig,
    binary: &Path,
    out: &Path,
    version: FmiVersion,
) -> Result<Layout, ExportError> {
    let layout = config.layout()?;
    slender_fmi::export::package_version(config, &layout, binary, out, version)?;
    Ok(layout)
}

/// The scene built and initialised: its master holds the settled start inputs of
/// every unit.
pub fn settle(scene: &Scene) -> Result<Master, ExportError> {
    let mut master = scene.build()?;
    master
        .initialize(scene.start)
        .map_err(|e| ExportError::Initialization {
            scene: scene.path.display().to_string(),
            source: Box::new(e),
        })?;
    Ok(master)
}

/// Exports every unit of a scene as an FMU (FMI `version`) into `dir` and
/// writes there a copy of the scene whose units are those FMUs (kind `fmu`),
/// so the same run can go through the FMI layer. Returns the new scene's path.
pub fn wrap_scene(
    scene: &Scene,
    binary: &Path,
    dir: &Path,
    version: FmiVersion,
) -> Result<std::path::PathBuf, ExportError> {
    let file_error = |path: &Path, problem: String| ExportError::SceneFile {
        path: path.display().to_string(),
        problem,
    };
    // The scene as loaded: a `[structure]` already written out as units.
    let mut table: toml::Table = toml::from_str(scene.source()?)
        .map_err(|e| file_error(&scene.path, e.message().to_owned()))?;
    std::fs::create_dir_all(dir).map_err(|e| file_error(dir, format!("cannot create ({e})")))?;
    let units = table
        .get_mut("units")
        .and_then(toml::Value::as_array_mut)
        .ok_or_else(|| file_error(&scene.path, "no [[units]]".into()))?;
    let exported = export_units(scene, binary, dir, version)?;
    // Inputs renamed in the FMUs ("unit.port" -> "unit.port_in"), for the
    // connections below.
    let mut renamed = BTreeMap::new();
    for unit in units.iter_mut() {
        let unit = unit
            .as_table_mut()
            .ok_or_else(|| file_error(&scene.path, "a [[units]] entry is not a table".into()))?;
        let name = unit
            .get("name")
            .and_then(toml::Value::as_str)
            .ok_or_else(|| file_error(&scene.path, "a unit without a name".into()))?
            .to_owned();
        let (file, layout) = exported
            .iter()
            .find(|e| e.name == name)
            .map(|e| (format!("{name}.fmu"), &e.layout))
            .ok_or_else(|| file_error(&scene.path, format!("unit `{name}` was not exported")))?;
        for (i, port) in layout.unit.inputs.iter().enumerate() {
            let variable = &input_variable_name(&layout.unit, i);
            if variable != &port.name {
                renamed.insert(
                    format!("{name}.{}", port.name),
                    format!("{name}.{variable}"),
                );
                if let Some(inputs) = unit.get_mut("inputs").and_then(toml::Value::as_table_mut)
                    && let Some(v) = inputs.remove(&port.name)
                {
                    inputs.insert(variable.clone(), v);
                }
            }
        }
        unit.insert("kind".into(), toml::Value::String("fmu".into()));
        unit.remove("effects");
        let mut parameters = toml::Table::new();
        parameters.insert("file".into(), toml::Value::String(file));
        unit.insert("parameters".into(), toml::Value::Table(parameters));
    }
    rewire_for_fmus(&mut table, &renamed, version);
    let out = dir.join(format!("{}_fmu.toml", scene_stem(scene)));
    let written = toml::to_string(&table).map_err(|e| file_error(&out, e.to_string()))?;
    std::fs::write(&out, written).map_err(|e| file_error(&out, format!("cannot write ({e})")))?;
    Ok(out)
}

/// One unit exported as an FMU: its name, the file written, its layout.
pub struct ExportedFmu {
    /// The unit's name in the scene.
    pub name: String,
    /// The FMU file written.
    pub file: std::path::PathBuf,
    /// Its variables and model description.
    pub layout: Layout,
}

/// Every unit of the scene exported as an FMU (FMI `version`) into `dir`
/// (`<unit>.fmu`), in scene order, each started from the inputs the scene's
/// master settles on.
pub fn export_units(
    scene: &Scene,
    binary: &Path,
    dir: &Path,
    version: FmiVersion,
) -> Result<Vec<ExportedFmu>, ExportError> {
    let master = settle(scene)?;
    let mut exported = Vec::new();
    for unit in &scene.spec.units {
        let name = unit.name.get_ref().clone();
        let config = ExportConfig::from_settled(scene, &master, &name)?;
        let file = dir.join(format!("{name}.fmu"));
        let layout = package_version(&config, binary, &file, version)?;
        exported.push(ExportedFmu { name, file, layout });
    }
    Ok(exported)
}

/// The scene file's stem ("scene" when it has none).
pub fn scene_stem(scene: &Scene) -> String {
    scene
        .path
        .file_stem()
        .map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned())
}

/// The wrapped scene's connections to renamed inputs, its title, and no output
/// folder of its own.
fn rewire_for_fmus(
    table: &mut toml::Table,
    renamed: &BTreeMap<String, String>,
    version: FmiVersion,
) {
    if let Some(connections) = table
        .get_mut("connections")
        .and_then(toml::Value::as_array_mut)
    {
        for c in connections.iter_mut().filter_map(toml::Value::as_table_mut) {
            let target = c.get("to").and_then(toml::Value::as_str).map(str::to_owned);
            if let Some(new) = target.and_then(|t| renamed.get(&t)) {
                c.insert("to".into(), toml::Value::String(new.clone()));
            }
        }
    }
    if let Some(title) = table.get("title").and_then(toml::Value::as_str) {
        let fmi = match version {
            FmiVersion::Two => "2.0",
            FmiVersion::Three => "3.0",
        };
        let title = format!("{title} [every unit through FMI {fmi}]");
        table.insert("title".into(), toml::Value::String(title));
    }
    if let Some(output) = table.get_mut("output").and_then(toml::Value::as_table_mut) {
        output.remove("directory");
    }
}
