//! A line of a ray log read in one pass into its keys' typed values
//! (docs/RAYLOG.md): the only reading a line gets, whatever it holds (NaN,
//! escapes, a key twice, a value of the wrong kind). A value of the wrong
//! kind is not an error yet: it is kept as its field's problem, with where
//! the value starts, so that the reader can check the line in the order of
//! the keys (and the scene's size, lights and objects) once the line is
//! known to be JSON. A key given twice keeps its last value.

use std::borrow::Cow;
use std::fmt::{self, Display};

use glam::DVec3;

use super::json::{Item, Number, Scanner, SyntaxError};

/// A key's value where it starts (a byte offset in the line), or what is
/// wrong with it (its key named).
#[derive(Debug, PartialEq)]
pub(super) struct Field<T> {
    pub(super) at: usize,
    pub(super) value: Result<T, String>,
}

/// The values of a line's keys; `None` where a key is absent.
#[derive(Debug, Default, PartialEq)]
pub(super) struct Line<'a> {
    pub(super) pixel: Option<Field<(u32, u32)>>,
    pub(super) path: Option<Field<Cow<'a, str>>>,
    pub(super) origin: Option<Field<DVec3>>,
    pub(super) dir: Option<Field<DVec3>>,
    pub(super) hit: Option<Field<Hit<'a>>>,
    pub(super) t: Option<Field<f64>>,
    pub(super) point: Option<Field<DVec3>>,
    pub(super) normal: Option<Field<DVec3>>,
    pub(super) color: Option<Field<DVec3>>,
    pub(super) ambient: Option<Field<DVec3>>,
    pub(super) diffuse: Option<Field<PerLight>>,
    pub(super) specular: Option<Field<PerLight>>,
    pub(super) s: Option<Field<f64>>,
    pub(super) weight: Option<Field<DVec3>>,
    /// The keys raystep doesn't know, in the line's order.
    pub(super) unknown: Vec<Cow<'a, str>>,
}

/// `hit` as written: null, an index or a name.
#[derive(Debug, PartialEq)]
pub(super) enum Hit<'a> {
    Miss,
    /// A number: its index if it is a whole one, and as written.
    Index(Option<u64>, &'a str),
    Name(Cow<'a, str>),
}

/// `diffuse` or `specular`: a list of [r, g, b], one per light, whose
/// count the reader checks against the scene's lights before its items.
#[derive(Debug, PartialEq)]
pub(super) struct PerLight {
    pub(super) items: usize,
    pub(super) vectors: Vec<DVec3>,
    /// The first item that is not [r, g, b], and why.
    pub(super) wrong: Option<String>,
}

/// `text` read: its keys, or `None` for JSON that is not an object.
pub(super) fn read_line(text: &str) -> Result<Option<Line<'_>>, SyntaxError> {
    let mut s = Scanner::new(text);
    if s.peek() != Some(b'{') {
        s.skip()?;
        s.end()?;
        return Ok(None);
    }
    s.open()?;
    let mut line = Line::default();
    let mut first = true;
    while let Some(key) = s.next_key(first)? {
        first = false;
        s.blank();
        let at = s.at;
        let key = match &*key {
            "pixel" => set(&mut line.pixel, at, pixel(&mut s)?),
            "path" => set(&mut line.path, at, path(&mut s)?),
            "origin" => set(&mut line.origin, at, vector(&mut s, "origin")?),
            "dir" => set(&mut line.dir, at, vector(&mut s, "dir")?),
            "hit" => set(&mut line.hit, at, hit(&mut s)?),
            "t" => set(&mut line.t, at, number(&mut s, "t")?),
            "point" => set(&mut line.point, at, vector(&mut s, "point")?),
            "normal" => set(&mut line.normal, at, vector(&mut s, "normal")?),
            "color" => set(&mut line.color, at, vector(&mut s, "color")?),
            "ambient" => set(&mut line.ambient, at, vector(&mut s, "ambient")?),
            "diffuse" => set(&mut line.diffuse, at, per_light(&mut s, "diffuse")?),
            "specular" => set(&mut line.specular, at, per_light(&mut s, "specular")?),
            "S" => set(&mut line.s, at, number(&mut s, "S")?),
            "weight" => set(&mut line.weight, at, weight(&mut s)?),
            _ => {
                s.skip()?;
                Some(key)
            }
        };
        line.unknown.extend(key);
    }
    s.end()?;
    Ok(Some(line))
}

/// Keeps `value` in `slot` (over any value before it); no key is left over.
fn set<'a, T>(
    slot: &mut Option<Field<T>>,
    at: usize,
    value: Result<T, String>,
) -> Option<Cow<'a, str>> {
    *slot = Some(Field { at, value });
    None
}

