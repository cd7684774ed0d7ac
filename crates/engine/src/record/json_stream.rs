//! The recording as JSON (`inspect --format json`), written as it is
//! walked: the bytes of `RayTree::to_json` printed pretty, with memory
//! bounded by one node per level of the tree instead of the whole
//! document (a tree of 65,536 rays is 1.1 GB of JSON; its `Value` took
//! 3.7 GB). Every object's keys come in sorted order, as serde_json's
//! `Value` keeps them; each node and event is turned into a `Value` of its
//! own, so its numbers are written exactly as before.

use std::collections::BTreeMap;
use std::io::Write;

use serde::Serialize;
use serde::ser::{Error, SerializeMap, SerializeSeq, Serializer};
use serde_json::Value;

use super::ray_tree::{Event, NodeId, RayTree};

/// Writes `tree` as indented JSON and a newline: the same bytes as
/// `serde_json::to_string_pretty(&tree.to_json())` and "\n".
pub fn write_json(tree: &RayTree, out: &mut dyn Write) -> serde_json::Result<()> {
    serde_json::to_writer_pretty(&mut *out, &Document(tree))?;
    out.write_all(b"\n").map_err(serde_json::Error::io)
}

/// A value of an object, written when its turn comes.
enum Field<'a> {
    Value(Value),
    Node(&'a RayTree, NodeId),
    Events(&'a [Event]),
}

impl Serialize for Field<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            Field::Value(value) => value.serialize(serializer),
            Field::Node(tree, id) => node_fields(tree, *id)
                .map_err(S::Error::custom)?
                .serialize(serializer),
            Field::Events(events) => {
                let mut seq = serializer.serialize_seq(Some(events.len()))?;
                for event in *events {
                    seq.serialize_element(&to_value(event)?)?;
                }
                seq.end()
            }
        }
    }
}

/// An object's fields, in sorted order.
struct Fields<'a>(BTreeMap<String, Field<'a>>);

impl Serialize for Fields<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(self.0.len()))?;
        for (key, value) in &self.0 {
            map.serialize_entry(key, value)?;
        }
        map.end()
    }
}

/// The whole recording: `RayTree::to_json`'s keys.
struct Document<'a>(&'a RayTree);

impl Serialize for Document<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let tree = self.0;
        let mut fields = BTreeMap::new();
        let mut value = |key: &str, value: Value| {
            fields.insert(key.to_string(), Field::Value(value));
        };
        value("pixel", to_value([tree.pixel.0, tree.pixel.1])?);
        value("color", to_value(tree.color())?);
        value("rgb8", to_value(tree.rgb8())?);
        if !tree.mistakes.is_empty() {
            value("mistakes", to_value(tree.mistakes)?);
        }
        fields.insert("tree".into(), Field::Node(tree, 0));
        fields.insert("events".into(), Field::Events(&tree.events));
        Fields(fields).serialize(serializer)
    }
}

/// Node `id` as `RayTree::node_json` makes it: its own fields, its
/// children in place of their ids (written when their turn comes), its id
/// and whether it was total internal reflection.
fn node_fields(tree: &RayTree, id: NodeId) -> serde_json::Result<Fields<'_>> {
    let node = &tree.nodes[id];
    let Value::Object(own) = serde_json::to_value(node)? else {
        return Err(serde_json::Error::custom("a node is not a JSON object"));
    };
    let mut fields: BTreeMap<String, Field> = (own.into_iter())
        .map(|(key, value)| (key, Field::Value(value)))
        .collect();
    let child =
        |child: Option<NodeId>| child.map_or(Field::Value(Value::Null), |c| Field::Node(tree, c));
    fields.insert("reflected".into(), child(node.reflected));
    fields.insert("transmitted".into(), child(node.transmitted));
    fields.insert("id".into(), Field::Value(id.into()));
    fields.insert("tir".into(), Field::Value(node.tir().into()));
    Ok(Fields(fields))
}

fn to_value<T: Serialize, E: Error>(value: T) -> Result<Value, E> {
    serde_json::to_value(value).map_err(E::custom)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::record::record_pixel;
    use crate::scene::builtin::load_file_or_builtin;
    use raystep_model::mistakes::Mistake;

    fn streamed(tree: &RayTree) -> String {
        let mut out = Vec::new();
        write_json(tree, &mut out).unwrap();
        String::from_utf8(out).unwrap()
    }

    #[test]
    fn the_stream_writes_the_bytes_of_the_whole_value() {
        // Every pixel of a coarse grid over the built-in scene (misses,
        // mirrors, glass, shadows), with and without mistakes: the bytes
        // are those of the `Value` printed whole.
        let scene = load_file_or_builtin(None).unwrap();
        let mut mistaken = scene.settings;
        mistaken.mistakes = (mistaken.mistakes)
            .with(Mistake::Gamma)
            .with(Mistake::NoAmbient);
        for settings in [scene.settings, mistaken] {
            for y in (0..scene.height).step_by(12) {
                for x in (0..scene.width).step_by(16) {
                    let tree = record_pixel(&scene, &settings, x, y);
                    let whole = serde_json::to_string_pretty(&tree.to_json()).unwrap() + "\n";
                    assert_eq!(streamed(&tree), whole, "pixel ({x}, {y})");
                }
            }
        }
    }
}
