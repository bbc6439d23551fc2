//! `slender check` of a scene's `[uncertainty]` (issue 27: a NaN bound passed
//! `check`, and duplicate names or keys gave garbage indices in `slender uq`):
//! what `uq` needs, checked before anything runs.

use crate::spec::{SceneSpec, UncertaintySpec};

/// The first problem of `spec`'s `[uncertainty]` as (key, message), if any.
pub(crate) fn problem(scene: &SceneSpec) -> Option<(String, String)> {
    let spec: &UncertaintySpec = scene.uncertainty.as_ref()?;
    let key = |k: &str| format!("uncertainty.{k}");
    if spec.samples < 4 {
        return Some((
            key("samples"),
            format!("{}: expected at least 4 points", spec.samples),
        ));
    }
    if spec.inputs.is_empty() || spec.outputs.is_empty() {
        return Some((
            key("inputs"),
            "expected at least one input and one output".into(),
        ));
    }
    if !(spec.unstable_growth.is_finite() && spec.unstable_growth > 1.0) {
        return Some((
            key("unstable_growth"),
            format!(
                "{}: expected a finite number above 1 (an error that many times its reference's peak marks an unstable loop)",
                spec.unstable_growth
            ),
        ));
    }
    if !spec.unstable_fidelity.is_finite() {
        return Some((
            key("unstable_fidelity"),
            format!("{}: expected a finite phi", spec.unstable_fidelity),
        ));
    }
    for (i, name) in spec.outputs.iter().enumerate() {
        if !scene.output.indicators.iter().any(|ind| &ind.name == name) {
            return Some((
                key(&format!("outputs[{i}]")),
                format!("`{name}` is not an indicator of the scene ([[output.indicators]])"),
            ));
        }
        if spec.outputs[..i].contains(name) {
            return Some((
                key(&format!("outputs[{i}]")),
                format!("`{name}` is listed twice"),
            ));
        }
    }
    for (i, input) in spec.inputs.iter().enumerate() {
        let at = |k: &str| key(&format!("inputs[{i}].{k}"));
        if let Err(e) = input.distribution.validate() {
            return Some((at("distribution"), format!("`{}`: {e}", input.name)));
        }
        let earlier = &spec.inputs[..i];
        if earlier.iter().any(|j| j.name == input.name) {
            return Some((
                at("name"),
                format!("`{}` is used by an earlier input", input.name),
            ));
        }
        if earlier.iter().any(|j| j.key == input.key) {
            return Some((
                at("key"),
                format!(
                    "`{}` is varied by an earlier input; each key once",
                    input.key
                ),
            ));
        }
    }
    None
}
