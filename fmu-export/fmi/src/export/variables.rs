//! The variables an FMU's description declares, as text the FMU carries
//! (`resources/slender-variables.txt`): its library lays the unit out again at
//! instantiation and refuses to run when the two disagree, which happens when
//! the library packaged was built from other sources than the exporter (a
//! stale `--binary`), instead of answering for variables it does not have.

use super::Layout;

/// Where the FMU carries the list.
pub const VARIABLES_FILE: &str = "slender-variables.txt";

impl Layout {
    /// One line per variable: value reference, name, causality, type and array
    /// dimensions.
    pub fn variables_text(&self) -> String {
        let mut text = String::new();
        for v in &self.model.variables {
            let dimensions: Vec<String> = v.dimensions.iter().map(usize::to_string).collect();
            text.push_str(&format!(
                "{} {} {:?} {} [{}]\n",
                v.value_reference,
                v.name,
                v.causality,
                v.value.type_name(),
                dimensions.join(" ")
            ));
        }
        text
    }

    /// Checks the list an FMU carries against this layout; the first line that
    /// differs, named, when they disagree.
    pub fn check_variables(&self, carried: &str) -> Result<(), String> {
        let own = self.variables_text();
        if own == carried {
            return Ok(());
        }
        let differs = own
            .lines()
            .zip(carried.lines())
            .find(|(a, b)| a != b)
            .map(|(a, b)| format!("the description has `{b}` where the library has `{a}`"))
            .unwrap_or_else(|| {
                let (a, b) = (own.lines().count(), carried.lines().count());
                format!("the description declares {b} variables, the library {a}")
            });
        Err(format!(
            "this FMU's library lays the unit out differently from its model description ({differs}): it was built from other sources than the slender that exported it; export again with a library from the same build"
        ))
    }
}
