//! A named shape with its material: what a scene lists and the acceleration
//! structure indexes. Apart from `scene` so `accel` can use it without
//! importing the scene that builds it.

use std::borrow::Cow;
use std::fmt;
use std::sync::Arc;

use crate::shapes::Shape;

#[derive(Clone, Debug, PartialEq)]
pub struct Object {
    pub name: ObjectName,
    pub shape: Shape,
    /// Index into `Scene::materials`.
    pub material: usize,
}

/// An object's name: as the scene file gives it, its kind and index in the
/// file ("polygon 12"), or its place in an OBJ or STL mesh, spelled out
/// only when shown. An NFF mesh names none of its triangles, and a `String`
/// for each was 32 bytes of heap a triangle; a mesh file's were about 48.
/// The indices are u32 so the name stays 24 bytes (a test pins it); an
/// index beyond that is given as text (`ObjectName::numbered`).
#[derive(Clone, Debug)]
pub enum ObjectName {
    Given(Box<str>),
    Numbered {
        kind: &'static str,
        index: u32,
    },
    /// Triangle `index` of a mesh, in the order the mesh's triangles were
    /// placed; the mesh's names are kept once for all of them.
    MeshTriangle {
        names: Arc<MeshNames>,
        index: u32,
    },
}

impl ObjectName {
    /// "{kind} {index}".
    pub fn numbered(kind: &'static str, index: usize) -> ObjectName {
        match u32::try_from(index) {
            Ok(index) => ObjectName::Numbered { kind, index },
            Err(_) => ObjectName::Given(format!("{kind} {index}").into()),
        }
    }

    /// The name as text.
    pub fn text(&self) -> Cow<'_, str> {
        match self {
            ObjectName::Given(name) => Cow::Borrowed(name),
            _ => Cow::Owned(self.to_string()),
        }
    }
}

impl fmt::Display for ObjectName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ObjectName::Given(name) => f.write_str(name),
            ObjectName::Numbered { kind, index } => write!(f, "{kind} {index}"),
            ObjectName::MeshTriangle { names, index } => names.write(*index, f),
        }
    }
}

/// The names of one mesh's triangles, kept once for the whole mesh: triangle
/// k of group g is "{g} triangle {k}", followed by " (material {m})" when its
/// material came from the mesh's MTL. Consecutive triangles of one group and
/// material, numbered one after the other, share a run, so a mesh of a few
/// groups keeps a few runs however many triangles it has.
#[derive(Clone, Debug, Default)]
pub struct MeshNames {
    /// The groups' names, each with the scene's prefix for the mesh.
    groups: Vec<String>,
    /// The MTL's material names.
    materials: Vec<String>,
    runs: Vec<NameRun>,
    /// How many triangles have a name here.
    count: u32,
}

/// Triangles `first..` (up to the next run's first) of the mesh: group
/// `group`, numbered from `number`, with material `material`'s name.
#[derive(Clone, Copy, Debug, PartialEq)]
struct NameRun {
    first: u32,
    group: u32,
    number: u32,
    material: Option<u32>,
}

impl MeshNames {
    pub fn new(groups: Vec<String>, materials: Vec<String>) -> MeshNames {
        MeshNames {
            groups,
            materials,
            ..MeshNames::default()
        }
    }

    /// Names the next triangle: number `number` of group `group` (indices
    /// into the groups and materials given to `new`); its index, or `None`
    /// when an index does not fit a u32 (the caller names it in full).
    pub fn push(&mut self, group: usize, number: usize, material: Option<usize>) -> Option<u32> {
        let run = NameRun {
            first: self.count,
            group: u32::try_from(group).ok()?,
            number: u32::try_from(number).ok()?,
            material: match material {
                Some(m) => Some(u32::try_from(m).ok()?),
                None => None,
            },
        };
        let index = self.count;
        let next = self.count.checked_add(1)?;
        let continues = self.runs.last().is_some_and(|last| {
            (last.group, last.material) == (run.group, run.material)
                && u64::from(last.number) + u64::from(index - last.first) == u64::from(run.number)
        });
        if !continues {
            self.runs.push(run);
        }
        self.count = next;
        Some(index)
    }

    /// The same names with `prefix` before each group's.
    pub fn prefixed(&self, prefix: &str) -> MeshNames {
        MeshNames {
            groups: self.groups.iter().map(|g| format!("{prefix}{g}")).collect(),
            ..self.clone()
        }
    }

