//! Reading a ray log line by line (never the whole file), as a student's
//! tracer printed it: every error names LOG:line:column and what is wrong,
//! and none panics.

use std::collections::BTreeSet;
use std::fmt;
use std::io::{BufRead, Read};

use glam::DVec3;

use super::line::{self, Field, PerLight, read_line};
use super::logged_ray::{Hit, LoggedRay};
use super::path::RayPath;
use super::seen::SeenRays;
use raystep_engine::input_file;
use raystep_engine::record::count;
use raystep_engine::scene::Scene;

/// The longest line read: one ray never needs more.
pub const MAX_LINE_BYTES: usize = 1 << 20;

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
    unknown_keys: UnknownKeys,
    /// The scene's objects by name, made at the first `hit` given by name.
    by_name: Option<ObjectsByName>,
    finished: bool,
    buffer: Vec<u8>,
}

/// The scene's objects by name, each name's first object found at once
/// (each name was looked for object by object: 2000 lines against a mesh
/// of 100,000 triangles took 7.5 s). It keeps a hash of each name, 8
/// bytes, not the name (a mesh's triangles spell theirs out only when
/// asked); the object it gives is checked against the name, and a
/// different name of the same hash sends the search object by object, as
/// before, so that the answer is always the first object of that name.
struct ObjectsByName {
    hasher: std::hash::RandomState,
    first: std::collections::HashMap<u64, usize>,
}

impl ObjectsByName {
    fn new(objects: &[raystep_engine::scene::Object]) -> ObjectsByName {
        use std::hash::BuildHasher;
        let hasher = std::hash::RandomState::new();
        let mut first = std::collections::HashMap::with_capacity(objects.len());
        for (i, object) in objects.iter().enumerate() {
            let name = object.name.text();
            first.entry(hasher.hash_one(name.as_ref())).or_insert(i);
        }
        ObjectsByName { hasher, first }
    }

    /// The first object named `name`.
    fn find(&self, objects: &[raystep_engine::scene::Object], name: &str) -> Option<usize> {
        use std::hash::BuildHasher;
        let i = *self.first.get(&self.hasher.hash_one(name))?;
        if objects[i].name == *name {
            Some(i)
        } else {
            objects.iter().position(|o| o.name == *name)
        }
    }
}

/// Where a problem is in a line (a column from 1) and what it is.
type Problem = (usize, String);

/// At most this many unknown keys are listed ...
const UNKNOWN_LISTED: usize = 8;
/// ... each cut to this many characters: a log whose every line held
/// another 1000-character key once kept and printed them all (495 MB, and
/// 115 MB on one line).
const UNKNOWN_CHARS: usize = 40;
/// Distinct keys are counted up to this many (8 bytes each); past it the
/// count says "at least".
const UNKNOWN_COUNTED: usize = 1 << 16;

/// The keys a log holds that raystep doesn't know: the first few, sorted,
/// printable (a line break in a key once forged a line of the report) and
/// cut short, and how many distinct keys there are. Bounded whatever the
/// log.
#[derive(Debug, Default)]
pub struct UnknownKeys {
    listed: BTreeSet<String>,
    seen: std::collections::HashSet<u64>,
}

impl UnknownKeys {
    fn add(&mut self, key: &str) {
        use std::hash::{BuildHasher, BuildHasherDefault, DefaultHasher};
        if self.seen.len() >= UNKNOWN_COUNTED {
            return;
        }
        // A fixed hasher: the count is the same on every run.
        let hash = BuildHasherDefault::<DefaultHasher>::default().hash_one(key);
        if self.seen.insert(hash) && self.listed.len() < UNKNOWN_LISTED {
            self.listed.insert(shown(key));
        }
    }

    /// The keys listed, at most `UNKNOWN_LISTED`, sorted.
    pub fn listed(&self) -> impl Iterator<Item = &str> {
        self.listed.iter().map(String::as_str)
    }

