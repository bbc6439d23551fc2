//! The chord unit's ports: its own (`describe`), the inner model's it feeds
//! and reads (`inner_ports`), and which inputs each output follows
//! (`set_dependencies`).

use super::axial::Axial;
use super::{ChordModel, ChordParams, InnerPorts, MAX_INNER_OUTPUTS, MovingEnd};
use crate::contract::{Capabilities, Port, PortKind, UnitDescription, UnitError};

/// The inner model's ports by name (the beam's ends are `left` and `right`, the
/// span's `upper` at x = 0 and `lower`).
pub(super) fn inner_ports(
    params: &ChordParams,
    inner: &UnitDescription,
) -> Result<InnerPorts, UnitError> {
    let (start, end) = match params.model {
        ChordModel::Beam => ("left", "right"),
        ChordModel::Span => ("upper", "lower"),
    };
    let (moving, loaded) = match params.moving {
        MovingEnd::Start => (start, end),
        MovingEnd::End => (end, start),
    };
    let find = |ports: &[Port], name: String| {
        ports.iter().position(|p| p.name == name).ok_or_else(|| {
            UnitError::State(format!("the chord's inner model has no port `{name}`"))
        })
    };
    let inputs = [
        find(&inner.inputs, format!("{moving}_deflection"))?,
        find(&inner.inputs, format!("{moving}_rotation"))?,
        find(&inner.inputs, format!("{loaded}_moment"))?,
        find(&inner.inputs, format!("{loaded}_shear"))?,
    ];
    let outputs = [
        find(&inner.outputs, format!("{moving}_moment"))?,
        find(&inner.outputs, format!("{moving}_shear"))?,
        find(&inner.outputs, format!("{loaded}_deflection"))?,
        find(&inner.outputs, format!("{loaded}_rotation"))?,
    ];
    let output_count = inner.outputs.len();
    if output_count > MAX_INNER_OUTPUTS || inner.inputs.len() != 4 {
        return Err(UnitError::State(format!(
            "the chord's inner model has {} inputs and {output_count} outputs: expected 4 and at most {MAX_INNER_OUTPUTS}",
            inner.inputs.len()
        )));
    }
    Ok(InnerPorts {
        inputs,
        outputs,
        output_count,
    })
}

/// Ports: the moving end's position and rotation and the loaded end's force
/// and moment in; the force and moment the moving end exerts, the loaded
/// end's neighbour's displacement and the axial force out.
pub(super) fn describe(moving: MovingEnd) -> UnitDescription {
    let (m, l) = match moving {
        MovingEnd::Start => ("start", "end"),
        MovingEnd::End => ("end", "start"),
    };
    let inputs = vec![
        Port::input(&format!("{m}_position_x"), PortKind::Displacement),
        Port::input(&format!("{m}_position_z"), PortKind::Displacement),
        Port::input(&format!("{m}_rotation"), PortKind::Rotation),
        Port::input(&format!("{l}_force_x"), PortKind::Force),
        Port::input(&format!("{l}_force_z"), PortKind::Force),
        Port::input(&format!("{l}_moment"), PortKind::Moment),
    ];
    let outputs = vec![
        Port::output(&format!("{m}_force_x"), PortKind::Force),
        Port::output(&format!("{m}_force_z"), PortKind::Force),
        Port::output(&format!("{m}_moment"), PortKind::Moment),
        Port::output(&format!("{l}_displacement_x"), PortKind::Displacement),
        Port::output(&format!("{l}_displacement_z"), PortKind::Displacement),
        Port::output(&format!("{l}_rotation"), PortKind::Rotation),
        Port::output("axial_force", PortKind::Force),
    ];
    UnitDescription {
        kind: "chord".into(),
        inputs,
        outputs,
        capabilities: Capabilities::default(),
    }
}

/// The outer inputs each output follows at a communication point, through the
/// frame changes (`local`, `assemble`) and the inner model's own dependencies:
/// the forces carry the loaded end's axial force (and the moving end's slide
/// where a mass lags between them) and the inner shear, the displacements the
/// moving end's slide (and the stretch under the axial force), the rest what
/// the inner outputs follow.
pub(super) fn set_dependencies(
    description: &mut UnitDescription,
    inner: &UnitDescription,
    ports: &InnerPorts,
    axial: &Axial,
) {
    // The outer inputs behind each inner input the chord feeds (`local`):
    // deflection, rotation, moment, shear.
    let sources: [&[usize]; 4] = [&[0, 1], &[2], &[5], &[3, 4]];
    let through = |inner_output: usize| -> Vec<usize> {
        let mut outer: Vec<usize> = inner.outputs[inner_output]
            .depends_on
            .iter()
            .filter_map(|p| ports.inputs.iter().position(|q| q == p))
            .flat_map(|k| sources[k].iter().copied())
            .collect();
        outer.sort_unstable();
        outer.dedup();
        outer
    };
    let [moment, shear, deflection, rotation] = ports.outputs.map(through);
    let join = |a: &[usize], b: &[usize]| {
        let mut all = [a, b].concat();
        all.sort_unstable();
        all.dedup();
        all
    };
    let along: &[usize] = if axial.has_mass() {
        &[0, 1, 3, 4]
    } else {
        &[3, 4]
    };
    let slide: &[usize] = if axial.stretches() {
        &[0, 1, 3, 4]
    } else {
        &[0, 1]
    };
    let force = join(along, &shear);
    let moved = join(slide, &deflection);
    let dependencies = [
        force.clone(),
        force,
        moment,
        moved.clone(),
        moved,
        rotation,
        vec![3, 4],
    ];
    for (port, depends_on) in description.outputs.iter_mut().zip(dependencies) {
        port.depends_on = depends_on;
    }
}
