//! A check that every number of a value is finite, made before a recording is
//! written as JSON. serde_json writes NaN and infinity as `null`, which would
//! hide exactly the numbers a student most needs to see are wrong; this
//! serializer walks the value instead, writes nothing, and names the first
//! non-finite number by its path (`nodes[3].lights[0].f_att`).

use std::fmt;

use serde::Serialize;
use serde::ser;

/// The first non-finite number found, or a serializer's own failure.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NonFinite(pub String);

impl fmt::Display for NonFinite {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for NonFinite {}

impl ser::Error for NonFinite {
    fn custom<T: fmt::Display>(message: T) -> Self {
        NonFinite(message.to_string())
    }
}

/// Ok if every f32/f64 inside `value` is finite; else the path of the first
/// one that is not, under the name `root`.
pub(crate) fn check_finite<T: Serialize + ?Sized>(root: &str, value: &T) -> Result<(), NonFinite> {
    let mut checker = Checker {
        path: vec![root.to_string()],
    };
    value.serialize(&mut checker)
}

struct Checker {
    /// Where the walk is: the root's name, then `.field` and `[index]` steps.
    path: Vec<String>,
}

impl Checker {
    fn float(&self, value: f64) -> Result<(), NonFinite> {
        if value.is_finite() {
            Ok(())
        } else {
            Err(NonFinite(format!(
                "{} is {value}, not a finite number",
                self.path.concat()
            )))
        }
    }

    fn nested<T: Serialize + ?Sized>(&mut self, step: String, value: &T) -> Result<(), NonFinite> {
        self.path.push(step);
        let result = value.serialize(&mut *self);
        self.path.pop();
        result
    }
}

/// A sequence, tuple, map or struct being walked, counting its elements.
struct Compound<'a> {
    checker: &'a mut Checker,
    index: usize,
    /// A map's key, while its value is walked.
    key: Option<String>,
}

impl Compound<'_> {
    fn element<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), NonFinite> {
        let step = format!("[{}]", self.index);
        self.index += 1;
        self.checker.nested(step, value)
    }
}

type Done = Result<(), NonFinite>;

impl<'a> ser::Serializer for &'a mut Checker {
    type Ok = ();
    type Error = NonFinite;
    type SerializeSeq = Compound<'a>;
    type SerializeTuple = Compound<'a>;
    type SerializeTupleStruct = Compound<'a>;
    type SerializeTupleVariant = Compound<'a>;
    type SerializeMap = Compound<'a>;
    type SerializeStruct = Compound<'a>;
    type SerializeStructVariant = Compound<'a>;

    fn serialize_f32(self, v: f32) -> Done {
        self.float(v.into())
    }
    fn serialize_f64(self, v: f64) -> Done {
        self.float(v)
    }
    fn serialize_bool(self, _: bool) -> Done {
        Ok(())
    }
    fn serialize_i8(self, _: i8) -> Done {
        Ok(())
    }
    fn serialize_i16(self, _: i16) -> Done {
        Ok(())
    }
    fn serialize_i32(self, _: i32) -> Done {
        Ok(())
    }
    fn serialize_i64(self, _: i64) -> Done {
        Ok(())
    }
    fn serialize_u8(self, _: u8) -> Done {
        Ok(())
    }
    fn serialize_u16(self, _: u16) -> Done {
        Ok(())
    }
    fn serialize_u32(self, _: u32) -> Done {
        Ok(())
    }
    fn serialize_u64(self, _: u64) -> Done {
        Ok(())
    }
    fn serialize_char(self, _: char) -> Done {
        Ok(())
    }
    fn serialize_str(self, _: &str) -> Done {
        Ok(())
    }
    fn serialize_bytes(self, _: &[u8]) -> Done {
        Ok(())
    }
    fn serialize_none(self) -> Done {
        Ok(())
    }
    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Done {
        value.serialize(self)
    }
    fn serialize_unit(self) -> Done {
        Ok(())
    }
    fn serialize_unit_struct(self, _: &'static str) -> Done {
        Ok(())
    }
    fn serialize_unit_variant(self, _: &'static str, _: u32, _: &'static str) -> Done {
        Ok(())
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(self, _: &'static str, v: &T) -> Done {
        v.serialize(self)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        value: &T,
    ) -> Done {
        self.nested(format!(".{variant}"), value)
    }
    fn serialize_seq(self, _: Option<usize>) -> Result<Compound<'a>, NonFinite> {
        Ok(Compound {
            checker: self,
            index: 0,
            key: None,
        })
    }
    fn serialize_tuple(self, len: usize) -> Result<Compound<'a>, NonFinite> {
        self.serialize_seq(Some(len))
    }
    fn serialize_tuple_struct(
        self,
        _: &'static str,
        len: usize,
    ) -> Result<Compound<'a>, NonFinite> {
        self.serialize_seq(Some(len))
    }
    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        len: usize,
    ) -> Result<Compound<'a>, NonFinite> {
        self.path.push(format!(".{variant}"));
        self.serialize_seq(Some(len))
    }
    fn serialize_map(self, len: Option<usize>) -> Result<Compound<'a>, NonFinite> {
        self.serialize_seq(len)
    }
    fn serialize_struct(self, _: &'static str, len: usize) -> Result<Compound<'a>, NonFinite> {
        self.serialize_seq(Some(len))
    }
    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        len: usize,
    ) -> Result<Compound<'a>, NonFinite> {
        self.path.push(format!(".{variant}"));
        self.serialize_seq(Some(len))
    }
}

