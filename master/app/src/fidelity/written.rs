//! A section's fidelity as the scene writes it (a name or a table), read back
//! into the command line's form for the report's labels.

use toml::{Table, Value};

/// A section's fidelity as the scene writes it, in the command line's form.
pub(super) fn scene_choice(t: &Table) -> String {
    let kind = written_kind(t);
    let count = match kind {
        "reduced" => "modes",
        "span" => "order",
        _ => "elements",
    };
    let elements = t
        .get("fidelity")
        .and_then(|f| f.get(count))
        .or(t.get(count));
    let model = match elements.and_then(Value::as_integer) {
        Some(n) => format!("{kind}:{n}"),
        None => kind.to_owned(),
    };
    match t.get("substeps").and_then(Value::as_integer) {
        Some(n) => format!("{model}/{n}"),
        None => model,
    }
}

/// A section's fidelity as written: a name, or a table's `kind` (default
/// nonlinear).
pub(super) fn written_kind(t: &Table) -> &str {
    match t.get("fidelity") {
        Some(Value::String(w)) => w,
        Some(Value::Table(f)) => f.get("kind").and_then(Value::as_str).unwrap_or("nonlinear"),
        _ => "nonlinear",
    }
}
