//! Example scenes edited in memory and run: what the tests of one fidelity
//! against the monolithic twin share.

use crate::{Series, root, run};
use slender_scene::Scene;

/// An example with its text edited (`(from, to)` replacements, each of
/// which must match), run in memory: its series, or the scene's or the
/// run's error.
pub fn run_edited(path: &str, edits: &[(&str, &str)]) -> Result<Series, String> {
    let file = root().join(path);
    let mut text = std::fs::read_to_string(&file).unwrap_or_else(|e| panic!("{path}: {e}"));
    for (from, to) in edits {
        assert!(text.contains(from), "{path}: {from}");
        text = text.replacen(from, to, 1);
    }
    let scene = Scene::parse(&file, text).map_err(|e| e.to_string())?;
    let s = run(&scene);
    match s.error.clone() {
        Some(e) => Err(e),
        None => Ok(s),
    }
}

/// The worst indicator epsilon of a run against its twin, each printed
/// after `what`.
pub fn worst_epsilon(what: &str, s: &Series) -> f64 {
    s.indicators.iter().fold(0.0f64, |worst, i| {
        eprintln!("{what}: {} epsilon {:.2e}", i.name, i.relative_error);
        worst.max(i.relative_error)
    })
}
