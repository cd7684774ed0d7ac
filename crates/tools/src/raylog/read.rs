//! Reading a ray log line by line (never the whole file), as a student's
//! tracer printed it: every error names LOG:line:column and what is wrong,
//! and none panics.

use std::collections::BTreeSet;
use std::fmt;
use std::io::{BufRead, Read};

use glam::DVec3;
use serde_json::{Map, Value};

use super::logged_ray::{Hit, LoggedRay};
use super::path::RayPath;
use super::quick_line::{QuickHit, quick_line};
use super::seen::SeenRays;
use super::stand_ins::{column_of, number, prepare, spelling_hint};
use raystep_engine::record::count;
use raystep_engine::scene::Scene;

/// The longest line read: one ray never needs more.
pub const MAX_LINE_BYTES: usize = 1 << 20;

/// The keys docs/RAYLOG.md defines; others are ignored and listed.
const KEYS: [&str; 14] = [
    "pixel", "path", "origin", "dir", "hit", "t", "point", "normal", "color", "ambient", "diffuse",
    "specular", "S", "weight",
];

/// What is wrong with a log, and where: `LOG:line:column: problem`, both
/// counted from 1, the column in characters.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RaylogError {
    pub log: String,
    pub line: usize,
    pub column: usize,
    pub problem: String,
}

impl fmt::Display for RaylogError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}:{}:{}: {}",
            self.log, self.line, self.column, self.problem
        )
    }
}

impl std::error::Error for RaylogError {}

/// The rays of a log for `scene` (its size, lights and objects decide what
/// is valid), one at a time with their line numbers. It stops at the first
/// error; an empty log is one.
pub struct RaylogReader<'a, R> {
    log: String,
    input: R,
    scene: &'a Scene,
    line: usize,
    /// Each pixel and path read, with its line, to name a repeat.
    seen: SeenRays,
    unknown_keys: BTreeSet<String>,
    finished: bool,
    buffer: Vec<u8>,
}

/// Where a problem is in a line (a column from 1) and what it is.
type Problem = (usize, String);

impl<'a, R: BufRead> RaylogReader<'a, R> {
    /// Reads `input`, named `log` in errors.
    pub fn new(log: impl Into<String>, input: R, scene: &'a Scene) -> Self {
        Self {
            log: log.into(),
            input,
            scene,
            line: 0,
            seen: SeenRays::new(scene.width, scene.height, scene.lights.len()),
            unknown_keys: BTreeSet::new(),
            finished: false,
            buffer: Vec::new(),
        }
    }

    /// The keys raystep doesn't know, in the lines read so far.
    pub fn unknown_keys(&self) -> &BTreeSet<String> {
        &self.unknown_keys
    }

    /// Whether a ray of `pixel` with `path` was read: at the end of the
    /// log, whether the log holds it.
    pub fn was_logged(&self, pixel: (u32, u32), path: &RayPath) -> bool {
        self.seen.first_line(pixel, path).is_some()
    }

    fn error(&mut self, (column, problem): Problem) -> RaylogError {
        self.finished = true;
        RaylogError {
            log: self.log.clone(),
            line: self.line.max(1),
            column,
            problem,
        }
    }

