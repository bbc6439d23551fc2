//! What a reduced section refuses, named by its key, at `slender check`.

use super::Sampling;
use crate::contact::Law;
use crate::contract::{UnitError, require_in_range};
use crate::nonlinear::NonlinearSection;
use crate::nonlinear::params::{Integrator, NonlinearParams};

/// Refuses what the reduced section cannot take, naming the key.
pub(in crate::nonlinear) fn validate(params: &NonlinearParams) -> Result<(), UnitError> {
    let refuse = |key: &str, value: &str, why: &str| Err(UnitError::parameter(key, value, why));
    let Some(modes) = params.reduced_modes else {
        return match params.reduced_sampling {
            Some(_) => refuse(
                "reduced_sampling",
                "given",
                "none without reduced_modes (it samples a reduced section's forces)",
            ),
            None => Ok(()),
        };
    };
    if modes == 0 {
        return refuse("reduced_modes", "0", "at least 1 mode");
    }
    if params.linear {
        return refuse(
            "linear",
            "true",
            "false with reduced_modes (a section is linearised or reduced, not both)",
        );
    }
    if !matches!(params.integrator, Integrator::Hht { .. }) {
        return refuse(
            "integrator",
            "not hht",
            "kind = \"hht\" with reduced_modes (Newton on the reduced coordinates)",
        );
    }
    if let Some(sampling) = &params.reduced_sampling {
        validate_sampling(sampling)?;
    }
    for (key, contact) in [("contact", &params.contact), ("stinger", &params.stinger)] {
        if let Some(c) = contact
            && !matches!(c.method, Law::Penalty { .. })
        {
            return refuse(
                &format!("{key}.method"),
                "not penalty",
                "kind = \"penalty\" with reduced_modes (its force a function of the reduced state)",
            );
        }
    }
    Ok(())
}

/// Refuses a training window or tolerance out of range.
fn validate_sampling(sampling: &Sampling) -> Result<(), UnitError> {
    require_in_range(
        "reduced_sampling.training",
        sampling.training,
        1e-9,
        1e6,
        "s",
    )?;
    require_in_range(
        "reduced_sampling.tolerance",
        sampling.tolerance,
        1e-12,
        0.5,
        "",
    )?;
    Ok(())
}

/// The most free DOFs a reduced section's basis is formed for: its modes
/// come from a dense eigen-solve (O(n^3) time, 8 n^2 bytes), minutes and
/// gigabytes beyond this.
const MOST_FREE_DOFS: usize = 3000;

impl NonlinearSection {
    /// Refuses `reduced_modes` beyond the section's free DOFs, and a section
    /// too large for the dense modal solve, when the unit is built (so that
    /// `slender check` says so).
    pub(in crate::nonlinear) fn check_reduced_size(&self) -> Result<(), UnitError> {
        let Some(count) = self.params.reduced_modes else {
            return Ok(());
        };
        let free = self.model.dofs() - self.held_dofs().len();
        if count > free {
            return Err(UnitError::parameter(
                "reduced_modes",
                count.to_string(),
                &format!("at most {free}, the section's free DOFs"),
            ));
        }
        if free > MOST_FREE_DOFS {
            return Err(UnitError::parameter(
                "reduced_modes",
                count.to_string(),
                &format!(
                    "none on a section of {free} free DOFs: its modes are found by a dense eigen-solve, bounded to {MOST_FREE_DOFS} free DOFs (coarsen the section or cut it shorter)"
                ),
            ));
        }
        Ok(())
    }
}