    fn write(&self, index: u32, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let run = &self.runs[self.runs.partition_point(|r| r.first <= index) - 1];
        let number = u64::from(run.number) + u64::from(index - run.first);
        write!(f, "{} triangle {number}", self.groups[run.group as usize])?;
        if let Some(m) = run.material {
            write!(f, " (material {})", self.materials[m as usize])?;
        }
        Ok(())
    }
}

/// Whether `value` displays as `text`, without writing it out: the
/// comparison stops at the first byte that differs.
fn displays_as(value: &impl fmt::Display, text: &str) -> bool {
    struct Rest<'a>(&'a str);
    impl fmt::Write for Rest<'_> {
        fn write_str(&mut self, s: &str) -> fmt::Result {
            match self.0.strip_prefix(s) {
                Some(rest) => {
                    self.0 = rest;
                    Ok(())
                }
                None => Err(fmt::Error),
            }
        }
    }
    let mut rest = Rest(text);
    fmt::write(&mut rest, format_args!("{value}")).is_ok() && rest.0.is_empty()
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
            ObjectName::MeshTriangle { .. } => displays_as(self, other),
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

    #[test]
    fn mesh_triangles_read_as_their_group_number_and_material() {
        // Groups "g" and "h", materials "red" and "blue". Pushed in order:
        // g 0, g 1 (red), g 2 (red), (g 3 skipped: degenerate), g 4 (red),
        // h 0, g 5 (red). Runs: g 0 | g 1.. red | g 4 red | h 0 | g 5 red.
        let mut names = MeshNames::new(
            vec!["g".into(), "h".into()],
            vec!["red".into(), "blue".into()],
        );
        let pushed = [
            (0, 0, None),
            (0, 1, Some(0)),
            (0, 2, Some(0)),
            (0, 4, Some(0)),
            (1, 0, None),
            (0, 5, Some(0)),
        ];
        for (i, (group, number, material)) in pushed.into_iter().enumerate() {
            assert_eq!(names.push(group, number, material), Some(i as u32));
        }
        assert_eq!(names.runs.len(), 5);
        let names = Arc::new(names);
        let name = |index| ObjectName::MeshTriangle {
            names: Arc::clone(&names),
            index,
        };
        let expected = [
            "g triangle 0",
            "g triangle 1 (material red)",
            "g triangle 2 (material red)",
            "g triangle 4 (material red)",
            "h triangle 0",
            "g triangle 5 (material red)",
        ];
        for (index, text) in expected.into_iter().enumerate() {
            let name = name(index as u32);
            assert_eq!(name.to_string(), text);
            assert_eq!(name, text);
            assert_eq!(name, ObjectName::from(text));
        }
        for other in [
            "g triangle 1",
            "g triangle 1 (material red",
            "g triangle 10 (material red)",
            "",
        ] {
            assert!(name(1) != other, "{other:?}");
        }
        let prefixed = ObjectName::MeshTriangle {
            names: Arc::new(names.prefixed("mesh 1 ")),
            index: 3,
        };
        assert_eq!(prefixed, "mesh 1 g triangle 4 (material red)");
    }

    /// A mesh of a million triangles holds a million objects, so every byte
    /// of `Object` is a megabyte (issue 26: at most 150 bytes a triangle).
    /// The sizes follow from the fields on a 64-bit target: a polygon is its
    /// boxed vertex slice (16), its plane (normal 24 + d 8) and the dropped
    /// axis (1, padded to 8): 56; a patch adds its boxed normals: 72, the
    /// largest variant (a cone is boxed), and the enum's tag fits in the
    /// axis's unused values. The name is 24 (a kind's `&str` and an index),
    /// the material index 8. A change here should be a choice, not an accident.
    /// (The name's u32 indices let its tag sit beside one of them: with a
    /// usize index it was 32 bytes.)
    #[test]
    #[cfg(target_pointer_width = "64")]
    fn shapes_and_objects_keep_their_size() {
        use crate::shapes::Polygon;
        assert_eq!(std::mem::size_of::<Polygon>(), 56);
        assert_eq!(std::mem::size_of::<Shape>(), 72);
        assert_eq!(std::mem::size_of::<ObjectName>(), 24);
        assert_eq!(std::mem::size_of::<Object>(), 104);
    }
}