    /// The next line in `buffer` (reused: no allocation per line),
    /// without its line ending; `None` at the end.
    fn next_line<'b>(&mut self, buffer: &'b mut Vec<u8>) -> Result<Option<&'b str>, Problem> {
        buffer.clear();
        // One byte past the limit tells a line that is too long.
        let limit = MAX_LINE_BYTES as u64 + 1;
        let read = (&mut self.input)
            .take(limit)
            .read_until(b'\n', buffer)
            .map_err(|e| (1, format!("cannot read the log: {e}")))?;
        if read == 0 {
            return Ok(None);
        }
        self.line += 1;
        if buffer.last() == Some(&b'\n') {
            buffer.pop();
        }
        if buffer.last() == Some(&b'\r') {
            buffer.pop();
        }
        if buffer.len() > MAX_LINE_BYTES {
            return Err((
                MAX_LINE_BYTES + 1,
                format!("the line is over 1 MB ({MAX_LINE_BYTES} bytes): a log has one ray a line"),
            ));
        }
        match std::str::from_utf8(buffer) {
            Ok(text) => Ok(Some(text)),
            Err(e) => {
                let valid = std::str::from_utf8(&buffer[..e.valid_up_to()]).unwrap_or("");
                Err((valid.chars().count() + 1, "not UTF-8 text".to_string()))
            }
        }
    }

    /// One line's ray.
    fn ray(&mut self, text: &str) -> Result<LoggedRay, Problem> {
        if let Some(ray) = self.quick_ray(text) {
            return Ok(ray);
        }
        self.general_ray(text)
    }

    /// The ray of a line as most are (`quick_line`), or `None` for
    /// `general_ray` to read it and say what is wrong.
    fn quick_ray(&mut self, text: &str) -> Option<LoggedRay> {
        let line = quick_line(text)?;
        let scene = self.scene;
        let lights = scene.lights.len();
        let pixel = line.pixel?;
        if pixel.0 >= scene.width || pixel.1 >= scene.height {
            return None;
        }
        let path = RayPath::parse(line.path?, lights).ok()?;
        if self.seen.first_line(pixel, &path).is_some() {
            return None;
        }
        let hit = match line.hit {
            None => None,
            Some(QuickHit::Miss) => Some(Hit::Miss),
            Some(QuickHit::Index(i)) => {
                let i = usize::try_from(i)
                    .ok()
                    .filter(|&i| i < scene.objects.len())?;
                Some(Hit::Object(i))
            }
            Some(QuickHit::Name(name)) => Some(Hit::Object(
                scene.objects.iter().position(|o| o.name == *name)?,
            )),
        };
        let per_light = |v: &Option<Vec<_>>| v.as_ref().is_none_or(|v| v.len() == lights);
        if !per_light(&line.diffuse) || !per_light(&line.specular) {
            return None;
        }
        for key in line.unknown {
            self.unknown_keys.insert(key.into_owned());
        }
        let ray = LoggedRay {
            origin: line.origin,
            dir: line.dir,
            hit,
            t: line.t,
            point: line.point,
            normal: line.normal,
            color: line.color,
            ambient: line.ambient,
            diffuse: line.diffuse,
            specular: line.specular,
            s: line.s,
            weight: line.weight,
            ..LoggedRay::new(pixel, path)
        };
        self.seen.insert(pixel, &ray.path, self.line);
        Some(ray)
    }

    /// One line's ray, read as a `Value`: every line `quick_ray` leaves,
    /// and every problem found and worded.
    fn general_ray(&mut self, text: &str) -> Result<LoggedRay, Problem> {
        let prepared = prepare(text, false);
        let value: Value = serde_json::from_str(&prepared.json).map_err(|e| {
            let at = prepared.text_offset(e.column().saturating_sub(1));
            let words = e.to_string();
            let words = words
                .rfind(" at line ")
                .map_or(words.as_str(), |end| &words[..end]);
            (
                column_of(text, at),
                format!("not JSON: {words}{}", spelling_hint(text, at)),
            )
        })?;
        let Value::Object(map) = value else {
            return Err((1, "not a JSON object: a line is one ray, {...}".to_string()));
        };
        for key in map.keys() {
            if !KEYS.contains(&key.as_str()) {
                self.unknown_keys.insert(key.clone());
            }
        }
        let fields = Fields { map: &map, text };
        let pixel = self.pixel(&fields)?;
        let path = match fields.get("path")? {
            Value::String(path) => RayPath::parse(path, self.scene.lights.len())
                .map_err(|e| (fields.column("path"), e))?,
            _ => {
                return Err((
                    fields.column("path"),
                    "path is not a string such as \"P/R\"".into(),
                ));
            }
        };
        if let Some(first) = self.seen.first_line(pixel, &path) {
            return Err((
                fields.column("path"),
                format!(
                    "pixel [{}, {}] path {path} is logged twice: first on line {first}",
                    pixel.0, pixel.1
                ),
            ));
        }
        let lights = self.scene.lights.len();
        let ray = LoggedRay {
            origin: fields.vector("origin")?,
            dir: fields.vector("dir")?,
            hit: self.hit(&fields)?,
            t: fields.number("t")?,
            point: fields.vector("point")?,
            normal: fields.vector("normal")?,
            color: fields.vector("color")?,
            ambient: fields.vector("ambient")?,
            diffuse: fields.per_light("diffuse", lights)?,
            specular: fields.per_light("specular", lights)?,
            s: fields.number("S")?,
            weight: fields.number("weight")?,
            ..LoggedRay::new(pixel, path)
        };
        self.seen.insert(pixel, &ray.path, self.line);
        Ok(ray)
    }

    fn pixel(&self, fields: &Fields) -> Result<(u32, u32), Problem> {
        let value = fields.get("pixel")?;
        let coordinates: Option<Vec<u32>> = value.as_array().and_then(|items| {
            items
                .iter()
                .map(|v| v.as_u64().and_then(|n| u32::try_from(n).ok()))
                .collect()
        });
        let Some([x, y]) = coordinates.as_deref() else {
            return Err((
                fields.column("pixel"),
                format!("pixel is not [x, y], two whole numbers from 0: {value}"),
            ));
        };
        let (width, height) = (self.scene.width, self.scene.height);
        if *x >= width || *y >= height {
            return Err((
                fields.column("pixel"),
                format!(
                    "pixel [{x}, {y}] is outside the image, which is {width}x{height} \
                     (x from 0 to {}, y from 0 to {})",
                    width.saturating_sub(1),
                    height.saturating_sub(1)
                ),
            ));
        }
        Ok((*x, *y))
    }

    fn hit(&self, fields: &Fields) -> Result<Option<Hit>, Problem> {
        let Some(value) = fields.map.get("hit") else {
            return Ok(None);
        };
        let column = || fields.column("hit");
        let objects = &self.scene.objects;
        match value {
            Value::Null => Ok(Some(Hit::Miss)),
            Value::String(name) => match objects.iter().position(|o| &o.name == name) {
                Some(i) => Ok(Some(Hit::Object(i))),
                None => Err((
                    column(),
                    format!("hit names no object of the scene: there is no object {name:?}"),
                )),
            },
            Value::Number(n) => match n.as_u64().and_then(|i| usize::try_from(i).ok()) {
                Some(i) if i < objects.len() => Ok(Some(Hit::Object(i))),
                _ => Err((
                    column(),
                    format!(
                        "hit {n} names no object of the scene: it has {}, \
                         counted from 0 in file order",
                        count(objects.len() as u64, "object", "objects")
                    ),
                )),
            },
            _ => Err((
                column(),
                "hit is not an object's index, its name or null (a miss)".to_string(),
            )),
        }
    }
}

