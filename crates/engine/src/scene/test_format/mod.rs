//! Reader of UCSD CSE 167's `.test` scene format (CSE167x on edX, formerly
//! BerkeleyX CS184.1x): issue 42's groundwork. It parses a file into a
//! [`TestScene`], a plain description with the transform stack already
//! flattened into the objects and lights; nothing here renders it yet, and
//! `scene::load` still refuses `.test` files (the lighting *profile* that
//! says what the scene means is the next part of issue 42).
//!
//! # What is read
//!
//! One command per line; blank lines and `#` comments (a `#` at the start of
//! a word runs to the end of the line) are skipped. Every command:
//!
//! | command | values |
//! |---|---|
//! | `size` | width height (must be the first command) |
//! | `maxdepth` | n (default 5, as the course's spec says) |
//! | `output` | file name |
//! | `camera` | from(3) at(3) up(3) fovy (vertical, degrees) |
//! | `sphere` | x y z radius |
//! | `maxverts`, `maxvertnorms` | n |
//! | `vertex` | x y z |
//! | `vertexnormal` | x y z nx ny nz |
//! | `tri`, `trinormal` | i j k (0-based indices into each pile) |
//! | `translate`, `scale` | x y z |
//! | `rotate` | ax ay az degrees |
//! | `pushTransform`, `popTransform` | — |
//! | `directional` | x y z r g b (the direction *to* the light) |
//! | `point` | x y z r g b |
//! | `attenuation` | c0 c1 c2 (default 1 0 0) |
//! | `ambient`, `diffuse`, `specular`, `emission` | r g b |
//! | `shininess` | s |
//!
//! # The course's conventions followed
//!
//! The course's skeleton `readfile.cpp` (HW2 of CSE167x; e.g. the copy in
//! the repository mbrucher/edx-CSE167x, `hw2/readfile.cpp`) is the reference:
//!
//! - The stack starts as the identity; `translate`, `rotate` and `scale`
//!   right-multiply its top (`rightmultiply`: `T = T * M`), so the command
//!   nearest the object acts on it first, as in OpenGL. `pushTransform` copies
//!   the top; `popTransform` on the last matrix is refused here (the skeleton
//!   prints "Stack has no elements. Cannot Pop" and goes on). `rotate`'s axis
//!   is normalised and the turn is counter-clockwise, as `glRotate`.
//! - Material state (`ambient` 0.2 grey, the other colours and `shininess`
//!   0 until set) is copied into each object when it is made, and the
//!   current transform with it.
//! - A sphere keeps its centre and radius in object space with its world
//!   matrix (under a non-uniform scale it is an ellipsoid); a `tri`'s
//!   vertices are transformed to world space when it is made; a `trinormal`'s
//!   normals by the inverse transpose of the matrix, then normalised.
//! - Lights: the skeleton leaves their code to the student ("YOUR CODE FOR
//!   HW 2 HERE") but supplies `matransform`, which "applies the appropriate
//!   transform to a 4-vector" (the light's position, w given in HW2's file),
//!   and the spec says "as in OpenGL", where a light's position is
//!   transformed by the matrix in force. So a `point` light's position is
//!   transformed as a point (w = 1) and a `directional` light's direction as
//!   a vector (w = 0, no translation). Students' tracers differ here (some
//!   copy lights untransformed); the course's scenes define their lights
//!   under the identity, where both agree.
//! - `attenuation` is a global state in the skeleton, never copied into an
//!   object. It is recorded twice: [`TestScene::attenuation`], the last value
//!   the file sets (what a tracer that reads the whole file before rendering
//!   uses), and each point light's [`TestLight::attenuation`], the value in
//!   force where it is defined (OpenGL's per-light reading). Directional
//!   lights are never attenuated. Which one the `cse167` profile uses is the
//!   profile's decision.
//!
//! # Where this reader is stricter than the course's
//!
//! The skeleton skips, with a message on the console, an unknown command or
//! one whose values fail to read, and ignores extra values. Here each is an
//! error at FILE:LINE:COL, like the NFF and TOML readers': a misspelt
//! `pushtransform` that is skipped silently moves every object after it, and
//! a debugger should say so rather than render something else. Also refused:
//! a command before `size` or a second `size`, a second `camera`, no camera,
//! a `tri` naming a vertex not yet defined, a vertex past `maxverts`, a
//! negative radius, and every number outside the ranges of `limits.rs`
//! (plus the `.test`-only ones there: scale factors, angles, composed
//! matrices, vertex counts, stack depth). A later `maxdepth` or `output`
//! replaces an earlier one, as in the course.
//!
//! # Left for the profile (issue 42)
//!
//! How `maxdepth` counts, the output name's default, degenerate triangles,
//! the lighting equation, and turning a [`TestScene`] into raystep's scene.