impl ser::SerializeSeq for Compound<'_> {
    type Ok = ();
    type Error = NonFinite;
    fn serialize_element<T: Serialize + ?Sized>(&mut self, value: &T) -> Done {
        self.element(value)
    }
    fn end(self) -> Done {
        Ok(())
    }
}

impl ser::SerializeTuple for Compound<'_> {
    type Ok = ();
    type Error = NonFinite;
    fn serialize_element<T: Serialize + ?Sized>(&mut self, value: &T) -> Done {
        self.element(value)
    }
    fn end(self) -> Done {
        Ok(())
    }
}

impl ser::SerializeTupleStruct for Compound<'_> {
    type Ok = ();
    type Error = NonFinite;
    fn serialize_field<T: Serialize + ?Sized>(&mut self, value: &T) -> Done {
        self.element(value)
    }
    fn end(self) -> Done {
        Ok(())
    }
}

impl ser::SerializeTupleVariant for Compound<'_> {
    type Ok = ();
    type Error = NonFinite;
    fn serialize_field<T: Serialize + ?Sized>(&mut self, value: &T) -> Done {
        self.element(value)
    }
    fn end(self) -> Done {
        self.checker.path.pop();
        Ok(())
    }
}

impl ser::SerializeMap for Compound<'_> {
    type Ok = ();
    type Error = NonFinite;
    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Done {
        key.serialize(&mut *self.checker)?;
        // A flattened struct arrives as a map: name its values by their keys.
        self.key = match serde_json::to_value(key) {
            Ok(serde_json::Value::String(key)) => Some(key),
            _ => None,
        };
        Ok(())
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, value: &T) -> Done {
        match self.key.take() {
            Some(key) => self.checker.nested(format!(".{key}"), value),
            None => self.element(value),
        }
    }
    fn end(self) -> Done {
        Ok(())
    }
}

impl ser::SerializeStruct for Compound<'_> {
    type Ok = ();
    type Error = NonFinite;
    fn serialize_field<T: Serialize + ?Sized>(&mut self, key: &'static str, value: &T) -> Done {
        self.checker.nested(format!(".{key}"), value)
    }
    fn end(self) -> Done {
        Ok(())
    }
}

impl ser::SerializeStructVariant for Compound<'_> {
    type Ok = ();
    type Error = NonFinite;
    fn serialize_field<T: Serialize + ?Sized>(&mut self, key: &'static str, value: &T) -> Done {
        self.checker.nested(format!(".{key}"), value)
    }
    fn end(self) -> Done {
        self.checker.path.pop();
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Serialize)]
    struct Light {
        f_att: f64,
    }

    #[derive(Serialize)]
    struct Node {
        color: [f64; 3],
        lights: Vec<Light>,
        s: Option<f64>,
    }

    fn node(f_att: f64, blue: f64) -> Node {
        Node {
            color: [0.5, 0.25, blue],
            lights: vec![Light { f_att: 1.0 }, Light { f_att }],
            s: Some(1.0),
        }
    }

    #[test]
    fn finite_values_pass() {
        assert_eq!(check_finite("nodes", &vec![node(0.5, 0.0)]), Ok(()));
    }

    #[test]
    fn a_nan_is_named_by_its_path() {
        let nodes = vec![node(0.5, 0.0), node(f64::NAN, 0.0)];
        let error = check_finite("nodes", &nodes).unwrap_err();
        assert_eq!(
            error.0,
            "nodes[1].lights[1].f_att is NaN, not a finite number"
        );
    }

    #[test]
    fn an_infinity_inside_an_array_is_named() {
        let error = check_finite("node", &node(1.0, f64::INFINITY)).unwrap_err();
        assert_eq!(error.0, "node.color[2] is inf, not a finite number");
    }

    #[test]
    fn an_option_and_an_enum_variant_are_walked() {
        #[derive(Serialize)]
        enum Event {
            Light { s: Option<f64> },
        }
        let error = check_finite(
            "events",
            &[Event::Light {
                s: Some(f64::NEG_INFINITY),
            }],
        );
        assert_eq!(
            error.unwrap_err().0,
            "events[0].Light.s is -inf, not a finite number"
        );
    }

    #[test]
    fn a_flattened_tagged_event_is_named_by_its_keys() {
        #[derive(Serialize)]
        #[serde(tag = "event", rename_all = "snake_case")]
        enum Kind {
            Hit { t: f64 },
        }
        #[derive(Serialize)]
        struct Event {
            node: usize,
            #[serde(flatten)]
            kind: Kind,
        }
        let events = [Event {
            node: 2,
            kind: Kind::Hit { t: f64::NAN },
        }];
        let error = check_finite("events", &events).unwrap_err();
        assert_eq!(error.0, "events[0].t is NaN, not a finite number");
    }
}
