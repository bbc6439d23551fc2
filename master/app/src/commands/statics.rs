//! `slender statics`: a moored body's statics from its scene's `[mooring]`:
//! the equilibrium, each line's fairlead tension, the mooring's 6x6
//! stiffness there, the undamped natural periods about it, and the
//! offset-restoring curves (surge, sway, yaw: the mooring's restoring load
//! and each line's tension against the offset), as statics.json,
//! offsets.csv and statics.svg.

use super::{CliError, SceneArg, load, report_written, results_folder};
use slender_app::figures::curves::{CurvePanel, curves};
use slender_app::whole;
use slender_scene::mooring::{self, Mooring};
use slender_units::body::mooring::{MooredLine, MooringStatics, mooring_state, natural_modes};
use slender_units::body::params::DOFS;
use std::path::PathBuf;

/// The offset curves: surge and sway over `range` (m), yaw over `yaw` (deg),
/// each in `points` points.
pub(super) struct Sweep {
    pub range: f64,
    pub yaw: f64,
    pub points: usize,
}

/// The statics of the scene's moored body, printed and written.
pub(super) fn statics(arg: &SceneArg, out: Option<PathBuf>, sweep: Sweep) -> Result<(), CliError> {
    if !(sweep.range > 0.0 && sweep.yaw > 0.0 && (3..=1001).contains(&sweep.points)) {
        return Err(CliError::input(
            "--range and --yaw: > 0; --points: from 3 to 1001",
        ));
    }
    let scene = load(arg)?;
    let system = mooring::of_scene(&scene)
        .map_err(CliError::input)?
        .ok_or_else(|| {
            CliError::input(format!(
                "{}: no `[mooring]` (a body and its lines) to solve the statics of",
                arg.path.display()
            ))
        })?;
    let lines = system.catenaries().map_err(CliError::input)?;
    let eq = system.equilibrium_on(&lines).map_err(CliError::failure)?;
    let fail = |e: slender_units::UnitError| CliError::failure(e.to_string());
    let modes = natural_modes(&system.body, &lines, &eq.offset).map_err(fail)?;
    print_statics(&system, &eq, &modes, &arg.path);
    let dir = out.unwrap_or_else(|| scene.default_output_dir());
    let _lock = results_folder(&dir)?;
    let rows = offset_rows(&system, &lines, &eq, &sweep).map_err(fail)?;
    let json = dir.join("statics.json");
    whole::write(&json, statics_json(&system, &eq, &modes))
        .map_err(|e| CliError::failure(format!("{}: {e}", json.display())))?;
    let csv = dir.join("offsets.csv");
    whole::write(&csv, offsets_csv(&system, &rows))
        .map_err(|e| CliError::failure(format!("{}: {e}", csv.display())))?;
    let svg = dir.join("statics.svg");
    let title = format!("Statics of `{}` on its lines", system.name);
    whole::through(&svg, |f| curves(f, &title, &panels(&system, &rows)))
        .map_err(CliError::failure)?;
    report_written(&[json, csv, svg]);
    Ok(())
}

fn print_statics(
    system: &Mooring,
    eq: &MooringStatics,
    modes: &[slender_units::body::mooring::RigidMode],
    path: &std::path::Path,
) {
    let o = eq.offset;
    println!(
        "statics of `{}` in {} (each line as its elastic catenary)",
        system.name,
        path.display()
    );
    println!(
        "equilibrium  surge {:.4} m, sway {:.4} m, heave {:.4} m, roll {:.4} deg, pitch {:.4} deg, yaw {:.4} deg ({} Newton iterations)",
        o[0],
        o[1],
        o[2],
        o[3].to_degrees(),
        o[4].to_degrees(),
        o[5].to_degrees(),
        eq.iterations
    );
    println!(
        "{:>10} {:>9} {:>14} {:>14} {:>14}",
        "line", "fairlead", "tension (N)", "horizontal (N)", "vertical (N)"
    );
    for ((name, fairlead), f) in system.line_names().iter().zip(&eq.fairlead_forces) {
        let t = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
        println!(
            "{name:>10} {fairlead:>9} {t:>14.1} {:>14.1} {:>14.1}",
            f[0].hypot(f[1]),
            -f[2]
        );
    }
    println!(
        "mooring stiffness at the equilibrium (rows: load surge..yaw; columns: offset surge..yaw; N/m, N/rad, N m/m, N m/rad):"
    );
    for row in &eq.stiffness {
        let cells: Vec<String> = row.iter().map(|k| format!("{k:>13.5e}")).collect();
        println!("  {}", cells.join(" "));
    }
    println!("undamped natural periods about the equilibrium:");
    for (i, m) in modes.iter().enumerate() {
        println!(
            "  mode {}  {:>10.3} s  ({})",
            i + 1,
            m.period,
            DOFS[m.dominant]
        );
    }
}

