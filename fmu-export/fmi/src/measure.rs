//! Units of measure in FMI terms: a port's unit name as a `UnitDefinition` (SI
//! base-unit exponents, from [`slender_contract::measure`]).

use crate::model_description::UnitDefinition;
pub use slender_contract::measure::same_unit;
use slender_contract::measure::si_exponents;

/// The FMI definition of a unit name such as "N.m" or "m/s^2"; `None` for an empty
/// name or a symbol slender does not know.
pub fn si_definition(name: &str) -> Option<UnitDefinition> {
    Some(UnitDefinition {
        name: name.to_owned(),
        exponents: si_exponents(name)?,
        factor: 1.0,
        offset: 0.0,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_definition_carries_the_name_and_the_exponents() {
        let d = si_definition("N.m").unwrap();
        assert_eq!(
            (d.name.as_str(), d.exponents),
            ("N.m", [1, 2, -2, 0, 0, 0, 0, 0])
        );
        assert!(si_definition("furlong").is_none());
    }
}