use std::ops::Range;
use std::path::Path;

use glam::{DMat3, DMat4, DVec3};

use super::limits::{
    ANGLE, ATTENUATION, Bounds, COLOR, COORDINATE, MAX_TEST_VERTICES, MAX_TRANSFORM_DEPTH, SCALE,
    SHININESS, SIZE, TRANSFORM_ENTRY, show,
};
use super::toml_format::MAX_DEPTH_LIMIT;
use super::{SceneError, check_camera, check_image_size};
use raystep_model::camera::Camera;
use raystep_model::math::exceeds;

#[cfg(test)]
mod parsing_tests;
mod to_scene;

pub(crate) use to_scene::to_scene;

/// The course's default recursion depth (its spec: "default 5").
pub const DEFAULT_MAXDEPTH: u32 = 5;
/// The course's default ambient colour.
pub const DEFAULT_AMBIENT: DVec3 = DVec3::splat(0.2);
/// The course's default attenuation: constant 1, no fall-off.
pub const DEFAULT_ATTENUATION: Attenuation = Attenuation {
    constant: 1.0,
    linear: 0.0,
    quadratic: 0.0,
};

/// The commands, as listed in messages.
const COMMANDS: &str = "size, maxdepth, output, camera, sphere, maxverts, maxvertnorms, vertex, \
vertexnormal, tri, trinormal, translate, rotate, scale, pushTransform, popTransform, directional, \
point, attenuation, ambient, diffuse, specular, shininess, emission";

/// A `.test` file as read: everything in world space, each part with the
/// 1-based line that made it.
#[derive(Clone, Debug, PartialEq)]
pub struct TestScene {
    /// Width and height in pixels.
    pub size: (u32, u32),
    pub size_line: usize,
    /// `maxdepth` as written (default [`DEFAULT_MAXDEPTH`]); what it counts
    /// is the profile's choice.
    pub maxdepth: u32,
    /// The `output` file name and its line, if any.
    pub output: Option<(String, usize)>,
    pub camera: TestCamera,
    pub objects: Vec<TestObject>,
    pub lights: Vec<TestLight>,
    /// The last `attenuation` the file sets (the course's global state) and
    /// its line; [`DEFAULT_ATTENUATION`] and `None` without one.
    pub attenuation: Attenuation,
    pub attenuation_line: Option<usize>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TestCamera {
    pub eye: DVec3,
    pub look_at: DVec3,
    pub up: DVec3,
    /// The vertical field of view, in degrees.
    pub fovy: f64,
    pub line: usize,
}

/// The material state in force when an object was made.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TestMaterial {
    pub ambient: DVec3,
    pub diffuse: DVec3,
    pub specular: DVec3,
    pub shininess: f64,
    pub emission: DVec3,
}