/// One point of an offset curve: the degree of freedom moved, the offset
/// (m or deg), the mooring's restoring load along it and each line's tension.
struct OffsetRow {
    dof: usize,
    offset: f64,
    restoring: f64,
    tensions: Vec<f64>,
}

/// Surge, sway and yaw moved one at a time from the equilibrium.
fn offset_rows(
    system: &Mooring,
    lines: &[MooredLine],
    eq: &MooringStatics,
    sweep: &Sweep,
) -> Result<Vec<OffsetRow>, slender_units::UnitError> {
    let mut rows = Vec::new();
    for (dof, span) in [(0, sweep.range), (1, sweep.range), (5, sweep.yaw)] {
        for i in 0..sweep.points {
            let s = -span + 2.0 * span * i as f64 / (sweep.points - 1) as f64;
            let mut at = eq.offset;
            at[dof] += if dof == 5 { s.to_radians() } else { s };
            let (load, tensions) = mooring_state(&system.body, lines, &at)?;
            rows.push(OffsetRow {
                dof,
                offset: s,
                restoring: -load[dof],
                tensions,
            });
        }
    }
    Ok(rows)
}

fn offsets_csv(system: &Mooring, rows: &[OffsetRow]) -> String {
    let mut text = String::from("dof,offset,restoring");
    for (name, _) in system.line_names() {
        text += &format!(",{name}_tension_N");
    }
    text += "\n";
    for r in rows {
        text += &format!("{},{},{}", DOFS[r.dof], r.offset, r.restoring);
        for t in &r.tensions {
            text += &format!(",{t}");
        }
        text += "\n";
    }
    text
}

fn panels(system: &Mooring, rows: &[OffsetRow]) -> Vec<CurvePanel> {
    let names = system.line_names();
    let mut panels = Vec::new();
    for (dof, unit, load_unit) in [(0, "m", "N"), (1, "m", "N"), (5, "deg", "N m")] {
        let of = || rows.iter().filter(move |r| r.dof == dof);
        panels.push(CurvePanel {
            x_label: format!("{} offset ({unit})", DOFS[dof]),
            y_label: format!("mooring restoring ({load_unit})"),
            series: vec![(
                "restoring".to_owned(),
                of().map(|r| (r.offset, r.restoring)).collect(),
            )],
        });
        let tensions = names
            .iter()
            .enumerate()
            .map(|(k, (name, _))| {
                (
                    name.clone(),
                    of().map(|r| (r.offset, r.tensions[k])).collect(),
                )
            })
            .collect();
        panels.push(CurvePanel {
            x_label: format!("{} offset ({unit})", DOFS[dof]),
            y_label: "fairlead tension (N)".into(),
            series: tensions,
        });
    }
    panels
}

fn statics_json(
    system: &Mooring,
    eq: &MooringStatics,
    modes: &[slender_units::body::mooring::RigidMode],
) -> String {
    let lines: Vec<serde_json::Value> = system
        .line_names()
        .iter()
        .zip(&eq.fairlead_forces)
        .map(|((name, fairlead), f)| {
            serde_json::json!({ "line": name, "fairlead": fairlead, "force_N": f })
        })
        .collect();
    let periods: Vec<serde_json::Value> = modes
        .iter()
        .map(|m| serde_json::json!({ "period_s": m.period, "dof": DOFS[m.dominant] }))
        .collect();
    let value = serde_json::json!({
        "body": system.name,
        "offset": eq.offset,
        "newton_iterations": eq.iterations,
        "lines": lines,
        "mooring_stiffness": eq.stiffness,
        "natural_periods": periods,
    });
    serde_json::to_string_pretty(&value).unwrap_or_default() + "\n"
}