/// What a value read for a key is: right, or what is wrong with it.
type Read<T> = Result<Result<T, String>, SyntaxError>;

fn pixel(s: &mut Scanner) -> Read<(u32, u32)> {
    let start = s.at;
    let mut xy = [None; 2];
    if let Item::List = s.item()? {
        let mut items = 0;
        while s.next_element(items == 0)? {
            let whole = match s.item()? {
                Item::Number(Number { whole, .. }) => whole.and_then(|w| u32::try_from(w).ok()),
                Item::List => {
                    s.skip_list()?;
                    None
                }
                _ => None,
            };
            if items < 2 {
                xy[items] = whole;
            }
            items += 1;
        }
        if items != 2 {
            xy = [None; 2];
        }
    }
    Ok(match xy {
        [Some(x), Some(y)] => Ok((x, y)),
        _ => Err(format!(
            "pixel is not [x, y], two whole numbers from 0: {}",
            s.since(start)
        )),
    })
}

fn path<'a>(s: &mut Scanner<'a>) -> Read<Cow<'a, str>> {
    Ok(match s.item()? {
        Item::Text(path) => Ok(path),
        item => {
            finish(s, &item)?;
            Err("path is not a string such as \"P/R\"".to_string())
        }
    })
}

fn hit<'a>(s: &mut Scanner<'a>) -> Read<Hit<'a>> {
    let start = s.at;
    Ok(match s.item()? {
        Item::Null => Ok(Hit::Miss),
        Item::Number(n) => Ok(Hit::Index(n.whole, s.since(start))),
        Item::Text(name) => Ok(Hit::Name(name)),
        item => {
            finish(s, &item)?;
            Err("hit is not an object's index, its name or null (a miss)".to_string())
        }
    })
}

fn number(s: &mut Scanner, key: &str) -> Read<f64> {
    let start = s.at;
    Ok(match s.item()? {
        Item::Number(n) => Ok(n.value),
        item => {
            finish(s, &item)?;
            Err(format!("{key} is not a number: {}", s.since(start)))
        }
    })
}

/// A weight: a number, the same on every channel, or [r, g, b] where a
/// profile weighs a ray by a colour (cse167's mirror ray, MODEL §11).
fn weight(s: &mut Scanner) -> Read<DVec3> {
    if s.peek() == Some(b'[') {
        vector(s, "weight")
    } else {
        Ok(number(s, "weight")?.map(DVec3::splat))
    }
}

/// Exactly three numbers; `key` names it in the words.
fn vector(s: &mut Scanner, key: impl Display) -> Read<DVec3> {
    let start = s.at;
    let item = s.item()?;
    if item != Item::List {
        return Ok(Err(format!(
            "{key} is not a vector of 3 numbers: {}",
            s.since(start)
        )));
    }
    let mut v = [0.0; 3];
    let (mut items, mut wrong) = (0, None);
    while s.next_element(items == 0)? {
        s.blank();
        let from = s.at;
        match s.item()? {
            Item::Number(n) if items < 3 => v[items] = n.value,
            Item::Number(_) => {}
            item => {
                finish(s, &item)?;
                wrong = wrong.or(Some(s.since(from)));
            }
        }
        items += 1;
    }
    Ok(match wrong {
        _ if items != 3 => Err(format!(
            "{key} has {items} numbers, not 3: {}",
            s.since(start)
        )),
        Some(item) => Err(format!("{key} is not 3 numbers: {item} is not a number")),
        None => Ok(DVec3::from_array(v)),
    })
}

/// A list of vectors.
fn per_light(s: &mut Scanner, key: &str) -> Read<PerLight> {
    let item = s.item()?;
    if item != Item::List {
        return Ok(Err(format!(
            "{key} is not a list of [r, g, b], one per light"
        )));
    }
    let mut list = PerLight {
        items: 0,
        vectors: Vec::new(),
        wrong: None,
    };
    while s.next_element(list.items == 0)? {
        s.blank();
        let i = list.items;
        match vector(s, Nth(key, i))? {
            Ok(v) => list.vectors.push(v),
            Err(e) => list.wrong = list.wrong.or(Some(e)),
        }
        list.items += 1;
    }
    Ok(Ok(list))
}

/// Item i of a list, in words: `diffuse[1]`.
struct Nth<'k>(&'k str, usize);

impl Display for Nth<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}[{}]", self.0, self.1)
    }
}

/// The rest of a value `item` began, when it is a list.
fn finish(s: &mut Scanner, item: &Item) -> Result<(), SyntaxError> {
    match item {
        Item::List => s.skip_list(),
        _ => Ok(()),
    }
}