impl Default for TestMaterial {
    fn default() -> Self {
        Self {
            ambient: DEFAULT_AMBIENT,
            diffuse: DVec3::ZERO,
            specular: DVec3::ZERO,
            shininess: 0.0,
            emission: DVec3::ZERO,
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct TestObject {
    pub shape: TestShape,
    pub material: TestMaterial,
    pub line: usize,
}

#[derive(Clone, Debug, PartialEq)]
pub enum TestShape {
    /// A sphere in object space under `transform` (object to world); its
    /// world centre is `transform` applied to `center`.
    Sphere {
        center: DVec3,
        radius: f64,
        transform: DMat4,
        world_center: DVec3,
    },
    /// A triangle's world-space vertices, in the file's order.
    Triangle { vertices: [DVec3; 3] },
    /// A triangle with a unit world-space normal at each vertex.
    NormalTriangle {
        vertices: [DVec3; 3],
        normals: [DVec3; 3],
    },
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Attenuation {
    pub constant: f64,
    pub linear: f64,
    pub quadratic: f64,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TestLightKind {
    /// The world-space direction *to* the light (as transformed, not normalised).
    Directional { direction: DVec3 },
    /// The world-space position.
    Point { position: DVec3 },
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TestLight {
    pub kind: TestLightKind,
    pub color: DVec3,
    /// For a point light, the attenuation in force where it is defined;
    /// `None` for a directional light, which is never attenuated.
    pub attenuation: Option<Attenuation>,
    pub line: usize,
}

/// Parses `.test` text; `file` names it in messages.
pub fn parse(text: &str, file: &Path) -> Result<TestScene, SceneError> {
    let mut reader = Reader {
        path: file,
        text,
        state: State::default(),
    };
    let start = crate::input_file::byte_order_mark(text.as_bytes());
    let mut offset = start;
    for (index, raw) in text[start..].split_inclusive('\n').enumerate() {
        let line = tokens(raw, offset);
        offset += raw.len();
        if let Some((command, args)) = line.split_first() {
            reader.command(index + 1, *command, args)?;
        }
    }
    reader.finish()
}

/// One word of a line and its byte span in the file.
#[derive(Clone, Copy, Debug)]
struct Word<'a> {
    text: &'a str,
    start: usize,
}

impl Word<'_> {
    fn span(&self) -> Range<usize> {
        self.start..self.start + self.text.len()
    }
}

/// The words of `line` (which starts at byte `offset`), up to a `#`. Words
/// end at ASCII whitespace or `#`, so every span lies on character boundaries.
fn tokens(line: &str, offset: usize) -> Vec<Word<'_>> {
    let bytes = line.as_bytes();
    let mut words = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i].is_ascii_whitespace() {
            i += 1;
        } else if bytes[i] == b'#' {
            break;
        } else {
            let start = i;
            while i < bytes.len() && !bytes[i].is_ascii_whitespace() && bytes[i] != b'#' {
                i += 1;
            }
            words.push(Word {
                text: &line[start..i],
                start: offset + start,
            });
        }
    }
    words
}

/// What the file has said so far.
struct State {
    size: Option<((u32, u32), usize)>,
    maxdepth: u32,
    output: Option<(String, usize)>,
    camera: Option<TestCamera>,
    /// The transform stack; never empty, its top last.
    stack: Vec<DMat4>,
    material: TestMaterial,
    attenuation: Attenuation,
    attenuation_line: Option<usize>,
    /// The `vertex` pile, as given (object space).
    vertices: Vec<DVec3>,
    maxverts: Option<(usize, usize)>,
    /// The `vertexnormal` pile, as given.
    vertex_normals: Vec<(DVec3, DVec3)>,
    maxvertnorms: Option<(usize, usize)>,
    objects: Vec<TestObject>,
    lights: Vec<TestLight>,
}

impl Default for State {
    fn default() -> Self {
        Self {
            size: None,
            maxdepth: DEFAULT_MAXDEPTH,
            output: None,
            camera: None,
            stack: vec![DMat4::IDENTITY],
            material: TestMaterial::default(),
            attenuation: DEFAULT_ATTENUATION,
            attenuation_line: None,
            vertices: Vec::new(),
            maxverts: None,
            vertex_normals: Vec::new(),
            maxvertnorms: None,
            objects: Vec::new(),
            lights: Vec::new(),
        }
    }
}

const XYZ: [&str; 3] = ["x", "y", "z"];
const RGB: [&str; 3] = ["red", "green", "blue"];

struct Reader<'a> {
    path: &'a Path,
    text: &'a str,
    state: State,
}

