//! Static contact-point approximation (seed 004 sec. 6.6): from the deflection y0
//! and angle y0' at the upper end of a pipe section lying down on a flat surface,
//! the touchdown point of the static solution is x_C = -3 y0 / y0' (eq. 4.41), valid
//! for y0 > 0 and y0' < 0. A cheap stand-in for the FE section where only the
//! touchdown point is needed.

use crate::contract::{
    Capabilities, HoldSupport, Inputs, Port, PortKind, StateSlot, StepReport, Time, Unit,
    UnitDescription, UnitError,
};
use serde::Deserialize;

/// Parameters (scene kind `touchdown_estimate`): none besides the surface height.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TouchdownParams {
    /// Height of the flat surface (m), default 0.
    #[serde(default)]
    pub surface_height: f64,
}

/// Inputs `deflection` (m), `rotation` (rad); outputs `touchdown_x` (m, 0 when not
/// valid) and `valid` (1 or 0). Stateless: the outputs follow the inputs.
pub struct TouchdownEstimate {
    params: TouchdownParams,
    description: UnitDescription,
}

impl TouchdownEstimate {
    /// Builds the unit.
    pub fn new(params: TouchdownParams) -> Result<TouchdownEstimate, UnitError> {
        crate::contract::require_finite("surface_height", params.surface_height)?;
        Ok(TouchdownEstimate {
            params,
            description: UnitDescription {
                kind: "touchdown_estimate".into(),
                inputs: vec![
                    Port::input("deflection", PortKind::Displacement),
                    Port::input("rotation", PortKind::Rotation),
                ],
                outputs: vec![
                    Port::output("touchdown_x", PortKind::Displacement).with_feedthrough(&[0, 1]),
                    Port::output("valid", PortKind::Generic).with_feedthrough(&[0, 1]),
                ],
                capabilities: Capabilities {
                    hold: HoldSupport::Fixed,
                    ..Capabilities::default()
                },
            },
        })
    }

    /// (x_C, valid) for end deflection y (m above the surface) and angle y'.
    pub fn estimate(height: f64, slope: f64) -> (f64, bool) {
        if height > 0.0 && slope < 0.0 {
            (-3.0 * height / slope, true)
        } else {
            (0.0, false)
        }
    }
}

impl Unit for TouchdownEstimate {
    fn description(&self) -> &UnitDescription {
        &self.description
    }
    fn initialize(&mut self, _t0: Time, _inputs: Inputs<'_>) -> Result<(), UnitError> {
        Ok(())
    }
    fn do_step(
        &mut self,
        _t: Time,
        _h: Time,
        _inputs: Inputs<'_>,
    ) -> Result<StepReport, UnitError> {
        Ok(StepReport::default())
    }
    fn outputs(&self, inputs: Inputs<'_>, out: &mut [f64]) {
        let inputs = inputs.end();
        let (x, valid) =
            TouchdownEstimate::estimate(inputs[0] - self.params.surface_height, inputs[1]);
        out[0] = x;
        out[1] = if valid { 1.0 } else { 0.0 };
    }
    fn save_state(&self, slot: &mut StateSlot) -> Result<(), UnitError> {
        slot.store(&());
        Ok(())
    }
    fn restore_state(&mut self, slot: &StateSlot) -> Result<(), UnitError> {
        slot.load::<()>()?;
        Ok(())
    }
}
