//! A named shape with its material: what a scene lists and the acceleration
//! structure indexes. Apart from `scene` so `accel` can use it without
//! importing the scene that builds it.

use std::borrow::Cow;
use std::fmt;

use crate::shapes::Shape;

#[derive(Clone, Debug, PartialEq)]
pub struct Object {
    pub name: ObjectName,
    pub shape: Shape,
    /// Index into `Scene::materials`.
    pub material: usize,
}

/// An object's name: as the scene file gives it, or its kind and index in
/// the file ("polygon 12"), spelled out only when shown. An NFF mesh names
/// none of its triangles, and a `String` for each was 32 bytes of heap a
/// triangle.
#[derive(Clone, Debug)]
pub enum ObjectName {
    Given(Box<str>),
    Numbered { kind: &'static str, index: usize },
}

impl ObjectName {
    /// The name as text.
    pub fn text(&self) -> Cow<'_, str> {
        match self {
            ObjectName::Given(name) => Cow::Borrowed(name),
            ObjectName::Numbered { .. } => Cow::Owned(self.to_string()),
        }
    }
}

impl fmt::Display for ObjectName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ObjectName::Given(name) => f.write_str(name),
            ObjectName::Numbered { kind, index } => write!(f, "{kind} {index}"),
        }
    }
}

impl From<&str> for ObjectName {
    fn from(name: &str) -> ObjectName {
        ObjectName::Given(name.into())
    }
}

/// Names are equal when they read the same, however each is kept.
impl PartialEq for ObjectName {
    fn eq(&self, other: &ObjectName) -> bool {
        *self == *other.text()
    }
}

/// Without spelling a numbered name out: recordings look objects up by name.
impl PartialEq<str> for ObjectName {
    fn eq(&self, other: &str) -> bool {
        match self {
            ObjectName::Given(name) => **name == *other,
            ObjectName::Numbered { kind, index } => other
                .strip_prefix(kind)
                .and_then(|rest| rest.strip_prefix(' '))
                .is_some_and(|digits| {
                    // As `Display` writes it: digits only, no leading zero.
                    digits.bytes().all(|b| b.is_ascii_digit())
                        && (digits == "0" || !digits.starts_with('0'))
                        && digits.parse() == Ok(*index)
                }),
        }
    }
}

impl PartialEq<&str> for ObjectName {
    fn eq(&self, other: &&str) -> bool {
        *self == **other
    }
}

impl PartialEq<String> for ObjectName {
    fn eq(&self, other: &String) -> bool {
        *self == **other
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_numbered_name_equals_its_text_only() {
        let name = ObjectName::Numbered {
            kind: "polygon",
            index: 120,
        };
        assert_eq!(name.to_string(), "polygon 120");
        assert_eq!(name, "polygon 120");
        assert_eq!(name, ObjectName::from("polygon 120"));
        for other in [
            "polygon 12",
            "polygon 0120",
            "polygon +120",
            "polygon  120",
            "sphere 120",
            "polygon",
            "",
        ] {
            assert!(name != other, "{other:?}");
        }
        let zero = ObjectName::Numbered {
            kind: "sphere",
            index: 0,
        };
        assert_eq!(zero, "sphere 0");
        assert!(zero != "sphere 00");
        assert_eq!(ObjectName::from("my ball"), "my ball");
    }
}
