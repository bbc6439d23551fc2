//! SSP 1.0: a scene's units as FMUs in one archive with the system's structure
//! (`slender fmu wrap SCENE --out X.ssp`), and an archive, slender's or another
//! tool's, as a scene (`slender run X.ssp`): its components as units of kind
//! `fmu`, its connections with their linear transformations as gains and
//! offsets, its default experiment and fixed step as the time window, the
//! non-iterative Jacobi scheme that libcosim's fixed-step algorithm runs, and
//! inputs held over each step (an SSP master passes values, not derivatives).

use crate::export::{ExportError, ExportedFmu, FmiVersion, export_units, scene_stem};
use crate::{Scene, SceneError};
use slender_fmi::export::input_variable_name;
use slender_fmi::model_description::{Value as FmiValue, VariableCausality};
use slender_fmi::ssp::{
    Component, Connection, Connector, ConnectorKind, SystemStructure, archive, ssd_unit,
};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use toml::{Table, Value};

/// Writes the scene's system as an SSP archive at `out` (every unit an FMU
/// built with `binary`, started from the scene's settled inputs); returns the
/// structure written.
pub fn write_ssp(scene: &Scene, binary: &Path, out: &Path) -> Result<SystemStructure, ExportError> {
    let dir = tempfile::tempdir().map_err(|e| ExportError::SceneFile {
        path: out.display().to_string(),
        problem: format!("no temporary folder for the FMUs ({e})"),
    })?;
    let mut components = Vec::new();
    let mut fmus = Vec::new();
    // (unit, input port) -> the FMU's variable name.
    let mut variables = BTreeMap::new();
    for ExportedFmu { name, file, layout } in
        export_units(scene, binary, dir.path(), FmiVersion::Two)?
    {
        let mut connectors = Vec::new();
        for (i, port) in layout.unit.inputs.iter().enumerate() {
            let variable = input_variable_name(&layout.unit, i);
            variables.insert((name.clone(), port.name.clone()), variable.clone());
            connectors.push(Connector {
                name: variable,
                kind: ConnectorKind::Input,
                unit: ssd_unit(&port.unit).map(str::to_owned),
            });
        }
        connectors.extend(layout.unit.outputs.iter().map(|p| Connector {
            name: p.name.clone(),
            kind: ConnectorKind::Output,
            unit: ssd_unit(&p.unit).map(str::to_owned),
        }));
        let source = format!("resources/{name}.fmu");
        fmus.push((source.clone(), file));
        components.push(Component {
            name,
            source,
            connectors,
            parameters: BTreeMap::new(),
        });
    }
    let connections = scene
        .spec
        .connections
        .iter()
        .filter_map(|c| {
            let (from_unit, from_port) = c.from.get_ref().split_once('.')?;
            let (to_unit, to_port) = c.to.get_ref().split_once('.')?;
            let variable = variables.get(&(to_unit.to_owned(), to_port.to_owned()))?;
            Some(Connection {
                start_element: from_unit.to_owned(),
                start_connector: from_port.to_owned(),
                end_element: to_unit.to_owned(),
                end_connector: variable.clone(),
                factor: c.gain,
                offset: c.offset,
            })
        })
        .collect();
    let structure = SystemStructure {
        name: scene_stem(scene),
        components,
        connections,
        start_time: Some(scene.start.as_secs()),
        stop_time: Some(scene.end().as_secs()),
        step: Some(scene.step.as_secs()),
        generation_tool: format!("slender {}", env!("CARGO_PKG_VERSION")),
    };
    archive::package(&structure, &fmus, out)?;
    Ok(structure)
}

/// Whether `path` names an SSP archive or description (`.ssp`, `.ssd`).
pub fn is_ssp(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("ssp") || e.eq_ignore_ascii_case("ssd"))
}

/// An SSP as a scene: unpacked into a temporary folder that the scene keeps.
pub(crate) fn load(path: &Path) -> Result<Scene, SceneError> {
    let error = |key: &str, message: String| SceneError {
        file: path.to_owned(),
        line: None,
        key: key.to_owned(),
        message,
    };
    let dir = tempfile::tempdir()
        .map_err(|e| error("", format!("no temporary folder to unpack into ({e})")))?;
    let (structure, root) =
        archive::open(path, dir.path()).map_err(|e| error("", e.to_string()))?;
    let text = scene_text(&structure, &root).map_err(|(key, message)| error(&key, message))?;
    let mut scene = Scene::parse(path, text)?;
    scene.resources = Some(dir);
    Ok(scene)
}