impl<R: BufRead> Iterator for RaylogReader<'_, R> {
    /// A ray and the line it is on.
    type Item = Result<(usize, LoggedRay), RaylogError>;

    fn next(&mut self) -> Option<Self::Item> {
        let mut buffer = std::mem::take(&mut self.buffer);
        let item = self.next_ray(&mut buffer);
        self.buffer = buffer;
        item
    }
}

impl<R: BufRead> RaylogReader<'_, R> {
    /// The iterator's next item, its lines read into `buffer`.
    fn next_ray(&mut self, buffer: &mut Vec<u8>) -> Option<<Self as Iterator>::Item> {
        while !self.finished {
            let text = match self.next_line(buffer) {
                Ok(Some(text)) => text,
                Ok(None) => {
                    self.finished = true;
                    if !self.seen.is_empty() {
                        return None;
                    }
                    let problem = "the log holds no ray (it is empty, or only comments and \
                                   blank lines): print one line per ray of a pixel"
                        .to_string();
                    return Some(Err(self.error((1, problem))));
                }
                Err(problem) => return Some(Err(self.error(problem))),
            };
            let content = text.trim_start();
            if content.is_empty() || content.starts_with('#') {
                continue;
            }
            return Some(match self.ray(text) {
                Ok(ray) => Ok((self.line, ray)),
                Err(problem) => Err(self.error(problem)),
            });
        }
        None
    }
}

