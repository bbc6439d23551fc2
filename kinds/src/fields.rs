//! The parameter names of a unit kind, read from its serde definition: a
//! deserializer that records the fields a struct asks for and stops. The scene
//! reference is checked against these names, so a parameter cannot go
//! undocumented.

use serde::de::{self, DeserializeOwned, Visitor};
use std::fmt;

/// The field names `T` deserializes from (empty when `T` is not a struct with
/// named fields).
pub fn field_names<T: DeserializeOwned>() -> &'static [&'static str] {
    match T::deserialize(FieldRecorder) {
        Err(Recorded(fields)) => fields,
        Ok(_) => &[],
    }
}

struct FieldRecorder;

/// The fields of the struct asked for (the "error" that stops deserializing).
#[derive(Debug)]
struct Recorded(&'static [&'static str]);

impl fmt::Display for Recorded {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "fields: {:?}", self.0)
    }
}

impl std::error::Error for Recorded {}

impl de::Error for Recorded {
    fn custom<T: fmt::Display>(_: T) -> Self {
        Recorded(&[])
    }
}

impl<'de> de::Deserializer<'de> for FieldRecorder {
    type Error = Recorded;

    fn deserialize_any<V: Visitor<'de>>(self, _: V) -> Result<V::Value, Recorded> {
        Err(Recorded(&[]))
    }

    fn deserialize_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        fields: &'static [&'static str],
        _visitor: V,
    ) -> Result<V::Value, Recorded> {
        Err(Recorded(fields))
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string
        bytes byte_buf option unit unit_struct newtype_struct seq tuple
        tuple_struct map enum identifier ignored_any
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(serde::Deserialize)]
    #[allow(dead_code)]
    struct Sample {
        mass: f64,
        #[serde(default)]
        stiffness: f64,
    }

    #[test]
    fn the_fields_of_a_struct_are_recorded() {
        assert_eq!(field_names::<Sample>(), &["mass", "stiffness"]);
        assert!(field_names::<f64>().is_empty());
    }
}