    /// How many distinct keys, and whether that is only a lower bound.
    pub fn count(&self) -> (usize, bool) {
        (self.seen.len(), self.seen.len() >= UNKNOWN_COUNTED)
    }
}

/// A key as listed: control characters spelled out, at most
/// `UNKNOWN_CHARS` characters, then "…".
fn shown(key: &str) -> String {
    let printable = raystep_engine::printable::printable(key);
    match printable.char_indices().nth(UNKNOWN_CHARS) {
        Some((end, _)) => format!("{}…", &printable[..end]),
        None => printable.into_owned(),
    }
}

impl<'a, R: BufRead> RaylogReader<'a, R> {
    /// Reads `input`, named `log` in errors.
    pub fn new(log: impl Into<String>, input: R, scene: &'a Scene) -> Self {
        Self {
            log: log.into(),
            input,
            scene,
            line: 0,
            seen: SeenRays::new(scene.width, scene.height, scene.lights.len()),
            unknown_keys: UnknownKeys::default(),
            by_name: None,
            finished: false,
            buffer: Vec::new(),
        }
    }

    /// The keys raystep doesn't know, in the lines read so far: a few,
    /// printable and cut short, and how many there are.
    pub fn unknown_keys(&self) -> &UnknownKeys {
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
        if self.line == 1 {
            // Notepad's and PowerShell 5's byte-order mark, before the
            // first ray: no part of the log (columns count after it).
            buffer.drain(..input_file::byte_order_mark(buffer));
        }
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

    /// One line's ray: the line read (`read_line`, its only reading),
    /// then its keys checked in their order against the scene.
    fn ray(&mut self, text: &str) -> Result<LoggedRay, Problem> {
        let column = |at| column_of(text, at);
        let line = match read_line(text) {
            Ok(Some(line)) => line,
            Ok(None) => return Err((1, "not a JSON object: a line is one ray, {...}".into())),
            Err(e) => return Err((column(e.at), format!("not JSON: {}", e.words))),
        };
        for key in &line.unknown {
            self.unknown_keys.add(key);
        }
        let pixel = self.pixel(line.pixel, text)?;
        let Field { at: path_at, value } = required(line.path, "path")?;
        let lights = self.scene.lights.len();
        let path = value
            .and_then(|p| RayPath::parse(&p, lights))
            .map_err(|e| (column(path_at), e))?;
        if let Some(first) = self.seen.first_line(pixel, &path) {
            return Err((
                column(path_at),
                format!(
                    "pixel [{}, {}] path {path} is logged twice: first on line {first}",
                    pixel.0, pixel.1
                ),
            ));
        }
        // `t: null` is how some JSON printers write a miss's infinite t:
        // read as no t, marked, never refused (docs/RAYLOG.md).
        let t_null = line
            .t
            .as_ref()
            .is_some_and(|f| f.value.is_err() && text[f.at..].starts_with("null"));
        let t = if t_null { None } else { line.t };
        let ray = LoggedRay {
            origin: optional(line.origin, text)?,
            dir: optional(line.dir, text)?,
            hit: self.hit(line.hit, text)?,
            t: optional(t, text)?,
            t_null,
            point: optional(line.point, text)?,
            normal: optional(line.normal, text)?,
            color: optional(line.color, text)?,
            ambient: optional(line.ambient, text)?,
            diffuse: per_light(line.diffuse, "diffuse", lights, text)?,
            specular: per_light(line.specular, "specular", lights, text)?,
            s: optional(line.s, text)?,
            weight: optional(line.weight, text)?,
            ..LoggedRay::new(pixel, path)
        };
        self.seen.insert(pixel, &ray.path, self.line);
        Ok(ray)
    }

    fn pixel(&self, field: Option<Field<(u32, u32)>>, text: &str) -> Result<(u32, u32), Problem> {
        let field = required(field, "pixel")?;
        let (x, y) = field.value.map_err(|e| (column_of(text, field.at), e))?;
        let (width, height) = (self.scene.width, self.scene.height);
        if x >= width || y >= height {
            return Err((
                column_of(text, field.at),
                format!(
                    "pixel [{x}, {y}] is outside the image, which is {width}x{height} \
                     (x from 0 to {}, y from 0 to {})",
                    width.saturating_sub(1),
                    height.saturating_sub(1)
                ),
            ));
        }
        Ok((x, y))
    }

    fn hit(&mut self, field: Option<Field<line::Hit>>, text: &str) -> Result<Option<Hit>, Problem> {
        let Some(field) = field else {
            return Ok(None);
        };
        let column = || column_of(text, field.at);
        let objects = &self.scene.objects;
        match field.value.map_err(|e| (column(), e))? {
            line::Hit::Miss => Ok(Some(Hit::Miss)),
            line::Hit::Name(name) => match self
                .by_name
                .get_or_insert_with(|| ObjectsByName::new(objects))
                .find(objects, &name)
            {
                Some(i) => Ok(Some(Hit::Object(i))),
                None => Err((
                    column(),
                    format!("hit names no object of the scene: there is no object {name:?}"),
                )),
            },
            line::Hit::Index(index, written) => match index.and_then(|i| usize::try_from(i).ok()) {
                Some(i) if i < objects.len() => Ok(Some(Hit::Object(i))),
                _ => Err((
                    column(),
                    format!(
                        "hit {written} names no object of the scene: it has {}, \
                             counted from 0 in file order",
                        count(objects.len() as u64, "object", "objects")
                    ),
                )),
            },
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

/// A key every ray has.
fn required<T>(field: Option<Field<T>>, key: &str) -> Result<Field<T>, Problem> {
    field.ok_or_else(|| {
        (
            1,
            format!("no \"{key}\": every ray names its pixel and path"),
        )
    })
}

/// An optional key's value, if it is right.
fn optional<T>(field: Option<Field<T>>, text: &str) -> Result<Option<T>, Problem> {
    field
        .map(|f| f.value.map_err(|e| (column_of(text, f.at), e)))
        .transpose()
}

/// One [r, g, b] per light.
fn per_light(
    field: Option<Field<PerLight>>,
    key: &str,
    lights: usize,
    text: &str,
) -> Result<Option<Vec<DVec3>>, Problem> {
    let Some(field) = field else {
        return Ok(None);
    };
    let column = || column_of(text, field.at);
    let list = field.value.map_err(|e| (column(), e))?;
    if list.items != lights {
        return Err((
            column(),
            format!(
                "{key} holds {} [r, g, b], but the scene has {lights} light{}: one per light",
                list.items,
                if lights == 1 { "" } else { "s" }
            ),
        ));
    }
    match list.wrong {
        Some(e) => Err((column(), e)),
        None => Ok(Some(list.vectors)),
    }
}

/// The column (in characters, from 1) of byte `offset` of `text`.
fn column_of(text: &str, offset: usize) -> usize {
    text.char_indices().take_while(|(i, _)| *i < offset).count() + 1
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
    fn unknown_keys_are_few_printable_short_and_counted() {
        let (scene, _) = raystep_engine::test_scenes::ball();
        // 100 lines, each with its own 1000-character key holding a line
        // break: 8 listed (the sorted first 8 met), 40 characters each and
        // "…", the break spelled out; 100 counted.
        let log: String = (0..100)
            .map(|i| {
                let key = format!("k{i:03}\\n{}", "x".repeat(1000));
                format!(
                    "{{\"pixel\": [{}, {}], \"path\": \"P\", \"{key}\": 1}}\n",
                    i % 11,
                    i / 11
                )
            })
            .collect();
        let mut reader = RaylogReader::new("LOG", log.as_bytes(), &scene);
        assert!(reader.by_ref().all(|read| read.is_ok()));
        let keys = reader.unknown_keys();
        assert_eq!(keys.count(), (100, false));
        let listed: Vec<&str> = keys.listed().collect();
        assert_eq!(listed.len(), 8);
        // "k000" + "\u{a}" (5 characters) + 31 x's = 40, then "…".
        assert_eq!(listed[0], format!("k000\\u{{a}}{}…", "x".repeat(31)));
        assert_eq!(listed[7], format!("k007\\u{{a}}{}…", "x".repeat(31)));
    }

    /// The first ray of `line` for the ball (11x11, one light, one object
    /// "ball"), or its error; and the unknown keys the line named.
    fn read_line_of_ball(line: &str) -> (Result<LoggedRay, RaylogError>, BTreeSet<String>) {
        let (scene, _) = raystep_engine::test_scenes::ball();
        let mut reader = RaylogReader::new("LOG", line.as_bytes(), &scene);
        let ray = reader.next().unwrap().map(|(_, ray)| ray);
        let unknown = reader.unknown_keys().listed().map(String::from).collect();
        (ray, unknown)
    }

    /// Lines that read, for the ball: raystep's own, and others as a
    /// student's tracer may print them.
    fn good_lines() -> Vec<String> {
        let (_, tree) = raystep_engine::test_scenes::ball();
        let own = crate::raylog::raylog(&tree);
        assert!(own.lines().count() >= 3, "{own}");
        let others = [
            // Integers, -0, a hit by name and by index, a miss.
            r#"{"pixel": [5, 5], "path": "P", "t": 2, "dir": [0, -0, -1], "hit": "ball"}"#,
            r#"{"pixel": [5, 5], "path": "P", "hit": 0, "weight": 1e0, "mine": [{"a": 1}]}"#,
            r#"{"pixel": [5, 5], "path": "P/S0", "hit": null, "S": 1}"#,
            r#"{"pixel":[5,5],"path":"P","diffuse":[[0.5,0.25,1]],"specular":[[0,0,0]]}"#,
            r#"{"pixel": [10, 10], "path": "P/R/T/R", "color": [1.5e-300, 1e300, 123456789012345678901234567890]}"#,
            // A stand-in, a key twice (the last kept), an escaped path and key.
            r#"{"pixel": [5, 5], "path": "P", "t": NaN, "color": [Infinity, -Infinity, 0]}"#,
            r#"{"pixel": [5, 5], "path": "P", "t": 1, "t": 2}"#,
            r#"{"pixel": [5, 5], "p\u0061th": "P\/R"}"#,
        ];
        own.lines().chain(others).map(str::to_string).collect()
    }

    /// Lines refused for the ball: each with the text its column points at
    /// (its first occurrence; "" for column 1) and the problem.
    const BAD_LINES: [(&str, &str, &str); 20] = [
        (
            r#"{"pixel": [5.0, 5], "path": "P"}"#,
            "[5.0",
            "pixel is not [x, y], two whole numbers from 0: [5.0, 5]",
        ),
        (
            r#"{"pixel": [5, 5, 0], "path": "P"}"#,
            "[5",
            "pixel is not [x, y], two whole numbers from 0: [5, 5, 0]",
        ),
        (
            r#"{"pixel": [11, 5], "path": "P"}"#,
            "[11",
            "pixel [11, 5] is outside the image, which is 11x11 (x from 0 to 10, y from 0 to 10)",
        ),
        (
            r#"{"pixel": [5, 5], "path": "P/S1"}"#,
            "\"P/S1",
            "path \"P/S1\": there is no light 1: the scene has 1 light (S0)",
        ),
        (
            r#"{"pixel": [5, 5], "path": "P", "hit": 1}"#,
            "1}",
            "hit 1 names no object of the scene: it has 1 object, counted from 0 in file order",
        ),
        (
            r#"{"pixel": [5, 5], "path": "P", "hit": "cube"}"#,
            "\"cube",
            "hit names no object of the scene: there is no object \"cube\"",
        ),
        (
            r#"{"pixel": [5, 5], "path": "P", "hit": -0.0}"#,
            "-0.0",
            "hit -0.0 names no object of the scene: it has 1 object, counted from 0 in file order",
        ),
        (
            r#"{"pixel": [5, 5], "path": "P", "dir": [1, NaN]}"#,
            "[1",
            "dir has 2 numbers, not 3: [1, NaN]",
        ),
        (
            r#"{"pixel": [5, 5], "path": "P", "dir": [1, null, true]}"#,
            "[1",
            "dir is not 3 numbers: null is not a number",
        ),
        (
            r#"{"pixel": [5, 5], "path": "P", "diffuse": [[1, 2, 3], [1, 2, 3]]}"#,
            "[[",
            "diffuse holds 2 [r, g, b], but the scene has 1 light: one per light",
        ),
        (
            r#"{"pixel": [5, 5], "path": "P", "specular": [[1, 2]]}"#,
            "[[",
            "specular[0] has 2 numbers, not 3: [1, 2]",
        ),
        (
            r#"{"pixel": [5, 5], "path": "P", "S": null}"#,
            "null",
            "S is not a number: null",
        ),
        (
            r#"{"pixel": [5, 5], "path": "P", "S": "NaN"}"#,
            "\"NaN",
            "S is not a number: \"NaN\"",
        ),
        (
            r#"{"pixel": [5, 5], "path": "P/R", "weight": [0.3, 0.2]}"#,
            "[0.3",
            "weight has 2 numbers, not 3: [0.3, 0.2]",
        ),
        (
            r#"{"pixel": [5, 5], "path": "P/R", "weight": "0.4"}"#,
            "\"0.4",
            "weight is not a number: \"0.4\"",
        ),
        (
            r#"{"pixel": [5, 5]}"#,
            "",
            "no \"path\": every ray names its pixel and path",
        ),
        (
            r#"{"pixel": [5, 5], "path": "P"} ;"#,
            ";",
            "not JSON: trailing characters",
        ),
        (
            r#"{"pixel": [5, 5], "path": "P", "t": nan}"#,
            "an}",
            "not JSON: expected ident (write NaN, Infinity or -Infinity)",
        ),
        (
            r#"{"pixel": [5, 5], "path": "P", "weight": -inf}"#,
            "inf}",
            "not JSON: invalid number (write NaN, Infinity or -Infinity)",
        ),
        (
            r#"[5, 5]"#,
            "",
            "not a JSON object: a line is one ray, {...}",
        ),
    ];

    #[test]
    fn a_refused_line_names_its_column_and_problem() {
        for (line, at, problem) in BAD_LINES {
            let (ray, _) = read_line_of_ball(line);
            let error = ray.unwrap_err();
            let column = line.find(at).map_or(0, |i| line[..i].chars().count()) + 1;
            assert_eq!((error.line, error.column), (1, column), "{line}: {error}");
            assert_eq!(error.problem, problem, "{line}");
        }
        // The line ends inside a value: the column is just past its end.
        for line in [r#"{"pixel": [5, 5], "dir": [1, 2"#, "{\"a\": \"é"] {
            let error = read_line_of_ball(line).0.unwrap_err();
            assert_eq!(error.column, line.chars().count() + 1, "{error}");
            assert!(
                error.problem.starts_with("not JSON: EOF while parsing"),
                "{error}"
            );
        }
    }

    /// Until issue 37 a line was read one of three ways: straight into
    /// typed values when it was usual, else as a serde_json `Value` once
    /// its NaN and infinities were made strings, and an error's columns
    /// were found by a tokenizer of their own. Now one reading takes every
    /// line: a line reads to the same ray, or fails with the same words at
    /// the same value, with what used to send it another way put first (a
    /// bare stand-in, an escaped key, a key given twice).
    #[test]
    fn every_line_has_the_one_reading_whatever_else_it_holds() {
        let firsts = [
            r#""note": NaN, "#,
            r#""\u006eote": [Infinity, {"a": -Infinity}], "#,
            r#""pixel": "twice: the last is kept", "#,
        ];
        let good = good_lines();
        let bad = BAD_LINES.iter().map(|(line, ..)| line.to_string());
        for line in good.iter().cloned().chain(bad) {
            let (alone, _) = read_line_of_ball(&line);
            for first in firsts {
                let with = line.replacen('{', &format!("{{{first}"), 1);
                let (ray, unknown) = read_line_of_ball(&with);
                match (&alone, &ray) {
                    // The same bits (NaN's too).
                    (Ok(a), Ok(b)) => assert_eq!(format!("{a:?}"), format!("{b:?}"), "{with}"),
                    (Err(a), Err(b)) => {
                        assert_eq!(a.problem, b.problem, "{with}");
                        let moved = if line.starts_with('{') && a.column > 1 {
                            first.chars().count()
                        } else {
                            0
                        };
                        assert_eq!(a.column + moved, b.column, "{with}");
                    }
                    _ => panic!("{line}: {alone:?}\n{with}: {ray:?}"),
                }
                if ray.is_ok() && !first.starts_with(r#""pixel""#) {
                    assert!(unknown.contains("note"), "{with}");
                }
            }
        }
    }

    #[test]
    fn the_lines_read_to_their_values() {
        let (ray, unknown) = read_line_of_ball(&good_lines()[good_lines().len() - 3]);
        let ray = ray.unwrap();
        assert!(ray.t.unwrap().is_nan());
        let color = ray.color.unwrap().to_array();
        assert_eq!(color, [f64::INFINITY, f64::NEG_INFINITY, 0.0]);
        assert!(unknown.is_empty());
        let (ray, _) = read_line_of_ball(r#"{"pixel": [5, 5], "path": "P", "t": 1, "t": 2}"#);
        assert_eq!(ray.unwrap().t, Some(2.0));
        let (ray, _) = read_line_of_ball(r#"{"pixel": [5, 5], "p\u0061th": "P\/R"}"#);
        assert_eq!(*ray.unwrap().path.steps, [crate::raylog::Step::Reflected]);
        let line = r#"{"pixel": [5, 5], "path": "P", "hit": 0, "weight": 1e0, "mine": [{"a": 1}]}"#;
        let (ray, unknown) = read_line_of_ball(line);
        let ray = ray.unwrap();
        assert_eq!(
            (ray.hit, ray.weight),
            (Some(Hit::Object(0)), Some(glam::DVec3::ONE))
        );
        assert_eq!(unknown.into_iter().collect::<Vec<_>>(), ["mine"]);
        // A weight may be a colour, as a CSE 167 tracer's mirror weight S is.
        let line = r#"{"pixel": [5, 5], "path": "P/R", "weight": [0.3, 0.2, 0.1]}"#;
        let weight = read_line_of_ball(line).0.unwrap().weight.unwrap();
        assert_eq!(weight.to_array(), [0.3, 0.2, 0.1]);
        let line = r#"{"pixel": [10, 10], "path": "P/R/T/R", "color": [1.5e-300, 1e300, 123456789012345678901234567890]}"#;
        let color = read_line_of_ball(line).0.unwrap().color.unwrap();
        assert_eq!(color.to_array(), [1.5e-300, 1e300, 1.2345678901234568e29]);
        // A miss's t as some JSON printers write infinity: no t, marked
        // (issue 39); `null` elsewhere is still refused (BAD_LINES).
        let line = r#"{"pixel": [5, 5], "path": "P/R", "hit": null, "t": null}"#;
        let ray = read_line_of_ball(line).0.unwrap();
        assert_eq!((ray.hit, ray.t, ray.t_null), (Some(Hit::Miss), None, true));
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