impl Reader<'_> {
    fn error(&self, span: Range<usize>, message: impl Into<String>) -> SceneError {
        SceneError::at(self.path, self.text, span, message)
    }

    fn top(&self) -> DMat4 {
        *self.state.stack.last().expect("the stack is never empty")
    }

    fn command(&mut self, line: usize, command: Word, args: &[Word]) -> Result<(), SceneError> {
        let name = command.text;
        if !COMMANDS.split(", ").any(|c| c == name) {
            let hint = COMMANDS
                .split(", ")
                .find(|c| c.eq_ignore_ascii_case(name))
                .map(|c| format!(" (commands are case-sensitive: did you mean `{c}`?)"))
                .unwrap_or_default();
            let what = if name.parse::<f64>().is_ok() {
                format!("unexpected number `{name}` where a command was expected")
            } else {
                format!("unknown command `{name}`")
            };
            return Err(self.error(
                command.span(),
                format!("{what}: expected one of {COMMANDS}{hint}"),
            ));
        }
        match (&self.state.size, name) {
            (None, "size") => {}
            (None, _) => {
                return Err(self.error(
                    command.span(),
                    format!("`size` must be the first command, found `{name}` first"),
                ));
            }
            (Some((_, first)), "size") => {
                return Err(self.error(
                    command.span(),
                    format!("a second `size`: `size` comes once, first (it is on line {first})"),
                ));
            }
            _ => {}
        }
        match name {
            "size" => {
                let [w, h] = self.values(command, args, ["width", "height"])?;
                let width = self.integer(w, "the image width", u32::MAX as u64)? as u32;
                let height = self.integer(h, "the image height", u32::MAX as u64)? as u32;
                check_image_size(width, height)
                    .map_err(|e| self.error(w.start..h.span().end, e))?;
                self.state.size = Some(((width, height), line));
            }
            "maxdepth" => {
                let [n] = self.values(command, args, ["depth"])?;
                // Bounces: the primary ray and `maxdepth` more, at most
                // raystep's deepest tree (`to_scene`).
                let bounces = (MAX_DEPTH_LIMIT - 1) as u64;
                self.state.maxdepth = self.integer(n, "maxdepth (bounces)", bounces)? as u32;
            }
            "output" => {
                let [file] = self.values(command, args, ["file name"])?;
                self.state.output = Some((file.text.to_owned(), line));
            }
            "camera" => {
                if let Some(first) = &self.state.camera {
                    return Err(self.error(
                        command.span(),
                        format!(
                            "a second `camera`: a file has one (the first is on line {})",
                            first.line
                        ),
                    ));
                }
                let v: [Word; 10] = self.values(
                    command,
                    args,
                    [
                        "fromx", "fromy", "fromz", "atx", "aty", "atz", "upx", "upy", "upz", "fovy",
                    ],
                )?;
                let eye = self.vec3(&v[0..3], "the camera's eye", COORDINATE)?;
                let look_at = self.vec3(&v[3..6], "the camera's look-at point", COORDINATE)?;
                let up = self.vec3(&v[6..9], "the camera's up vector", COORDINATE)?;
                let fovy = self.number(v[9], "fovy")?;
                let camera = Camera {
                    eye,
                    look_at,
                    up,
                    fov: fovy,
                };
                check_camera(&camera).map_err(|e| self.error(command.span(), e))?;
                self.state.camera = Some(TestCamera {
                    eye,
                    look_at,
                    up,
                    fovy,
                    line,
                });
            }
            "sphere" => {
                let v: [Word; 4] = self.values(command, args, ["x", "y", "z", "radius"])?;
                let center = self.vec3(&v[0..3], "the sphere's centre", COORDINATE)?;
                let radius = self.number(v[3], "the sphere's radius")?;
                if radius < 0.0 {
                    return Err(self.error(
                        v[3].span(),
                        format!("the sphere's radius is negative ({})", v[3].text),
                    ));
                }
                self.within(v[3], radius, "the sphere's radius", SIZE)?;
                let transform = self.top();
                let world_center = transform.transform_point3(center);
                self.check_point(command, world_center, "the sphere's world centre")?;
                let linear = DMat3::from_mat4(transform);
                let longest = [linear.x_axis, linear.y_axis, linear.z_axis]
                    .iter()
                    .map(|a| a.length())
                    .fold(0.0, f64::max)
                    * radius;
                let mean = linear.determinant().abs().cbrt() * radius;
                if !(SIZE.check(longest).is_ok() && SIZE.check(mean).is_ok()) {
                    return Err(self.error(
                        command.span(),
                        format!(
                            "the sphere under the current transform is out of range: its longest axis is {} and its mean radius {}; both {}",
                            show(longest),
                            show(mean),
                            SIZE.check(f64::NAN).unwrap_err()
                        ),
                    ));
                }
                self.add(
                    line,
                    TestShape::Sphere {
                        center,
                        radius,
                        transform,
                        world_center,
                    },
                );
            }
            "maxverts" | "maxvertnorms" => {
                let [n] = self.values(command, args, ["count"])?;
                let count = self.integer(n, name, MAX_TEST_VERTICES as u64)? as usize;
                let defined = if name == "maxverts" {
                    self.state.vertices.len()
                } else {
                    self.state.vertex_normals.len()
                };
                if count < defined {
                    return Err(self.error(
                        n.span(),
                        format!("`{name} {count}` but {defined} are already defined"),
                    ));
                }
                if name == "maxverts" {
                    self.state.maxverts = Some((count, line));
                } else {
                    self.state.maxvertnorms = Some((count, line));
                }
            }
            "vertex" => {
                let v: [Word; 3] = self.values(command, args, XYZ)?;
                self.check_room(
                    command,
                    self.state.vertices.len(),
                    self.state.maxverts,
                    "maxverts",
                )?;
                let p = self.vec3(&v, "the vertex", COORDINATE)?;
                self.state.vertices.push(p);
            }
            "vertexnormal" => {
                let v: [Word; 6] = self.values(command, args, ["x", "y", "z", "nx", "ny", "nz"])?;
                self.check_room(
                    command,
                    self.state.vertex_normals.len(),
                    self.state.maxvertnorms,
                    "maxvertnorms",
                )?;
                let p = self.vec3(&v[0..3], "the vertex", COORDINATE)?;
                let n = self.vec3(&v[3..6], "the normal", COORDINATE)?;
                if !exceeds(n.length(), 0.0) {
                    return Err(self.error(v[3].start..v[5].span().end, "the normal is zero"));
                }
                self.state.vertex_normals.push((p, n));
            }
            "tri" => {
                let v: [Word; 3] = self.values(command, args, ["i", "j", "k"])?;
                let m = self.top();
                let mut vertices = [DVec3::ZERO; 3];
                for (slot, word) in vertices.iter_mut().zip(v) {
                    let i = self.index(word, self.state.vertices.len(), "vertex")?;
                    *slot = m.transform_point3(self.state.vertices[i]);
                    self.check_point(word, *slot, "the vertex in world space")?;
                }
                self.add(line, TestShape::Triangle { vertices });
            }
            "trinormal" => {
                let v: [Word; 3] = self.values(command, args, ["i", "j", "k"])?;
                let m = self.top();
                let linear = DMat3::from_mat4(m);
                let det = linear.determinant();
                if !(det.is_finite() && exceeds(det.abs(), 0.0)) {
                    return Err(self.error(
                        command.span(),
                        "the normals cannot be transformed: the current transform is singular",
                    ));
                }
                let normal_matrix = linear.inverse().transpose();
                let mut vertices = [DVec3::ZERO; 3];
                let mut normals = [DVec3::ZERO; 3];
                for (i, word) in v.iter().enumerate() {
                    let index =
                        self.index(*word, self.state.vertex_normals.len(), "vertexnormal")?;
                    let (p, n) = self.state.vertex_normals[index];
                    vertices[i] = m.transform_point3(p);
                    self.check_point(*word, vertices[i], "the vertex in world space")?;
                    let n = normal_matrix * n;
                    if !(n.is_finite() && n.length() > 0.0) {
                        return Err(self.error(
                            word.span(),
                            "the normal cannot be transformed: the current transform is singular",
                        ));
                    }
                    normals[i] = n.normalize();
                }
                self.add(line, TestShape::NormalTriangle { vertices, normals });
            }
            "translate" => {
                let v: [Word; 3] = self.values(command, args, XYZ)?;
                let t = self.vec3(&v, "the translation", COORDINATE)?;
                self.right_multiply(command, DMat4::from_translation(t))?;
            }
            "scale" => {
                let v: [Word; 3] = self.values(command, args, XYZ)?;
                let mut s = DVec3::ZERO;
                for (i, word) in v.iter().enumerate() {
                    let value = self.number(*word, &format!("the scale factor ({})", XYZ[i]))?;
                    SCALE.check(value.abs()).map_err(|reason| {
                        self.error(
                            word.span(),
                            format!(
                                "the scale factor ({}) {reason} in absolute value (a negative factor mirrors), got `{}`",
                                XYZ[i], word.text
                            ),
                        )
                    })?;
                    s[i] = value;
                }
                self.right_multiply(command, DMat4::from_scale(s))?;
            }
            "rotate" => {
                let v: [Word; 4] = self.values(command, args, ["ax", "ay", "az", "degrees"])?;
                let axis = self.vec3(&v[0..3], "the rotation axis", COORDINATE)?;
                if !exceeds(axis.length(), 0.0) {
                    return Err(
                        self.error(v[0].start..v[2].span().end, "the rotation axis is zero")
                    );
                }
                let degrees = self.number(v[3], "the rotation angle")?;
                self.within(v[3], degrees, "the rotation angle (degrees)", ANGLE)?;
                let r = DMat4::from_axis_angle(axis.normalize(), degrees.to_radians());
                self.right_multiply(command, r)?;
            }
            "pushTransform" => {
                self.values::<0>(command, args, [])?;
                if self.state.stack.len() > MAX_TRANSFORM_DEPTH {
                    return Err(self.error(
                        command.span(),
                        format!("more than {MAX_TRANSFORM_DEPTH} nested `pushTransform`s"),
                    ));
                }
                self.state.stack.push(self.top());
            }
            "popTransform" => {
                self.values::<0>(command, args, [])?;
                if self.state.stack.len() <= 1 {
                    return Err(self.error(
                        command.span(),
                        "`popTransform` with no `pushTransform` to undo: the stack holds only the initial identity",
                    ));
                }
                self.state.stack.pop();
            }
            "directional" | "point" => {
                let v: [Word; 6] = self.values(command, args, ["x", "y", "z", "r", "g", "b"])?;
                let m = self.top();
                let color = self.vec3(&v[3..6], "the light's colour", COLOR)?;
                let (kind, attenuation) = if name == "directional" {
                    let d = self.vec3(&v[0..3], "the direction to the light", COORDINATE)?;
                    let direction = m.transform_vector3(d);
                    if !exceeds(direction.length(), 0.0) {
                        return Err(self.error(
                            v[0].start..v[2].span().end,
                            "the direction to the light is zero",
                        ));
                    }
                    (TestLightKind::Directional { direction }, None)
                } else {
                    let p = self.vec3(&v[0..3], "the light's position", COORDINATE)?;
                    let position = m.transform_point3(p);
                    self.check_point(command, position, "the light's world position")?;
                    (
                        TestLightKind::Point { position },
                        Some(self.state.attenuation),
                    )
                };
                self.state.lights.push(TestLight {
                    kind,
                    color,
                    attenuation,
                    line,
                });
            }
            "attenuation" => {
                let v: [Word; 3] =
                    self.values(command, args, ["constant", "linear", "quadratic"])?;
                let c = self.vec3(&v, "the attenuation", ATTENUATION)?;
                if c == DVec3::ZERO {
                    return Err(self.error(
                        v[0].start..v[2].span().end,
                        "attenuation 0 0 0 divides by zero at every distance: at least one coefficient must be positive",
                    ));
                }
                self.state.attenuation = Attenuation {
                    constant: c.x,
                    linear: c.y,
                    quadratic: c.z,
                };
                self.state.attenuation_line = Some(line);
            }
            "ambient" | "diffuse" | "specular" | "emission" => {
                let v: [Word; 3] = self.values(command, args, RGB)?;
                let c = self.vec3(&v, &format!("the {name} colour"), COLOR)?;
                let m = &mut self.state.material;
                *match name {
                    "ambient" => &mut m.ambient,
                    "diffuse" => &mut m.diffuse,
                    "specular" => &mut m.specular,
                    _ => &mut m.emission,
                } = c;
            }
            "shininess" => {
                let [s] = self.values(command, args, ["s"])?;
                let value = self.number(s, "the shininess")?;
                self.within(s, value, "the shininess", SHININESS)?;
                self.state.material.shininess = value;
            }
            _ => unreachable!("every command in COMMANDS is handled"),
        }
        Ok(())
    }

    fn add(&mut self, line: usize, shape: TestShape) {
        self.state.objects.push(TestObject {
            shape,
            material: self.state.material,
            line,
        });
    }

    /// Exactly `N` values after `command`, named by `names` in messages.
    fn values<'w, const N: usize>(
        &self,
        command: Word,
        args: &[Word<'w>],
        names: [&str; N],
    ) -> Result<[Word<'w>; N], SceneError> {
        let takes = if N == 0 {
            "takes no values".to_owned()
        } else {
            format!(
                "takes {N} value{} ({})",
                if N == 1 { "" } else { "s" },
                names.join(" ")
            )
        };
        if args.len() > N {
            let extra = &args[N];
            return Err(self.error(
                extra.start..args[args.len() - 1].span().end,
                format!(
                    "`{}` {takes}, found {}: `{}` is one too many",
                    command.text,
                    args.len(),
                    extra.text
                ),
            ));
        }
        if args.len() < N {
            let end = args.last().unwrap_or(&command).span().end;
            return Err(self.error(
                end..end,
                format!(
                    "`{}` {takes}, found {}: {} is missing",
                    command.text,
                    args.len(),
                    names[args.len()]
                ),
            ));
        }
        Ok(std::array::from_fn(|i| args[i]))
    }

    /// A finite number.
    fn number(&self, word: Word, what: &str) -> Result<f64, SceneError> {
        match word.text.parse::<f64>() {
            Ok(value) if value.is_finite() => Ok(value),
            Ok(_) => Err(self.error(
                word.span(),
                format!("{what} must be a finite number, got `{}`", word.text),
            )),
            Err(_) => Err(self.error(
                word.span(),
                format!("expected a number for {what}, found `{}`", word.text),
            )),
        }
    }

    fn within(&self, word: Word, value: f64, what: &str, bounds: Bounds) -> Result<(), SceneError> {
        bounds.check(value).map_err(|reason| {
            self.error(word.span(), format!("{what} {reason}, got `{}`", word.text))
        })
    }

    /// Three numbers within `bounds`.
    fn vec3(&self, words: &[Word], what: &str, bounds: Bounds) -> Result<DVec3, SceneError> {
        let names = if what.contains("colour") {
            RGB
        } else if what.contains("attenuation") {
            ["c0", "c1", "c2"]
        } else {
            XYZ
        };
        let mut v = DVec3::ZERO;
        for (i, word) in words.iter().enumerate() {
            let what = format!("{what} ({})", names[i]);
            v[i] = self.number(*word, &what)?;
            self.within(*word, v[i], &what, bounds)?;
        }
        Ok(v)
    }

    /// A whole number from 0 to `max`.
    fn integer(&self, word: Word, what: &str, max: u64) -> Result<u64, SceneError> {
        let value = self.number(word, what)?;
        if value.fract() != 0.0 || value < 0.0 || value > max as f64 {
            return Err(self.error(
                word.span(),
                format!(
                    "{what} must be a whole number from 0 to {max}, got `{}`",
                    word.text
                ),
            ));
        }
        Ok(value as u64)
    }

    /// An index into a pile of `len` entries made by `maker` commands.
    fn index(&self, word: Word, len: usize, maker: &str) -> Result<usize, SceneError> {
        let value = self.number(word, &format!("a {maker} index"))?;
        if value.fract() != 0.0 || value < 0.0 {
            return Err(self.error(
                word.span(),
                format!(
                    "a {maker} index must be a whole number from 0, got `{}`",
                    word.text
                ),
            ));
        }
        if value >= len as f64 {
            let defined = match len {
                0 => format!("no `{maker}` is defined yet"),
                1 => format!("only `{maker}` 0 is defined so far"),
                n => format!("`{maker}`s 0 to {} are defined so far", n - 1),
            };
            return Err(self.error(
                word.span(),
                format!("{maker} {} is not defined yet: {defined}", word.text),
            ));
        }
        Ok(value as usize)
    }

    /// Room for one more entry in a pile of `len`, under a declared maximum.
    fn check_room(
        &self,
        command: Word,
        len: usize,
        declared: Option<(usize, usize)>,
        declarer: &str,
    ) -> Result<(), SceneError> {
        match declared {
            Some((max, line)) if len >= max => Err(self.error(
                command.span(),
                format!(
                    "`{}` number {len} is past `{declarer} {max}` (line {line}): {declarer} counts them all",
                    command.text
                ),
            )),
            _ if len >= MAX_TEST_VERTICES => Err(self.error(
                command.span(),
                format!("more than {MAX_TEST_VERTICES} `{}`s", command.text),
            )),
            _ => Ok(()),
        }
    }

    /// A world-space point within the coordinate range.
    fn check_point(&self, word: Word, point: DVec3, what: &str) -> Result<(), SceneError> {
        for (i, value) in point.to_array().into_iter().enumerate() {
            COORDINATE.check(value).map_err(|reason| {
                self.error(
                    word.span(),
                    format!(
                        "{what} ({}) is {}; under the current transform it {reason}",
                        XYZ[i],
                        show(value)
                    ),
                )
            })?;
        }
        Ok(())
    }

    /// `top = top * m`, as the course's `rightmultiply`.
    fn right_multiply(&mut self, command: Word, m: DMat4) -> Result<(), SceneError> {
        let product = self.top() * m;
        if let Some(bad) = product
            .to_cols_array()
            .into_iter()
            .find(|e| TRANSFORM_ENTRY.check(*e).is_err())
        {
            return Err(self.error(
                command.span(),
                format!(
                    "the composed transform has an entry of {}: every entry {}",
                    show(bad),
                    TRANSFORM_ENTRY.check(f64::NAN).unwrap_err()
                ),
            ));
        }
        *self
            .state
            .stack
            .last_mut()
            .expect("the stack is never empty") = product;
        Ok(())
    }

    fn finish(self) -> Result<TestScene, SceneError> {
        let Some((size, size_line)) = self.state.size else {
            return Err(self.error(
                0..0,
                "the file has no `size`: a .test file starts with `size width height`",
            ));
        };
        let Some(camera) = self.state.camera else {
            let end = self.text.len();
            return Err(self.error(
                end..end,
                "the file has no `camera` (from x y z, at x y z, up x y z, fovy)",
            ));
        };
        let state = self.state;
        Ok(TestScene {
            size,
            size_line,
            maxdepth: state.maxdepth,
            output: state.output,
            camera,
            objects: state.objects,
            lights: state.lights,
            attenuation: state.attenuation,
            attenuation_line: state.attenuation_line,
        })
    }
}
