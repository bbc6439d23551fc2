//! Why a `[structure]` or a `[mooring]` cannot be read, solved or written
//! out: typed at the crate's boundary with the key it is about, so that the
//! scene names the user's line of that key.

use thiserror::Error;

/// A `[structure]` or `[mooring]` that cannot be read, solved or written out.
#[derive(Debug, Error)]
#[error("{message}")]
pub struct StructureError {
    /// The key it is about (`structure.sections.laid.fidelity`,
    /// `mooring.lines[1].anchor`), where the message names one.
    pub key: Option<String>,
    /// What is wrong and what was expected, naming the key.
    pub message: String,
}

/// A refusal in words: its key is the first under `structure` or `mooring`
/// that it names in backticks.
impl From<String> for StructureError {
    fn from(message: String) -> StructureError {
        let key = (crate::structure_lines::named_keys(&message, "structure"))
            .chain(crate::structure_lines::named_keys(&message, "mooring"))
            .next()
            .map(str::to_owned);
        StructureError { key, message }
    }
}

impl From<&str> for StructureError {
    fn from(message: &str) -> StructureError {
        StructureError::from(message.to_owned())
    }
}

/// Its words, where a caller reports in words.
impl From<StructureError> for String {
    fn from(e: StructureError) -> String {
        e.message
    }
}

#[cfg(test)]
mod tests {
    use super::StructureError;

    #[test]
    fn the_key_is_the_first_the_message_names() {
        let e = StructureError::from(
            "`structure.sections.laid.fidelity` = \"cable\": the section lies on the seabed"
                .to_owned(),
        );
        assert_eq!(e.key.as_deref(), Some("structure.sections.laid.fidelity"));
        let e = StructureError::from("`mooring.lines[1].anchor`: expected [x, y, z]");
        assert_eq!(e.key.as_deref(), Some("mooring.lines[1].anchor"));
        assert_eq!(StructureError::from("no key here").key, None);
    }
}