/// A line's object, and its text to find its values' columns.
struct Fields<'a> {
    map: &'a Map<String, Value>,
    text: &'a str,
}

impl Fields<'_> {
    /// The column where `key`'s value starts (1 if not found). Only an
    /// error asks, so the line is scanned again for it then.
    fn column(&self, key: &str) -> usize {
        prepare(self.text, true)
            .value_at
            .get(key)
            .map_or(1, |&at| column_of(self.text, at))
    }

    fn get(&self, key: &str) -> Result<&Value, Problem> {
        self.map.get(key).ok_or_else(|| {
            (
                1,
                format!("no \"{key}\": every ray names its pixel and path"),
            )
        })
    }

    fn number(&self, key: &str) -> Result<Option<f64>, Problem> {
        match self.map.get(key) {
            None => Ok(None),
            Some(value) => number(value)
                .map(Some)
                .ok_or_else(|| (self.column(key), format!("{key} is not a number: {value}"))),
        }
    }

    fn vector(&self, key: &str) -> Result<Option<DVec3>, Problem> {
        match self.map.get(key) {
            None => Ok(None),
            Some(value) => vector(value)
                .map(Some)
                .map_err(|e| (self.column(key), format!("{key} {e}"))),
        }
    }

    /// One vector per light.
    fn per_light(&self, key: &str, lights: usize) -> Result<Option<Vec<DVec3>>, Problem> {
        let Some(value) = self.map.get(key) else {
            return Ok(None);
        };
        let column = || self.column(key);
        let items = value.as_array().ok_or_else(|| {
            (
                column(),
                format!("{key} is not a list of [r, g, b], one per light"),
            )
        })?;
        if items.len() != lights {
            return Err((
                column(),
                format!(
                    "{key} holds {} [r, g, b], but the scene has {lights} light{}: one per light",
                    items.len(),
                    if lights == 1 { "" } else { "s" }
                ),
            ));
        }
        items
            .iter()
            .enumerate()
            .map(|(i, item)| vector(item).map_err(|e| (column(), format!("{key}[{i}] {e}"))))
            .collect::<Result<_, _>>()
            .map(Some)
    }
}

