//! Names of units, plots and indicators: the characters allowed, and hints for
//! near misses in scenes and FMUs.
//!
//! A name is an ASCII letter or `_` followed by letters, digits and `_` (at most 64
//! characters): it is safe as a CSV column prefix (`unit.port`), a file name and an
//! FMI identifier, with nothing to quote.

/// A name that breaks the rule of the module docs.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "{what} `{name}`: expected an ASCII letter or `_` followed by letters, digits and `_` (at most 64 characters)"
)]
pub struct NameError {
    /// What the name names, e.g. "unit name".
    pub what: String,
    /// The name, escaped for display.
    pub name: String,
}

/// Checks a name (see the module docs); `what` says what it names in the message.
pub fn check_name(what: &str, name: &str) -> Result<(), NameError> {
    let mut chars = name.chars();
    let first_ok = chars
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_');
    if first_ok && name.len() <= 64 && chars.all(|c| c.is_ascii_alphanumeric() || c == '_') {
        Ok(())
    } else {
        Err(NameError {
            what: what.to_owned(),
            name: name.escape_debug().to_string(),
        })
    }
}

/// "; did you mean `x`?" when a candidate is close to `wrong`, else "".
pub fn did_you_mean<'a>(wrong: &str, candidates: impl Iterator<Item = &'a str>) -> String {
    candidates
        .map(|c| (strsim::levenshtein(wrong, c), c))
        .filter(|(d, c)| *d <= 2.max(c.len() / 3))
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| format!("; did you mean `{c}`?"))
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_that_would_corrupt_csv_or_paths_are_refused() {
        for good in ["a", "top_force", "_x1", "B6"] {
            assert!(check_name("unit", good).is_ok(), "{good}");
        }
        for bad in [
            "",
            "a,b",
            "a\nb",
            "../x",
            "a.b",
            "1a",
            "a b",
            &"x".repeat(65),
        ] {
            assert!(check_name("unit", bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn near_misses_get_a_hint_and_far_ones_do_not() {
        let names = ["top_force", "bottom_velocity"];
        assert_eq!(
            did_you_mean("top_forse", names.into_iter()),
            "; did you mean `top_force`?"
        );
        assert_eq!(did_you_mean("xyz", names.into_iter()), "");
    }
}
