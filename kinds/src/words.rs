//! Deserialisation messages in the user's words: serde and toml name Rust
//! types (`expected f64`, `expected u32`, `a map`, `unit variant`), which a
//! scene's author should not need to know (issue 27: 33 such messages).

/// Rust type names and serde's terms, and what a scene's author calls them.
const WORDS: [(&str, &str); 18] = [
    ("expected f64", "expected a number"),
    ("expected f32", "expected a number"),
    ("expected u8", "expected a whole number >= 0"),
    ("expected u16", "expected a whole number >= 0"),
    ("expected u32", "expected a whole number >= 0"),
    ("expected u64", "expected a whole number >= 0"),
    ("expected usize", "expected a whole number >= 0"),
    ("expected i32", "expected a whole number"),
    ("expected i64", "expected a whole number"),
    ("expected a map", "expected a table ({ key = value, ... })"),
    ("expected a sequence", "expected an array ([a, b, ...])"),
    ("expected a boolean", "expected true or false"),
    ("expected unit variant", "expected a name in quotes"),
    ("expected unit struct", "expected a name in quotes"),
    (
        "wanted string or table",
        "expected a name in quotes or a table",
    ),
    ("invalid type: map", "invalid type: a table"),
    ("invalid type: sequence", "invalid type: an array"),
    (
        "expected fewer elements in array",
        "expected fewer values in the array",
    ),
];

/// serde's words before a Rust type's own name (`expected struct
/// Tolerances`), and what a scene's author calls that kind of value.
const NAMED: [(&str, &str); 3] = [
    (
        "expected struct ",
        "expected a table ({ key = value, ... })",
    ),
    ("expected tuple struct ", "expected an array ([a, b, ...])"),
    ("expected enum ", "expected a name in quotes or a table"),
];

/// `message` with the Rust type names replaced by the user's words.
pub fn in_words(message: &str) -> String {
    let mut text = message.to_owned();
    for (rust, words) in NAMED {
        while let Some(at) = text.find(rust) {
            let name = text[at + rust.len()..]
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                .map_or(text.len(), |n| at + rust.len() + n);
            text.replace_range(at..name, words);
        }
    }
    for (rust, words) in WORDS {
        // Whole words only: `expected u32` must not match `expected u320`.
        let mut from = 0;
        while let Some(found) = text[from..].find(rust) {
            let at = from + found;
            let end = at + rust.len();
            let next = text[end..].chars().next();
            if next.is_some_and(|c| c.is_ascii_alphanumeric() || c == '_') {
                from = end;
                continue;
            }
            text.replace_range(at..end, words);
            from = at + words.len();
        }
    }
    text
}

#[cfg(test)]
mod tests {
    use super::in_words;

    #[test]
    fn a_rust_type_s_own_name_becomes_words() {
        assert_eq!(
            in_words("invalid type: integer `3`, expected struct Tolerances"),
            "invalid type: integer `3`, expected a table ({ key = value, ... })"
        );
        assert_eq!(
            in_words("expected enum Kind, at the end"),
            "expected a name in quotes or a table, at the end"
        );
    }

    #[test]
    fn rust_type_names_become_words() {
        assert_eq!(
            in_words("invalid type: string \"one\", expected f64"),
            "invalid type: string \"one\", expected a number"
        );
        assert_eq!(
            in_words("invalid value: integer `-3`, expected u32"),
            "invalid value: integer `-3`, expected a whole number >= 0"
        );
        assert_eq!(
            in_words("invalid type: integer `5`, expected a map"),
            "invalid type: integer `5`, expected a table ({ key = value, ... })"
        );
        assert_eq!(
            in_words("wanted string or table"),
            "expected a name in quotes or a table"
        );
        // Not inside a longer word.
        assert_eq!(in_words("expected u320"), "expected u320");
    }
}
