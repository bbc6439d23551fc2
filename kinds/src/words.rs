//! Deserialisation messages in the user's words: serde and toml name Rust
//! types (`expected f64`, `expected u32`, `a map`, `unit variant`), which a
//! scene's author should not need to know (issue 27: 33 such messages).

/// Rust type names and serde's terms, and what a scene's author calls them.
const WORDS: [(&str, &str); 21] = [
    ("expected f64", "expected a number"),
    ("expected f32", "expected a number"),
    ("expected u8", "expected a whole number from 0 to 255"),
    ("expected u16", "expected a whole number from 0 to 65535"),
    (
        "expected u32",
        "expected a whole number from 0 to 4294967295",
    ),
    ("expected u64", "expected a whole number >= 0"),
    ("expected usize", "expected a whole number >= 0"),
    ("expected i32", "expected a whole number"),
    ("expected i64", "expected a whole number"),
    ("expected a map", "expected a table ({ key = value, ... })"),
    ("expected a sequence", "expected an array ([a, b, ...])"),
    ("expected a boolean", "expected true or false"),
    ("expected unit variant", "expected a name in quotes"),
    ("expected unit struct", "expected a name in quotes"),
    ("expected variant identifier", "expected a name in quotes"),
    ("expected field identifier", "expected a key name"),
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
    (
        "invalid type: floating point",
        "invalid type: a number with a fraction",
    ),
];

/// Numbers in a message longer than this are written in scientific notation:
/// serde writes 1e308 with 309 digits.
const LONGEST_NUMBER: usize = 16;

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
    shorten_numbers(&text)
}

/// `text` with every number of more than `LONGEST_NUMBER` characters written
/// in scientific notation (`1e308`, not its 309 digits); numbers with an
/// exponent are short already and stay as written.
pub fn shorten_numbers(text: &str) -> String {
    let is_part = |c: char| c.is_ascii_digit() || c == '.';
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(start) = rest.find(|c: char| c.is_ascii_digit()) {
        let sign = usize::from(rest[..start].ends_with('-'));
        let digits_end = rest[start..]
            .find(|c: char| !is_part(c))
            .map_or(rest.len(), |n| start + n);
        let exponent = exponent_length(&rest[digits_end..]);
        let end = digits_end + exponent;
        let literal = &rest[start - sign..end];
        out.push_str(&rest[..start - sign]);
        match literal.parse::<f64>() {
            Ok(v) if exponent == 0 && literal.len() > LONGEST_NUMBER => {
                out.push_str(&format!("{v:e}"))
            }
            _ => out.push_str(literal),
        }
        rest = &rest[end..];
    }
    out.push_str(rest);
    out
}

/// The length of the exponent (`e9`, `E-12`) `text` starts with; 0 without one.
fn exponent_length(text: &str) -> usize {
    let b = text.as_bytes();
    if !matches!(b.first(), Some(b'e' | b'E')) {
        return 0;
    }
    let sign = usize::from(matches!(b.get(1), Some(b'+' | b'-')));
    let digits = b[1 + sign..]
        .iter()
        .take_while(|c| c.is_ascii_digit())
        .count();
    if digits == 0 { 0 } else { 1 + sign + digits }
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
            "invalid value: integer `-3`, expected a whole number from 0 to 4294967295"
        );
        assert_eq!(
            in_words("invalid type: floating point `0.5`, expected usize"),
            "invalid type: a number with a fraction `0.5`, expected a whole number >= 0"
        );
        assert_eq!(
            in_words("invalid type: integer `5`, expected a map"),
            "invalid type: integer `5`, expected a table ({ key = value, ... })"
        );
        assert_eq!(
            in_words("wanted string or table"),
            "expected a name in quotes or a table"
        );
        // A table where a kind's name belongs (`kind = { ... }`).
        assert_eq!(
            in_words("invalid type: map, expected variant identifier"),
            "invalid type: a table, expected a name in quotes"
        );
        // Not inside a longer word.
        assert_eq!(in_words("expected u320"), "expected u320");
    }

    #[test]
    fn long_numbers_are_written_in_scientific_notation() {
        let digits = format!("{}", 1e308f64);
        assert_eq!(digits.len(), 309);
        assert_eq!(
            in_words(&format!(
                "invalid type: floating point `-{digits}.0`, expected usize"
            )),
            "invalid type: a number with a fraction `-1e308`, expected a whole number >= 0"
        );
        // Short numbers, names with digits and versions stay as written.
        let kept = "units[12] (\"u2\"): 0.5 of 4294967296 at 1.2.3 to -9.223372036854776e9 s";
        assert_eq!(super::shorten_numbers(kept), kept);
    }
}
