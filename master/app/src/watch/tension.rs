//! The watch on loads: a run can end "completed" with loads no structure of
//! its kind could carry (issue 27 reported a riser meshed too coarsely at
//! its touchdown, stepped without numerical damping, at 9.8 MN where the
//! converged tension stays below 1.1 MN; one that gains energy while its
//! loads still look possible is the energy watch's). After every step
//! the largest tension along each section (the `nonlinear` unit's
//! `max_tension`) is compared with the structure's scale: the largest over
//! all sections at the start, the static one where the sections start from
//! their statics (a laid section's own small tension is no scale for the
//! top's). One beyond `factor` (default 5) times that scale is a warning
//! with the unit, port, value and time (once per port). A `breaking_load`
//! (N) bounds the tension too, whichever is lower. Without load at the start
//! (a structure released from its stress-free shape) there is no scale and
//! only a breaking load is watched.

use slender_coupling::coupler::Master;
use slender_scene::spec::WatchSpec;

/// The outputs watched: a section's largest tension along it (N). Its bending
/// moment is not: in a line of little bending stiffness an impulsive start
/// sends it to ten times its small static value, physically (the polyester
/// line example), so no multiple of the static one marks a broken run.
const WATCHED: [&str; 1] = ["max_tension"];

/// One watched port: unit, port, and the bound on its magnitude (N or N m)
/// with what it is.
struct Watched {
    unit: usize,
    port: usize,
    bound: f64,
    what: &'static str,
    warned: bool,
}

/// The watched bound: `factor` times the start `scale`, or the breaking
/// load where that is lower (or the only bound: no scale at the start).
fn bound(spec: &WatchSpec, scale: f64) -> Option<(f64, &'static str)> {
    let relative = (scale > 0.0).then_some((
        spec.factor * scale,
        "output.watch.factor times the largest at the start",
    ));
    let breaking = spec
        .breaking_load
        .map(|b| (b, "output.watch.breaking_load"));
    match (relative, breaking) {
        (Some(r), Some(b)) => Some(if b.0 < r.0 { b } else { r }),
        (r, b) => r.or(b),
    }
}

/// The watch on the sections' tensions over a run.
pub(super) struct TensionWatch {
    watched: Vec<Watched>,
}

impl TensionWatch {
    /// The watched outputs (after `Master::initialize`), each bounded by
    /// `spec.factor` times the largest start value of its name over all
    /// units.
    pub(super) fn new(master: &Master, spec: &WatchSpec) -> TensionWatch {
        let mut found = Vec::new();
        let mut scale = [0.0f64; WATCHED.len()];
        for unit in 0..master.unit_names().count() {
            let ports = &master.description(unit).outputs;
            for (port, p) in ports.iter().enumerate() {
                if let Some(k) = WATCHED.iter().position(|w| *w == p.name) {
                    let start = master.outputs(unit)[port].abs();
                    if start.is_finite() {
                        scale[k] = scale[k].max(start);
                    }
                    found.push((unit, port, k));
                }
            }
        }
        let watched = found
            .into_iter()
            .filter_map(|(unit, port, k)| {
                let (bound, what) = bound(spec, scale[k])?;
                Some(Watched {
                    unit,
                    port,
                    bound,
                    what,
                    warned: false,
                })
            })
            .collect();
        TensionWatch { watched }
    }

    /// Checks the outputs after a step at simulated time `t` (s), adding a
    /// warning to `warnings` per port the first time it goes beyond its
    /// bound.
    pub(super) fn observe(&mut self, master: &Master, t: f64, warnings: &mut Vec<String>) {
        for w in self.watched.iter_mut().filter(|w| !w.warned) {
            let value = master.outputs(w.unit)[w.port];
            if value.abs() > w.bound {
                w.warned = true;
                let port = &master.description(w.unit).outputs[w.port];
                let name = master.unit_names().nth(w.unit).unwrap_or("?");
                warnings.push(format!(
                    "implausible load: `{name}.{}` = {value:.4e} {} at t = {t} s, beyond {:.4e} ({})",
                    port.name, port.unit, w.bound, w.what
                ));
            }
        }
    }
}
