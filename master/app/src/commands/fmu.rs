//! `slender fmu export|wrap|info`.

use super::{CliError, SceneArg, load};
use crate::cli::FmuAction;
use slender_fmi::export::{ExportConfig, default_binary};
use slender_fmi::import::{FmuParams, FmuUnit};
use slender_fmi::model_description::VariableCausality;
use slender_scene::export::{FmiVersion, SceneExport, package_version, wrap_scene};
use slender_scene::ssp::write_ssp;
use slender_units::Unit;
use std::path::{Path, PathBuf};

/// Runs one FMU action (`set`: the scene keys of `--set`).
pub(super) fn fmu(action: FmuAction, set: &[String]) -> Result<(), CliError> {
    match action {
        FmuAction::Export {
            scene,
            unit,
            fmi,
            output,
            binary,
        } => export(
            &SceneArg::new(scene, set),
            &unit,
            fmi_version(fmi),
            output,
            binary,
        ),
        FmuAction::Wrap {
            scene,
            out,
            fmi,
            binary,
        } => {
            let version = fmi_version(fmi);
            if version == FmiVersion::Three && slender_scene::ssp::is_ssp(&out) {
                return Err(CliError::input(format!(
                    "--out {}: an SSP 1.0 archive holds FMI 2.0 FMUs; wrap with --fmi 2, or into a folder with --fmi 3",
                    out.display()
                )));
            }
            let scene = load(&SceneArg::new(scene, set))?;
            let binary = library(binary)?;
            let failed = |e: slender_scene::export::ExportError| CliError::input(e.to_string());
            if slender_scene::ssp::is_ssp(&out) {
                let system = write_ssp(&scene, &binary, &out).map_err(failed)?;
                println!(
                    "wrote {} (SSP 1.0: {} FMUs, {} connections; run it with `slender run {}`)",
                    out.display(),
                    system.components.len(),
                    system.connections.len(),
                    out.display()
                );
            } else {
                let path = wrap_scene(&scene, &binary, &out, version).map_err(failed)?;
                println!("wrote {}", path.display());
            }
            Ok(())
        }
        FmuAction::Info { fmu, preload } => info(fmu, preload),
    }
}

/// The FMI version of `--fmi` (2 or 3, checked by the argument parser).
fn fmi_version(fmi: u8) -> FmiVersion {
    if fmi == 3 {
        FmiVersion::Three
    } else {
        FmiVersion::Two
    }
}

/// The FMU library: the one given (checked to be a shared library with the FMI
/// entry points), else the one next to this executable.
fn library(binary: Option<PathBuf>) -> Result<PathBuf, CliError> {
    let binary = binary.or_else(default_binary).ok_or_else(|| {
        CliError::input(
            "libslender_fmu.so not found next to this executable; build it with `cargo build --release -p slender-fmu` or pass --binary",
        )
    })?;
    slender_fmi::export::check_binary(&binary).map_err(|e| CliError::input(e.to_string()))?;
    Ok(binary)
}

fn export(
    scene: &SceneArg,
    unit: &str,
    version: FmiVersion,
    output: Option<PathBuf>,
    binary: Option<PathBuf>,
) -> Result<(), CliError> {
    let scene = load(scene)?;
    let binary = library(binary)?;
    let output = output.unwrap_or_else(|| PathBuf::from(format!("{unit}.fmu")));
    let layout = ExportConfig::from_scene(&scene, unit)
        .and_then(|config| package_version(&config, &binary, &output, version))
        .map_err(|e| CliError::input(e.to_string()))?;
    let model = &layout.model;
    let count = |c| {
        let scalars = model.variables.iter().filter(|v| v.dimensions.is_empty());
        scalars.filter(|v| v.causality == c).count()
    };
    // FMI 3.0 carries the unit's fields as array outputs; FMI 2.0 has none.
    let arrays = match version {
        FmiVersion::Three if !layout.fields.is_empty() => {
            let sizes: Vec<&str> = layout.sizes.iter().map(|s| s.name.as_str()).collect();
            format!(
                ", {} array outputs sized by {}",
                layout.fields.len(),
                sizes.join(" and ")
            )
        }
        _ => String::new(),
    };
    println!(
        "wrote {} ({} inputs, {} outputs{arrays}, {} parameters, guid {})",
        output.display(),
        count(VariableCausality::Input),
        count(VariableCausality::Output),
        count(VariableCausality::Parameter),
        model.guid
    );
    Ok(())
}

/// Loads an FMU as slender would, with the FMU's own logging on so that its reason
/// for failing appears, and prints its ports.
fn info(fmu: PathBuf, preload: Vec<PathBuf>) -> Result<(), CliError> {
    let params = FmuParams {
        file: fmu,
        start: Default::default(),
        preload,
        logging: true,
    };
    let unit =
        FmuUnit::load(&params, Path::new(".")).map_err(|e| CliError::input(e.to_string()))?;
    let model = unit.model_description();
    let d = unit.description();
    println!(
        "{} (FMI {}, {}), generated by {}",
        model.model_name, model.fmi_version, model.guid, model.generation_tool
    );
    println!(
        "rollback: {}, variable step: {}",
        d.capabilities.rollback, d.capabilities.variable_step
    );
    for p in &d.inputs {
        println!(
            "  input  {:<24} {:<12} {:<5} hold {:?}",
            p.name,
            p.kind.name(),
            p.unit,
            p.hold
        );
    }
    for p in &d.outputs {
        let deps: Vec<&str> = p
            .depends_on
            .iter()
            .map(|i| d.inputs[*i].name.as_str())
            .collect();
        println!(
            "  output {:<24} {:<12} {:<5} depends on [{}]",
            p.name,
            p.kind.name(),
            p.unit,
            deps.join(", ")
        );
    }
    Ok(())
}