/// Exactly three numbers; the error completes "KEY ...".
fn vector(value: &Value) -> Result<DVec3, String> {
    let items = value
        .as_array()
        .ok_or_else(|| format!("is not a vector of 3 numbers: {value}"))?;
    if items.len() != 3 {
        return Err(format!("has {} numbers, not 3: {value}", items.len()));
    }
    let mut v = [0.0; 3];
    for (x, item) in v.iter_mut().zip(items) {
        *x = number(item).ok_or_else(|| format!("is not 3 numbers: {item} is not a number"))?;
    }
    Ok(DVec3::from_array(v))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rays of `log` for the ball of `test_scenes` (11x11, one light),
    /// and the reader at its end (or first error).
    fn read_ball(log: &str) -> (Vec<<RaylogReader<'_, &[u8]> as Iterator>::Item>, bool) {
        let (scene, _) = raystep_engine::test_scenes::ball();
        let mut reader = RaylogReader::new("LOG", log.as_bytes(), &scene);
        let rays: Vec<_> = reader.by_ref().collect();
        let deep = RayPath::parse(&deep_path(), 1).unwrap();
        (rays, reader.was_logged((5, 5), &deep))
    }

    /// 56 reflections: 11x11 pixels take 7 of a key's 64 bits, the path's
    /// P, its shadow bit and 56 steps 58 more (1 light takes none): this
    /// path does not pack and is kept in the reader's plain map.
    fn deep_path() -> String {
        format!("P{}", "/R".repeat(56))
    }

    #[test]
    fn a_repeat_is_named_with_its_first_line_whether_its_path_packs_or_not() {
        let deep = deep_path();
        let ray = |pixel: &str, path: &str| format!(r#"{{"pixel": {pixel}, "path": "{path}"}}"#);
        // Line 1 the deep path, 2 and 3 packed rays, 4 a comment, 5 the deep
        // path again.
        let log = [
            ray("[5, 5]", &deep),
            ray("[5, 5]", "P"),
            ray("[5, 5]", "P/S0"),
            "# again".to_string(),
            ray("[5, 5]", &deep),
        ]
        .join("\n");
        let (rays, _) = read_ball(&log);
        assert_eq!(rays.len(), 4, "three rays, then the error");
        let error = rays[3].as_ref().unwrap_err();
        // The path's value starts at column 27: `{"pixel": [5, 5], "path": ` is 26.
        assert_eq!((error.line, error.column), (5, 27), "{error}");
        assert_eq!(
            error.problem,
            format!("pixel [5, 5] path {deep} is logged twice: first on line 1")
        );
        // A packed ray repeated, first read after the deep one (kept apart)
        // and a blank line: the line its run of lines (4 and 5) starts on.
        let log = [
            ray("[5, 5]", "P"),
            ray("[5, 5]", &deep),
            String::new(),
            ray("[0, 10]", "P/R"),
            ray("[10, 0]", "P/R"),
            ray("[0, 10]", "P/R"),
        ]
        .join("\n");
        let (rays, deep_logged) = read_ball(&log);
        assert!(deep_logged);
        let error = rays.last().unwrap().as_ref().unwrap_err();
        assert_eq!(error.line, 6, "{error}");
        assert_eq!(
            error.problem,
            "pixel [0, 10] path P/R is logged twice: first on line 4"
        );
    }

    #[test]
    fn the_quick_reading_takes_the_usual_lines_and_reads_them_as_the_general_one() {
        let (scene, tree) = raystep_engine::test_scenes::ball();
        let own = crate::raylog::raylog(&tree);
        let mut lines: Vec<(String, bool)> = own.lines().map(|l| (l.to_string(), true)).collect();
        assert!(lines.len() >= 3, "{own}");
        let taken = [
            // Integers, -0, a hit by name and by index, a miss, an unknown key.
            r#"{"pixel": [5, 5], "path": "P", "t": 2, "dir": [0, -0, -1], "hit": "ball"}"#,
            r#"{"pixel": [5, 5], "path": "P", "hit": 0, "weight": 1e0, "mine": [{"a": 1}]}"#,
            r#"{"pixel": [5, 5], "path": "P/S0", "hit": null, "S": 1}"#,
            r#"{"pixel":[5,5],"path":"P","diffuse":[[0.5,0.25,1]],"specular":[[0,0,0]]}"#,
            // An escaped key is the same key.
            r#"{"pixel": [5, 5], "path": "P"}"#,
            r#"{"pixel": [10, 10], "path": "P/R/T/R", "color": [1.5e-300, 1e300, 123456789012345678901234567890]}"#,
        ];
        let left = [
            r#"{"pixel": [5, 5], "path": "P", "t": NaN}"#,
            r#"{"pixel": [5, 5], "path": "P", "t": 1, "t": 2}"#,
            r#"{"pixel": [5, 5], "path": "P\/R"}"#,
            r#"{"pixel": [5.0, 5], "path": "P"}"#,
            r#"{"pixel": [5, 5, 0], "path": "P"}"#,
            r#"{"pixel": [11, 5], "path": "P"}"#,
            r#"{"pixel": [5, 5], "path": "P/S1"}"#,
            r#"{"pixel": [5, 5], "path": "P", "hit": 1}"#,
            r#"{"pixel": [5, 5], "path": "P", "hit": "cube"}"#,
            r#"{"pixel": [5, 5], "path": "P", "hit": -1}"#,
            r#"{"pixel": [5, 5], "path": "P", "hit": 0.0}"#,
            r#"{"pixel": [5, 5], "path": "P", "dir": [1, 2]}"#,
            r#"{"pixel": [5, 5], "path": "P", "diffuse": [[1, 2, 3], [1, 2, 3]]}"#,
            r#"{"pixel": [5, 5], "path": "P", "t": null}"#,
            "{\"pixel\": [5, 5], \"path\": \"P\", \"t\": \"\0NaN\"}",
            r#"{"pixel": [5, 5]}"#,
            r#"{"pixel": [5, 5], "path": "P"} x"#,
            r#"[5, 5]"#,
        ];
        lines.extend(taken.iter().map(|l| (l.to_string(), true)));
        lines.extend(left.iter().map(|l| (l.to_string(), false)));
        for (line, quick) in &lines {
            let mut reader = RaylogReader::new("LOG", &b""[..], &scene);
            let mut general = RaylogReader::new("LOG", &b""[..], &scene);
            match reader.quick_ray(line) {
                Some(ray) => {
                    assert!(quick, "taken: {line}");
                    let other = general.general_ray(line).unwrap();
                    // The same bits (NaN aside: none is taken).
                    assert_eq!(format!("{ray:?}"), format!("{other:?}"), "{line}");
                    assert_eq!(reader.unknown_keys, general.unknown_keys, "{line}");
                    assert!(reader.was_logged(ray.pixel, &ray.path));
                }
                None => {
                    assert!(!quick, "left: {line}");
                    assert!(!reader.was_logged((5, 5), &RayPath::primary()));
                    assert!(reader.unknown_keys.is_empty());
                }
            }
        }
        // The general reading refuses all but the NaN, the doubled t (the
        // last kept) and the escaped path: those it reads as the quick
        // reading cannot.
        let accepted: Vec<&str> = left
            .iter()
            .filter(|l| {
                let mut general = RaylogReader::new("LOG", &b""[..], &scene);
                general.general_ray(l).is_ok()
            })
            .copied()
            .collect();
        assert_eq!(accepted, [left[0], left[1], left[2]]);
    }

    #[test]
    fn the_reader_tells_which_rays_were_logged() {
        let (scene, _) = raystep_engine::test_scenes::ball();
        let log = "{\"pixel\": [5, 5], \"path\": \"P\"}\n\n\
                   {\"pixel\": [5, 5], \"path\": \"P/R/S0\"}\n\
                   {\"pixel\": [10, 10], \"path\": \"P/T\"}\n";
        let mut reader = RaylogReader::new("LOG", log.as_bytes(), &scene);
        let lines: Vec<usize> = reader.by_ref().map(|r| r.unwrap().0).collect();
        assert_eq!(lines, [1, 3, 4]);
        let logged = |pixel, path| reader.was_logged(pixel, &RayPath::parse(path, 1).unwrap());
        assert!(logged((5, 5), "P"));
        assert!(logged((5, 5), "P/R/S0"));
        assert!(logged((10, 10), "P/T"));
        // Another path of a logged pixel, a logged path of another pixel,
        // the parent of a logged ray: none was logged.
        assert!(!logged((5, 5), "P/R"));
        assert!(!logged((5, 5), "P/T"));
        assert!(!logged((10, 10), "P"));
        assert!(!logged((5, 6), "P"));
        // A pixel outside the image was never logged.
        assert!(!logged((11, 5), "P"));
        // The deep path of the other test, not read here.
        assert!(!reader.was_logged((5, 5), &RayPath::parse(&deep_path(), 1).unwrap()));
    }
}
