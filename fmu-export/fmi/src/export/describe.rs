//! A port's description in an FMU's model description, read from the unit's
//! own declaration of it (its name, quantity and unit of measure) rather than
//! its kind alone: "force at the end, x component (N), output" where every
//! force output was "force output" (issue 49 #15).

use slender_contract::{Hold, Port};

/// The words of a port's name, its axis suffix as a component: `end_force_x`
/// -> "end force, x component"; `top_tension` -> "top tension".
fn words(name: &str) -> String {
    let (stem, axis) = match name.rsplit_once('_') {
        Some((stem, axis)) if matches!(axis, "x" | "y" | "z") => (stem, Some(axis)),
        _ => (name, None),
    };
    let stem = stem.replace('_', " ");
    match axis {
        Some(axis) => format!("{stem}, {axis} component"),
        None => stem,
    }
}

/// The unit of measure in brackets, or nothing for a dimensionless port.
fn measured(port: &Port) -> String {
    match port.unit.as_str() {
        "" => String::new(),
        unit => format!(" ({unit})"),
    }
}

/// An input's description: its name's words, its quantity and unit, and how
/// the unit holds it inside a step.
pub(super) fn input(port: &Port) -> String {
    let hold = match port.hold {
        Hold::Ramp => "ramp",
        Hold::ZeroOrder => "zero-order",
    };
    format!(
        "{}{}: {} input ({hold} hold when input derivatives are set)",
        words(&port.name),
        measured(port),
        port.kind
    )
}

/// An output's description: its name's words, its quantity and unit.
pub(super) fn output(port: &Port) -> String {
    format!(
        "{}{}: {} output",
        words(&port.name),
        measured(port),
        port.kind
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use slender_contract::PortKind;

    #[test]
    fn a_port_is_described_by_its_name_quantity_and_unit() {
        let force = Port::output("end_force_x", PortKind::Force);
        assert_eq!(output(&force), "end force, x component (N): force output");
        let velocity = Port::input("start_velocity_z", PortKind::Velocity);
        assert_eq!(
            input(&velocity),
            "start velocity, z component (m/s): velocity input (ramp hold when input derivatives are set)"
        );
        let tension = Port::output("top_tension", PortKind::Force);
        assert_eq!(output(&tension), "top tension (N): force output");
    }
}
