//! The unit of a study setting, for its axis title: from the scene reference
//! for a unit's parameter (`units.<name>.parameters.<key>`), from the tables
//! of `[simulation]` and `[master] tolerances`, and for the short names.

use slender_scene::kinds::reference;
use toml::Table;

/// The unit of measure of the setting `key` in `scene` (`""` for a count, a
/// name or a key slender does not know a unit for).
pub fn setting_unit(scene: &Table, key: &str) -> String {
    let parts: Vec<&str> = key.split('.').collect();
    let unit = match parts.as_slice() {
        ["step"] | ["simulation", "step" | "duration" | "start"] => "s",
        ["velocity_tolerance"] | ["master", "tolerances", "velocity"] => "m/s",
        ["force_tolerance"] | ["master", "tolerances", "force"] => "N",
        ["master", "tolerances", "displacement"] => "m",
        ["master", "tolerances", "rotation"] => "rad",
        ["master", "tolerances", "moment"] => "N m",
        ["units", name, "parameters", parameter, ..] => {
            return unit_parameter(scene, name, parameter);
        }
        _ => "",
    };
    unit.to_owned()
}

/// The documented unit of parameter `parameter` of the unit `name`'s kind.
fn unit_parameter(scene: &Table, name: &str, parameter: &str) -> String {
    let kind = (scene.get("units").and_then(toml::Value::as_array))
        .and_then(|units| {
            units
                .iter()
                .find(|u| u.get("name").and_then(toml::Value::as_str) == Some(name))
        })
        .and_then(|u| u.get("kind")?.as_str());
    kind.and_then(|k| reference::parameters(k).remove(parameter))
        .map(|info| info.unit)
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settings_carry_the_units_of_the_reference() {
        let scene: Table =
            toml::from_str("[[units]]\nname = \"line\"\nkind = \"cable\"\n[units.parameters]\n")
                .unwrap();
        assert_eq!(setting_unit(&scene, "simulation.step"), "s");
        assert_eq!(setting_unit(&scene, "velocity_tolerance"), "m/s");
        assert_eq!(setting_unit(&scene, "units.line.parameters.length"), "m");
        assert_eq!(setting_unit(&scene, "units.line.parameters.elements"), "");
        assert_eq!(setting_unit(&scene, "master.scheme"), "");
    }
}
