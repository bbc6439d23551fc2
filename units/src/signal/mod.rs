//! Signal units: sources of prescribed loads and motions, the artefacts a control system
//! puts on coupled signals, and the compensation of an actuator's delay.

pub mod artefact;
pub mod characteristic_load;
pub mod compensation;
pub mod prescribed;
pub mod series;
pub mod sine;
pub mod source;

use crate::contract::{Port, PortKind, UnitError};

/// The default channels of a signal unit: a planar vector's x and z.
pub(crate) fn two_channels() -> Vec<String> {
    vec!["x".into(), "z".into()]
}

/// A channel-by-channel signal unit's ports: inputs `in_<channel>` and outputs
/// `out_<channel>` of `quantity`. An output is what the last step made of its
/// input (sampled, delayed, lagged, noisy): it does not follow the input at a
/// communication point, so no output declares a direct dependency.
pub(crate) fn channel_ports(
    channels: &[String],
    quantity: PortKind,
) -> Result<(Vec<Port>, Vec<Port>), UnitError> {
    if channels.is_empty() {
        return Err(UnitError::parameter(
            "channels",
            "[]",
            "expected at least one channel",
        ));
    }
    let inputs = channels
        .iter()
        .map(|c| Port::input(&format!("in_{c}"), quantity))
        .collect();
    let outputs = channels
        .iter()
        .map(|c| Port::output(&format!("out_{c}"), quantity))
        .collect();
    Ok((inputs, outputs))
}
