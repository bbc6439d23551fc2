//! `slender decay`: runs a scene with a body (a decay test: the body let go
//! from an `initial_offset`) and reads each of its six motions' natural
//! period and damping ratio from the record (`slender_app::decay`), beside
//! the undamped periods of the moored body's statics where the scene has a
//! `[mooring]`; prints them and writes decay.json with the run's files.

use super::{CliError, SceneArg, load, report_written, results_folder};
use slender_app::decay::{Decay, decay};
use slender_app::run::{RunOptions, run_scene};
use slender_scene::mooring;
use slender_units::body::mooring::natural_modes;
use slender_units::body::params::DOFS;
use std::path::PathBuf;

/// The body's six motion outputs, in DOF order.
const MOTIONS: [&str; 6] = ["x", "y", "z", "roll", "pitch", "yaw"];

/// Runs the decay test of the scene `arg` and reads its motions.
pub(super) fn decay_test(arg: &SceneArg, out: Option<PathBuf>) -> Result<(), CliError> {
    let mut scene = load(arg)?;
    let bodies: Vec<String> = (scene.spec.units.iter())
        .filter(|u| u.kind.get_ref() == "body")
        .map(|u| u.name.get_ref().clone())
        .collect();
    let body = match bodies.as_slice() {
        [one] => one.clone(),
        [] => {
            return Err(CliError::input(format!(
                "{}: no unit of kind `body` to read a decay of",
                arg.path.display()
            )));
        }
        _ => {
            return Err(CliError::input(format!(
                "{}: several bodies ({}); a decay test reads one",
                arg.path.display(),
                bodies.join(", ")
            )));
        }
    };
    let settles = settling_values(&scene, &body)?;
    for m in MOTIONS {
        let name = format!("{body}.{m}");
        if !scene.spec.output.signals.contains(&name) {
            scene.spec.output.signals.push(name);
        }
    }
    let dir = out.unwrap_or_else(|| scene.default_output_dir());
    let _lock = results_folder(&dir)?;
    let options = RunOptions {
        output_dir: Some(dir.clone()),
        progress: true,
        realtime: false,
    };
    let result = run_scene(&scene, &options).map_err(|e| CliError::failure(e.to_string()))?;
    if let Some(e) = &result.summary.error {
        return Err(CliError::failure(format!("the decay run stopped: {e}")));
    }
    let recorder = &result.recorder;
    let mut rows = Vec::new();
    for (dof, m) in MOTIONS.iter().enumerate() {
        let values = recorder
            .column(&format!("{body}.{m}"))
            .ok_or_else(|| CliError::failure(format!("`{body}.{m}` was not recorded")))?;
        let settle = settles
            .as_ref()
            .map_or(*values.last().unwrap_or(&0.0), |(s, _)| s[dof]);
        // A motion the test does not excite moves at round-off: left out.
        let read = decay(&recorder.time, values, settle).filter(|d| d.amplitude > 1e-9);
        rows.push((dof, read));
    }
    let linear = settles.map(|(_, periods)| periods);
    print_rows(&body, &rows, linear.as_ref());
    let json = dir.join("decay.json");
    let value: Vec<serde_json::Value> = rows
        .iter()
        .map(|(dof, d)| {
            serde_json::json!({
                "dof": DOFS[*dof],
                "decay": d,
                "linear_period_s": linear.as_ref().map(|p| p[*dof]),
            })
        })
        .collect();
    let text = serde_json::to_string_pretty(&value).unwrap_or_default() + "\n";
    slender_app::whole::write(&json, text)
        .map_err(|e| CliError::failure(format!("{}: {e}", json.display())))?;
    report_written(&[json]);
    Ok(())
}

/// Per DOF where the motion settles and the linear period of its mode.
type Settling = ([f64; 6], [f64; 6]);

/// Where each motion settles (the reference point at the moored
/// equilibrium, the angles there) and the undamped period of the mode each
/// DOF leads, from the scene's `[mooring]` statics; None without one.
fn settling_values(scene: &slender_scene::Scene, body: &str) -> Result<Option<Settling>, CliError> {
    let Some(system) = mooring::of_scene(scene).map_err(CliError::input)? else {
        return Ok(None);
    };
    if system.name != body || !system.statics() {
        return Ok(None);
    }
    let lines = system.catenaries().map_err(CliError::input)?;
    let eq = system.equilibrium_on(&lines).map_err(CliError::failure)?;
    let modes = natural_modes(&system.body, &lines, &eq.offset)
        .map_err(|e| CliError::failure(e.to_string()))?;
    let mut settle = eq.offset;
    for (s, r) in settle.iter_mut().zip(system.body.reference) {
        *s += r;
    }
    let mut periods = [f64::NAN; 6];
    for m in modes.iter().rev() {
        periods[m.dominant] = m.period;
    }
    Ok(Some((settle, periods)))
}

fn print_rows(body: &str, rows: &[(usize, Option<Decay>)], linear: Option<&[f64; 6]>) {
    println!(
        "decay of `{body}`: period and damping ratio per motion (a motion with less than a cycle is left out)"
    );
    println!(
        "{:>6} {:>11} {:>9} {:>12} {:>7} {:>18}",
        "dof", "period (s)", "damping", "amplitude", "cycles", "linear period (s)"
    );
    for (dof, d) in rows {
        let Some(d) = d else { continue };
        let lin = linear.map_or("-".to_owned(), |p| format!("{:.3}", p[*dof]));
        println!(
            "{:>6} {:>11.3} {:>9.4} {:>12.4e} {:>7} {:>18}",
            DOFS[*dof], d.period, d.damping_ratio, d.amplitude, d.cycles, lin
        );
    }
}
