//! Issue 28's sea states in a scene: a hanging steel pipe's top heaves as a
//! vessel in a JONSWAP sea (Hs 4 m, Tp 10 s) through a heave RAO, faded in;
//! the top follows the same sea as a `signal` unit given the same sea state,
//! and the run stays within the watch on plausibility.

use slender_app::run::{RunOptions, run_scene};
use slender_tests::hanging_pipe;

const SEA: &str = "{ spectrum = { kind = \"jonswap\", significant_height = 4.0, peak_period = 10.0, components = 300, seed = 3 }, rao = { table = [[0.2, 1.0, 0.0], [0.5, 1.1, -0.2], [0.8, 0.6, -0.9], [1.2, 0.1, -2.0], [2.0, 0.0, -2.5]] } }";

#[test]
fn a_structure_top_follows_a_sea_state_through_its_rao() {
    let heave = format!("{{ fade_in = 20.0, sea = {SEA} }}");
    let output = format!(
        "signals = [\"pipe.end_position_z\", \"pipe.max_tension\", \"vessel.value\"]\n\n\
         [[units]]\nname = \"vessel\"\nkind = \"signal\"\n\
         parameters = {{ quantity = \"displacement\", fade_in = {{ shape = \"smoothstep\", time = 20.0 }}, sea = {SEA} }}"
    );
    let scene = hanging_pipe((120.0, ""), (&heave, 1.0), &output);
    let options = RunOptions {
        output_dir: None,
        progress: false,
        realtime: false,
    };
    let result = run_scene(&scene, &options).unwrap();
    assert!(result.summary.error.is_none(), "{:?}", result.summary.error);
    assert!(
        result.summary.warnings.is_empty(),
        "{:?}",
        result.summary.warnings
    );
    let top = result.recorder.column("pipe.end_position_z").unwrap();
    let vessel = result.recorder.column("vessel.value").unwrap();
    let worst = top
        .iter()
        .zip(vessel)
        .map(|(z, v)| (z - top[0] - v).abs())
        .fold(0.0, f64::max);
    assert!(
        worst < 1e-9,
        "the top departs from the signal's sea by {worst} m"
    );
    // An irregular heave of the order of the sea: a standard deviation of
    // the faded-in part between a tenth of Hs / 4 and twice it.
    let late: Vec<f64> = vessel[vessel.len() / 3..].to_vec();
    let mean = late.iter().sum::<f64>() / late.len() as f64;
    let sd = (late.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / late.len() as f64).sqrt();
    assert!(sd > 0.1 && sd < 2.0, "heave standard deviation {sd} m");
    let tension = result.recorder.column("pipe.max_tension").unwrap();
    assert!(
        tension
            .iter()
            .all(|t| t.is_finite() && *t < 5.0 * tension[0])
    );
}
