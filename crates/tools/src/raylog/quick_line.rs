//! A line of a ray log read straight into typed values, without building a
//! `serde_json::Value` (a map, a `String` per key, a `Vec` per array): about
//! half the reader's time on a million lines went there. It takes only what
//! comes as expected; anything else (a NaN or infinity, an escaped path, a
//! key given twice, a value of the wrong kind) makes it give up, and the
//! reader's general path reads the line and words what is wrong. So both
//! read every line the same.

use std::borrow::Cow;
use std::fmt;

use glam::DVec3;
use serde::de::{self, Deserialize, Deserializer, MapAccess, Visitor};
use serde_json::Value;

/// The values of a line's keys, as written; `None` where a key is absent.
#[derive(Debug, Default, PartialEq)]
pub(super) struct QuickLine<'a> {
    pub(super) pixel: Option<(u32, u32)>,
    pub(super) path: Option<&'a str>,
    pub(super) origin: Option<DVec3>,
    pub(super) dir: Option<DVec3>,
    pub(super) hit: Option<QuickHit<'a>>,
    pub(super) t: Option<f64>,
    pub(super) point: Option<DVec3>,
    pub(super) normal: Option<DVec3>,
    pub(super) color: Option<DVec3>,
    pub(super) ambient: Option<DVec3>,
    pub(super) diffuse: Option<Vec<DVec3>>,
    pub(super) specular: Option<Vec<DVec3>>,
    pub(super) s: Option<f64>,
    pub(super) weight: Option<f64>,
    /// The keys raystep doesn't know.
    pub(super) unknown: Vec<Cow<'a, str>>,
}

/// `hit` as written: null, an index or a name.
#[derive(Debug, PartialEq)]
pub(super) enum QuickHit<'a> {
    Miss,
    Index(u64),
    Name(Cow<'a, str>),
}

/// `text` read, if it is a line this reading takes.
pub(super) fn quick_line(text: &str) -> Option<QuickLine<'_>> {
    serde_json::from_str(text).ok()
}

impl<'de> Deserialize<'de> for QuickLine<'de> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_map(LineVisitor)
    }
}

struct LineVisitor;

impl<'de> Visitor<'de> for LineVisitor {
    type Value = QuickLine<'de>;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a ray")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<QuickLine<'de>, A::Error> {
        let mut line = QuickLine::default();
        let vector = |v: [f64; 3]| DVec3::from_array(v);
        let per_light = |v: Vec<[f64; 3]>| v.into_iter().map(DVec3::from_array).collect();
        while let Some(Key(key)) = map.next_key()? {
            // serde's f64 takes integers as `as` does, as Value::as_f64.
            let first = match &*key {
                "pixel" => set(&mut line.pixel, map.next_value::<(u32, u32)>()?),
                "path" => set(&mut line.path, map.next_value::<Borrowed>()?.0),
                "origin" => set(&mut line.origin, vector(map.next_value()?)),
                "dir" => set(&mut line.dir, vector(map.next_value()?)),
                "hit" => set(&mut line.hit, map.next_value()?),
                "t" => set(&mut line.t, map.next_value()?),
                "point" => set(&mut line.point, vector(map.next_value()?)),
                "normal" => set(&mut line.normal, vector(map.next_value()?)),
                "color" => set(&mut line.color, vector(map.next_value()?)),
                "ambient" => set(&mut line.ambient, vector(map.next_value()?)),
                "diffuse" => set(&mut line.diffuse, per_light(map.next_value()?)),
                "specular" => set(&mut line.specular, per_light(map.next_value()?)),
                "S" => set(&mut line.s, map.next_value()?),
                "weight" => set(&mut line.weight, map.next_value()?),
                _ => {
                    // As a Value, so that it is refused exactly where the
                    // general reading refuses it (say, nested too deep).
                    map.next_value::<Value>()?;
                    line.unknown.push(key);
                    true
                }
            };
            if !first {
                return Err(de::Error::custom(
                    "a key twice: the general reading keeps the last",
                ));
            }
        }
        Ok(line)
    }
}

/// Sets an absent value; false if it was there.
fn set<T>(slot: &mut Option<T>, value: T) -> bool {
    slot.replace(value).is_none()
}

/// A key, borrowed from the line unless it has an escape.
struct Key<'a>(Cow<'a, str>);

impl<'de> Deserialize<'de> for Key<'de> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct KeyVisitor;
        impl<'de> Visitor<'de> for KeyVisitor {
            type Value = Key<'de>;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a key")
            }
            fn visit_borrowed_str<E>(self, v: &'de str) -> Result<Key<'de>, E> {
                Ok(Key(Cow::Borrowed(v)))
            }
            fn visit_str<E>(self, v: &str) -> Result<Key<'de>, E> {
                Ok(Key(Cow::Owned(v.to_string())))
            }
        }
        deserializer.deserialize_str(KeyVisitor)
    }
}

/// A string as written, without escapes (a path has none).
struct Borrowed<'a>(&'a str);

impl<'de> Deserialize<'de> for Borrowed<'de> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        <&str>::deserialize(deserializer).map(Borrowed)
    }
}

impl<'de> Deserialize<'de> for QuickHit<'de> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct HitVisitor;
        impl<'de> Visitor<'de> for HitVisitor {
            type Value = QuickHit<'de>;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("null, an index or a name")
            }
            fn visit_unit<E>(self) -> Result<QuickHit<'de>, E> {
                Ok(QuickHit::Miss)
            }
            fn visit_u64<E>(self, v: u64) -> Result<QuickHit<'de>, E> {
                Ok(QuickHit::Index(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<QuickHit<'de>, E> {
                // As Value keeps it: a number from 0 is a u64 to as_u64.
                u64::try_from(v)
                    .map(QuickHit::Index)
                    .map_err(|_| E::custom("a negative index"))
            }
            fn visit_borrowed_str<E>(self, v: &'de str) -> Result<QuickHit<'de>, E> {
                Ok(QuickHit::Name(Cow::Borrowed(v)))
            }
            fn visit_str<E>(self, v: &str) -> Result<QuickHit<'de>, E> {
                Ok(QuickHit::Name(Cow::Owned(v.to_string())))
            }
        }
        deserializer.deserialize_any(HitVisitor)
    }
}