/// The scene's TOML for a system structure whose FMUs lie under `root`; an
/// error names the SSD element or attribute.
fn scene_text(s: &SystemStructure, root: &Path) -> Result<String, (String, String)> {
    let start = s.start_time.unwrap_or(0.0);
    let stop = s.stop_time.ok_or((
        "DefaultExperiment".to_owned(),
        "no stopTime: the SSP must say how long to run".to_owned(),
    ))?;
    let mut units = Vec::new();
    let mut steps = Vec::new();
    for c in &s.components {
        let (unit, step) = unit_of(c, root)?;
        units.push(unit);
        steps.extend(step);
    }
    let step = s.step.or_else(|| steps.into_iter().reduce(f64::min)).ok_or((
        "FixedStepAlgorithm".to_owned(),
        "no step: neither the SSP's OSP annotation (baseStepSize) nor any FMU's DefaultExperiment stepSize gives one".to_owned(),
    ))?;
    let connections = s.connections.iter().map(|c| {
        let mut t = Table::new();
        t.insert(
            "from".into(),
            Value::String(format!("{}.{}", c.start_element, c.start_connector)),
        );
        t.insert(
            "to".into(),
            Value::String(format!("{}.{}", c.end_element, c.end_connector)),
        );
        t.insert("gain".into(), Value::Float(c.factor));
        t.insert("offset".into(), Value::Float(c.offset));
        Value::Table(t)
    });
    let mut scene = Table::new();
    let title = format!("{} (SSP, {} components)", s.name, s.components.len());
    scene.insert("title".into(), Value::String(title));
    let mut simulation = Table::new();
    simulation.insert("start".into(), Value::Float(start));
    simulation.insert("duration".into(), Value::Float(stop - start));
    simulation.insert("step".into(), Value::Float(step));
    scene.insert("simulation".into(), Value::Table(simulation));
    let mut master = Table::new();
    master.insert("scheme".into(), Value::String("jacobi".into()));
    scene.insert("master".into(), Value::Table(master));
    scene.insert("units".into(), Value::Array(units));
    scene.insert("connections".into(), Value::Array(connections.collect()));
    toml::to_string(&scene).map_err(|e| (String::new(), e.to_string()))
}

/// A component as a unit of kind `fmu`, and its FMU's default step (s).
fn unit_of(c: &Component, root: &Path) -> Result<(Value, Option<f64>), (String, String)> {
    let file = source_path(root, &c.source).ok_or((
        c.name.clone(),
        format!(
            "source \"{}\": expected a path inside the archive",
            c.source
        ),
    ))?;
    // The FMU's own start values of its inputs start them here too (what an
    // FMI master does before any connection has a value).
    let description = archive::fmu_description(&file);
    let step = description
        .as_ref()
        .and_then(|d| d.default_experiment.as_ref()?.step_size);
    let mut inputs = Table::new();
    for v in description.iter().flat_map(|d| &d.variables) {
        if let (VariableCausality::Input, FmiValue::Real(Some(start)), true) =
            (v.causality, &v.value, v.dimensions.is_empty())
        {
            inputs.insert(v.name.clone(), Value::Float(*start));
        }
    }
    let mut parameters = Table::new();
    parameters.insert("file".into(), Value::String(file.display().to_string()));
    if !c.parameters.is_empty() {
        let start: Table = c.parameters.clone().into_iter().collect();
        parameters.insert("start".into(), Value::Table(start));
    }
    let mut unit = Table::new();
    unit.insert("name".into(), Value::String(c.name.clone()));
    unit.insert("kind".into(), Value::String("fmu".into()));
    // An SSP master passes values, not input derivatives: inputs hold over a
    // step, as in libcosim.
    unit.insert("hold".into(), Value::String("zero_order".into()));
    unit.insert("parameters".into(), Value::Table(parameters));
    if !inputs.is_empty() {
        unit.insert("inputs".into(), Value::Table(inputs));
    }
    Ok((Value::Table(unit), step))
}

/// A component's FMU: `source` relative to the archive's root, inside it.
fn source_path(root: &Path, source: &str) -> Option<PathBuf> {
    let relative = Path::new(source.strip_prefix("./").unwrap_or(source));
    let inside = relative
        .components()
        .all(|c| matches!(c, std::path::Component::Normal(_)));
    inside.then(|| root.join(relative))
}
