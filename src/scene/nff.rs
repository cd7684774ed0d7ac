//! Import of Eric Haines's Neutral File Format (NFF) as written by the SPD
//! generators (MODEL §2 and §4, `spd/README.md`).
//!
//! The file is read as a stream of whitespace-separated tokens, each with its
//! byte span, so that every error names its line and column and a `c` entity
//! may hold its eight numbers on one line or on three. `#` starts a comment
//! that runs to the end of the line.
//!
//! Entities: `v` (followed by `from x y z`, `at x y z`, `up x y z`, `angle a`,
//! `hither h`, `resolution w h`), `b r g b`, `l x y z [r g b]`,
//! `f r g b Kd Ks Shine T ior`, `c bx by bz br ax ay az ar`, `s x y z r`,
//! `p n` + n vertices, `pp n` + n vertices each followed by its normal.

use std::ops::Range;
use std::path::Path;

use glam::DVec3;

use super::{
    Light, Material, Object, SceneDescription, SceneError, Settings, check_camera, check_image_size,
};
use crate::camera::Camera;
use crate::math::Color;
use crate::shapes::{Cone, GeometryError, Patch, Polygon, Shape, Sphere};

/// The entity keywords, as listed in messages.
const ENTITIES: &str = "v, b, l, f, c, s, p, pp";
const XYZ: [&str; 3] = ["x", "y", "z"];
const RGB: [&str; 3] = ["red", "green", "blue"];
/// Vertex lists are preallocated up to this many vertices; a larger count in
/// the file is trusted only as far as the file actually holds vertices.
const MAX_PREALLOCATED_VERTICES: usize = 4096;

/// Parses NFF text; `path` names it in messages.
pub fn parse(path: &Path, text: &str) -> Result<SceneDescription, SceneError> {
    let mut parser = Parser::new(path, text);
    let mut scene = Builder::default();
    while let Some(keyword) = parser.next() {
        match keyword.text {
            "v" => {
                if let Some(first) = &scene.view {
                    let line = text[..first.keyword.start].matches('\n').count() + 1;
                    return Err(parser.error(
                        keyword.span(),
                        format!("a second viewpoint `v`: a file has exactly one (the first is on line {line})"),
                    ));
                }
                scene.view = Some(parser.view(keyword)?);
            }
            "b" => scene.background = parser.vec3(RGB, |c| format!("the background's {c}"))?,
            "l" => {
                let position = parser.vec3(XYZ, |c| format!("the light's position ({c})"))?;
                let color = if parser.peek().is_some_and(|t| t.text.parse::<f64>().is_ok()) {
                    let red = parser.non_negative(|| "the light's colour (red)".into())?;
                    let green = parser.non_negative(|| "the light's colour (green)".into())?;
                    let blue = parser.non_negative(|| "the light's colour (blue)".into())?;
                    Some(Color::new(red, green, blue))
                } else {
                    None
                };
                scene.lights.push((position, color));
            }
            "f" => {
                let material = parser.material(scene.f_lines)?;
                scene.f_lines += 1;
                scene.materials.push(material);
                scene.current_material = Some(scene.materials.len() - 1);
            }
            "s" => {
                let center = parser.vec3(XYZ, |c| format!("the sphere's centre ({c})"))?;
                let radius = parser.number(|| "the sphere's radius".into())?;
                let shape = Sphere::new(center, radius.abs()).map(Shape::Sphere);
                scene.add(&parser, &keyword, "sphere", shape)?;
            }
            "c" => {
                let base = parser.vec3(XYZ, |c| format!("the cone's base ({c})"))?;
                let base_radius = parser.number(|| "the cone's base radius".into())?.abs();
                let apex = parser.vec3(XYZ, |c| format!("the cone's apex ({c})"))?;
                let apex_radius = parser.number(|| "the cone's apex radius".into())?.abs();
                let kind = if base_radius == apex_radius {
                    "cylinder"
                } else {
                    "cone"
                };
                let shape = Cone::new(base, base_radius, apex, apex_radius).map(Shape::Cone);
                scene.add(&parser, &keyword, kind, shape)?;
            }
            "p" => {
                let count = parser.count("the polygon's vertex count")?;
                let mut vertices = Vec::with_capacity(count.min(MAX_PREALLOCATED_VERTICES));
                for i in 0..count {
                    vertices.push(parser.vec3(XYZ, |c| format!("the polygon's vertex {i} ({c})"))?);
                }
                let shape = Polygon::new(vertices).map(Shape::Polygon);
                scene.add(&parser, &keyword, "polygon", shape)?;
            }
            "pp" => {
                let count = parser.count("the patch's vertex count")?;
                let mut vertices = Vec::with_capacity(count.min(MAX_PREALLOCATED_VERTICES));
                let mut normals = Vec::with_capacity(count.min(MAX_PREALLOCATED_VERTICES));
                for i in 0..count {
                    vertices.push(parser.vec3(XYZ, |c| format!("the patch's vertex {i} ({c})"))?);
                    normals.push(parser.vec3(XYZ, |c| format!("the patch's normal {i} ({c})"))?);
                }
                let shape = Patch::new(vertices, normals).map(Shape::Patch);
                scene.add(&parser, &keyword, "patch", shape)?;
            }
            other if other.parse::<f64>().is_ok() => {
                return Err(parser.error(
                    keyword.span(),
                    format!("unexpected number `{other}`: expected an entity keyword ({ENTITIES})"),
                ));
            }
            other => {
                let hint = if VIEW_KEYWORDS.contains(&other) {
                    format!(" (`{other}` belongs to a viewpoint and must follow a `v`)")
                } else {
                    String::new()
                };
                return Err(parser.error(
                    keyword.span(),
                    format!(
                        "unknown entity `{other}`: expected an entity keyword ({ENTITIES}){hint}"
                    ),
                ));
            }
        }
    }
    scene.finish(&parser)
}

/// The camera's edge-to-edge vertical field of view for NFF's `angle`, which
/// is measured between the centres of the top and bottom pixel rows of an
/// image `height` pixels high: tan(fov / 2) = tan(angle / 2) H / (H - 1)
/// (MODEL §2). With one row there is no second centre: the angle is kept.
fn fov_from_angle(angle: f64, height: u32) -> f64 {
    if height <= 1 {
        return angle;
    }
    let h = height as f64;
    2.0 * ((angle.to_radians() / 2.0).tan() * h / (h - 1.0))
        .atan()
        .to_degrees()
}

const VIEW_KEYWORDS: [&str; 6] = ["from", "at", "up", "angle", "hither", "resolution"];

/// One whitespace-separated word of the file and where it starts.
#[derive(Clone, Copy, Debug)]
struct Token<'a> {
    text: &'a str,
    start: usize,
}

impl Token<'_> {
    fn span(&self) -> Range<usize> {
        self.start..self.start + self.text.len()
    }
}

/// A viewpoint `v` as read, before it becomes a camera.
struct View {
    keyword: Range<usize>,
    from: Option<DVec3>,
    at: Option<DVec3>,
    up: Option<DVec3>,
    angle: Option<f64>,
    resolution: Option<(u32, u32, Range<usize>)>,
}

/// What the file has said so far.
#[derive(Default)]
struct Builder {
    view: Option<View>,
    background: Color,
    /// Positions and colours; a light without colour gets its colour at the end.
    lights: Vec<(DVec3, Option<Color>)>,
    materials: Vec<Material>,
    /// How many `f` lines have been read (materials are named after it).
    f_lines: usize,
    /// The material of the next object; `None` before the first `f` line.
    current_material: Option<usize>,
    /// Where the default white material is, once an object has used it.
    default_material: Option<usize>,
    objects: Vec<Object>,
}

impl Builder {
    /// Adds an object named after its kind and index, or reports its geometry
    /// error at the entity's keyword.
    fn add(
        &mut self,
        parser: &Parser,
        keyword: &Token,
        kind: &str,
        shape: Result<Shape, GeometryError>,
    ) -> Result<(), SceneError> {
        let index = self.objects.len();
        let shape = shape.map_err(|GeometryError(e)| {
            parser.error(keyword.span(), format!("{kind} {index}: {e}"))
        })?;
        let material = match self.current_material {
            Some(m) => m,
            None => *self.default_material.get_or_insert_with(|| {
                self.materials.push(Material::default_white());
                self.materials.len() - 1
            }),
        };
        self.objects.push(Object {
            name: format!("{} {index}", shape.kind()),
            shape,
            material,
        });
        Ok(())
    }

    fn finish(self, parser: &Parser) -> Result<SceneDescription, SceneError> {
        let Some(view) = self.view else {
            return Err(parser.error(
                0..0,
                "the file has no viewpoint `v`: an NFF file must have exactly one",
            ));
        };
        let missing = |what: &str| {
            parser.error(
                view.keyword.clone(),
                format!("the viewpoint `v` has no `{what}`"),
            )
        };
        let eye = view.from.ok_or_else(|| missing("from"))?;
        let look_at = view.at.ok_or_else(|| missing("at"))?;
        let up = view.up.ok_or_else(|| missing("up"))?;
        let angle = view.angle.ok_or_else(|| missing("angle"))?;
        let (width, height, resolution) = view.resolution.ok_or_else(|| missing("resolution"))?;
        check_image_size(width, height).map_err(|e| parser.error(resolution, e))?;
        let camera = Camera {
            eye,
            look_at,
            up,
            fov: fov_from_angle(angle, height),
        };
        check_camera(&camera).map_err(|e| parser.error(view.keyword.clone(), e))?;

        // The SPD convention (MODEL §4): n lights share sqrt(n) / (2 n) grey
        // as the ambient light and as the colour of every light given without one.
        let n = self.lights.len();
        let grey = if n == 0 {
            Color::ZERO
        } else {
            Color::splat((n as f64).sqrt() / (2.0 * n as f64))
        };
        let lights = self
            .lights
            .into_iter()
            .enumerate()
            .map(|(i, (position, color))| Light {
                name: format!("light {i}"),
                position,
                color: color.unwrap_or(grey),
            })
            .collect();
        Ok(SceneDescription {
            camera,
            width,
            height,
            settings: Settings {
                background: self.background,
                ambient: grey,
                ..Settings::default()
            },
            materials: self.materials,
            lights,
            objects: self.objects,
        })
    }
}

/// A hand-written tokenizer over the text, with the readers of each entity's parts.
struct Parser<'a> {
    path: &'a Path,
    text: &'a str,
    pos: usize,
    /// The end of the last token read: where "end of the file" errors point.
    last_end: usize,
}

impl<'a> Parser<'a> {
    fn new(path: &'a Path, text: &'a str) -> Self {
        let pos = if text.starts_with('\u{feff}') {
            '\u{feff}'.len_utf8()
        } else {
            0
        };
        Self {
            path,
            text,
            pos,
            last_end: pos,
        }
    }

    fn error(&self, span: Range<usize>, message: impl Into<String>) -> SceneError {
        SceneError::at(self.path, self.text, span, message)
    }

    /// The next token, without consuming it. Tokens end at ASCII whitespace or
    /// `#`, so every span lies on character boundaries.
    fn peek(&mut self) -> Option<Token<'a>> {
        let bytes = self.text.as_bytes();
        loop {
            while self.pos < bytes.len() && bytes[self.pos].is_ascii_whitespace() {
                self.pos += 1;
            }
            if self.pos < bytes.len() && bytes[self.pos] == b'#' {
                while self.pos < bytes.len() && bytes[self.pos] != b'\n' {
                    self.pos += 1;
                }
            } else {
                break;
            }
        }
        let start = self.pos;
        let mut end = start;
        while end < bytes.len() && !bytes[end].is_ascii_whitespace() && bytes[end] != b'#' {
            end += 1;
        }
        (end > start).then(|| Token {
            text: &self.text[start..end],
            start,
        })
    }

    fn next(&mut self) -> Option<Token<'a>> {
        let token = self.peek()?;
        self.pos = token.start + token.text.len();
        self.last_end = self.pos;
        Some(token)
    }

    /// The next token as a finite number; `what` names it in messages.
    fn number_token(
        &mut self,
        what: impl FnOnce() -> String,
    ) -> Result<(f64, Token<'a>), SceneError> {
        let Some(token) = self.next() else {
            let end = self.last_end;
            return Err(self.error(
                end..end,
                format!(
                    "expected a number for {}, found the end of the file",
                    what()
                ),
            ));
        };
        match token.text.parse::<f64>() {
            Ok(value) if value.is_finite() => Ok((value, token)),
            Ok(_) => Err(self.error(
                token.span(),
                format!("{} must be a finite number, got `{}`", what(), token.text),
            )),
            Err(_) => Err(self.error(
                token.span(),
                format!("expected a number for {}, found `{}`", what(), token.text),
            )),
        }
    }

    fn number(&mut self, what: impl FnOnce() -> String) -> Result<f64, SceneError> {
        Ok(self.number_token(what)?.0)
    }

    /// A finite number >= 0 (colours and material coefficients).
    fn non_negative(&mut self, what: impl Fn() -> String) -> Result<f64, SceneError> {
        let (value, token) = self.number_token(&what)?;
        if value < 0.0 {
            return Err(self.error(
                token.span(),
                format!("{} must be >= 0, got `{}`", what(), token.text),
            ));
        }
        Ok(value)
    }

    /// Three numbers; `what` names each by its component name.
    fn vec3(
        &mut self,
        names: [&str; 3],
        what: impl Fn(&str) -> String,
    ) -> Result<DVec3, SceneError> {
        let x = self.number(|| what(names[0]))?;
        let y = self.number(|| what(names[1]))?;
        let z = self.number(|| what(names[2]))?;
        Ok(DVec3::new(x, y, z))
    }

    /// A `p`/`pp` vertex count: a positive integer.
    fn count(&mut self, what: &str) -> Result<usize, SceneError> {
        let (_, token) = self.number_token(|| what.to_string())?;
        match token.text.parse::<usize>() {
            Ok(count) if count > 0 => Ok(count),
            // Too large to hold: the vertices will run out first and say so.
            Err(_) if token.text.bytes().all(|b| b.is_ascii_digit()) => Ok(usize::MAX),
            _ => Err(self.error(
                token.span(),
                format!("{what} must be a positive integer, got `{}`", token.text),
            )),
        }
    }

    /// A side of the image in pixels: a whole number (its range is checked later).
    fn pixels(&mut self, what: &str) -> Result<u32, SceneError> {
        let (value, token) = self.number_token(|| what.to_string())?;
        if value.fract() != 0.0 || !(0.0..=u32::MAX as f64).contains(&value) {
            return Err(self.error(
                token.span(),
                format!(
                    "{what} must be a whole number of pixels, got `{}`",
                    token.text
                ),
            ));
        }
        Ok(value as u32)
    }

    /// The viewpoint's keyword groups after `v`, in any order, each at most once.
    fn view(&mut self, keyword: Token) -> Result<View, SceneError> {
        let mut view = View {
            keyword: keyword.span(),
            from: None,
            at: None,
            up: None,
            angle: None,
            resolution: None,
        };
        let mut hither = false;
        while let Some(token) = self.peek() {
            let given = match token.text {
                "from" => view.from.is_some(),
                "at" => view.at.is_some(),
                "up" => view.up.is_some(),
                "angle" => view.angle.is_some(),
                "hither" => hither,
                "resolution" => view.resolution.is_some(),
                _ => break,
            };
            if given {
                return Err(self.error(
                    token.span(),
                    format!("the viewpoint gives `{}` twice", token.text),
                ));
            }
            self.next();
            match token.text {
                "from" => {
                    view.from = Some(self.vec3(XYZ, |c| format!("the viewpoint's `from` ({c})"))?)
                }
                "at" => view.at = Some(self.vec3(XYZ, |c| format!("the viewpoint's `at` ({c})"))?),
                "up" => view.up = Some(self.vec3(XYZ, |c| format!("the viewpoint's `up` ({c})"))?),
                "angle" => {
                    let (angle, token) = self.number_token(|| "the viewpoint's `angle`".into())?;
                    if angle <= 0.0 || angle >= 180.0 {
                        return Err(self.error(
                            token.span(),
                            format!("the viewpoint's `angle` must be between 0 and 180 degrees (exclusive), got {angle}"),
                        ));
                    }
                    view.angle = Some(angle);
                }
                "hither" => {
                    // Read and ignored (MODEL §2).
                    self.number(|| "the viewpoint's `hither`".into())?;
                    hither = true;
                }
                _ => {
                    let width = self.pixels("the viewpoint's resolution width")?;
                    let height = self.pixels("the viewpoint's resolution height")?;
                    view.resolution = Some((width, height, token.start..self.last_end));
                }
            }
        }
        Ok(view)
    }

    /// `f r g b Kd Ks Shine T ior`, the `index`-th `f` line.
    fn material(&mut self, index: usize) -> Result<Material, SceneError> {
        let red = self.non_negative(|| "the material's colour (red)".into())?;
        let green = self.non_negative(|| "the material's colour (green)".into())?;
        let blue = self.non_negative(|| "the material's colour (blue)".into())?;
        let color = Color::new(red, green, blue);
        let kd = self.non_negative(|| "the material's Kd".into())?;
        let ks = self.non_negative(|| "the material's Ks".into())?;
        let shininess = self.non_negative(|| "the material's Shine".into())?;
        let (kt, kt_token) = self.number_token(|| "the material's T".into())?;
        if !(0.0..=1.0).contains(&kt) {
            return Err(self.error(
                kt_token.span(),
                format!(
                    "the material's T must be between 0 and 1, got `{}`",
                    kt_token.text
                ),
            ));
        }
        let (ior, ior_token) = self.number_token(|| "the material's index of refraction".into())?;
        let ior = if kt > 0.0 {
            if ior <= 0.0 {
                return Err(self.error(
                    ior_token.span(),
                    format!(
                        "f {index}: a transmitting material (T = {kt}) needs an index of refraction > 0, got {ior}"
                    ),
                ));
            }
            ior
        } else if ior <= 0.0 {
            // Opaque: the SPD writes ior 0, which means nothing; store air's.
            1.0
        } else {
            ior
        };
        Ok(Material {
            name: format!("f {index}"),
            color,
            kd,
            ks,
            shininess,
            kt,
            ior,
            ka: 1.0,
            specular: None,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_str(text: &str) -> Result<SceneDescription, SceneError> {
        parse(Path::new("t.nff"), text)
    }

    /// The (line, column) and message of the error `text` gives.
    fn error_of(text: &str) -> (usize, usize, String) {
        let error = parse_str(text).expect_err("the text should be refused");
        let at = error
            .location
            .as_ref()
            .expect("every NFF error has a location");
        (at.line, at.column, error.message.clone())
    }

    const VIEW: &str =
        "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 512 512\n";

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * b.abs().max(1.0)
    }

    #[test]
    fn tiny_scene_with_every_entity() {
        let text = "\
b 0.1 0.2 0.3
v
from 1 2 3
at 0 0 0
up 0 0 1
angle 90
hither 0.01
resolution 4 3
l 10 0 0
l 0 10 0 0.5 0.25 1
s 0 0 0 -2
f 1 0 0 0.7 0.3 20 0.5 1.5
c 0 0 0 1 0 0 2 1
c 0 0 0 1
  1 0 0 0.5
p 3
0 0 0
1 0 0
0 1 0
f 0 1 0 1 0 100000 0 0
pp 3
0 0 0 0 0 1
1 0 0 0 0 2
0 1 0 0 0 1
";
        let scene = parse_str(text).unwrap();
        assert_eq!((scene.width, scene.height), (4, 3));
        assert_eq!(scene.settings.background, Color::new(0.1, 0.2, 0.3));
        assert_eq!(scene.camera.eye, DVec3::new(1.0, 2.0, 3.0));
        assert_eq!(scene.camera.look_at, DVec3::ZERO);
        assert_eq!(scene.camera.up, DVec3::Z);
        // angle 90 at H = 3: tan(fov/2) = tan 45 * 3/2 = 1.5, fov = 2 atan 1.5
        // = 2 * 56.309932474020215 = 112.61986494804043 degrees.
        assert!(
            close(scene.camera.fov, 112.61986494804043),
            "{}",
            scene.camera.fov
        );
        assert_eq!(scene.settings.max_depth, 5);
        assert_eq!(scene.settings.light_attenuation, [1.0, 0.0, 0.0]);

        // Two lights: I_a = sqrt 2 / 4 = 0.35355339059327373 grey.
        let grey = 2f64.sqrt() / 4.0;
        assert!(close(grey, 0.35355339059327373));
        assert_eq!(scene.settings.ambient, Color::splat(grey));
        assert_eq!(scene.lights.len(), 2);
        assert_eq!(scene.lights[0].name, "light 0");
        assert_eq!(scene.lights[0].position, DVec3::new(10.0, 0.0, 0.0));
        assert_eq!(scene.lights[0].color, Color::splat(grey));
        assert_eq!(scene.lights[1].name, "light 1");
        assert_eq!(scene.lights[1].color, Color::new(0.5, 0.25, 1.0));

        // The sphere comes before the first `f`: it gets the default white,
        // which is then the first material.
        let names: Vec<_> = scene.materials.iter().map(|m| m.name.as_str()).collect();
        assert_eq!(names, ["default", "f 0", "f 1"]);
        assert_eq!(scene.materials[0], Material::default_white());
        let glass = &scene.materials[1];
        assert_eq!(glass.color, Color::new(1.0, 0.0, 0.0));
        assert_eq!(
            (
                glass.kd,
                glass.ks,
                glass.shininess,
                glass.kt,
                glass.ior,
                glass.ka
            ),
            (0.7, 0.3, 20.0, 0.5, 1.5, 1.0)
        );
        // Opaque with ior 0: stored as 1.
        let green = &scene.materials[2];
        assert_eq!(
            (green.kd, green.ks, green.shininess, green.kt, green.ior),
            (1.0, 0.0, 100000.0, 0.0, 1.0)
        );

        let objects: Vec<_> = scene
            .objects
            .iter()
            .map(|o| (o.name.as_str(), o.material))
            .collect();
        assert_eq!(
            objects,
            [
                ("sphere 0", 0),
                ("cylinder 1", 1),
                ("cone 2", 1),
                ("polygon 3", 1),
                ("patch 4", 2)
            ]
        );
        // Negative radius: its absolute value.
        let Shape::Sphere(sphere) = &scene.objects[0].shape else {
            panic!()
        };
        assert_eq!(sphere.radius, 2.0);
        let Shape::Cone(cone) = &scene.objects[2].shape else {
            panic!()
        };
        assert_eq!(
            (cone.base, cone.base_radius, cone.apex, cone.apex_radius),
            (DVec3::ZERO, 1.0, DVec3::X, 0.5)
        );
        let Shape::Polygon(polygon) = &scene.objects[3].shape else {
            panic!()
        };
        assert_eq!(polygon.vertices, [DVec3::ZERO, DVec3::X, DVec3::Y]);
        let Shape::Patch(patch) = &scene.objects[4].shape else {
            panic!()
        };
        // Normals are stored unit length: (0, 0, 2) becomes (0, 0, 1).
        assert_eq!(patch.normals, [DVec3::Z, DVec3::Z, DVec3::Z]);
    }

    #[test]
    fn angle_is_between_row_centres() {
        // angle 45 at H = 512: tan(fov/2) = tan(22.5°) * 512/511
        // = 0.41421356237309503 * 1.0019569471624266 = 0.4150241564286197,
        // fov = 2 atan(0.4150241564286197) = 45.07926148765139 degrees.
        let scene = parse_str(&format!("{VIEW}s 0 0 0 1\n")).unwrap();
        assert!(
            close(scene.camera.fov, 45.07926148765139),
            "{}",
            scene.camera.fov
        );
        let expected = 2.0
            * ((22.5f64).to_radians().tan() * 512.0 / 511.0)
                .atan()
                .to_degrees();
        assert!(close(scene.camera.fov, expected));
        // H = 2: the two row centres are half the image apart, so
        // tan(fov/2) = 2 tan(angle/2); angle 90 gives fov = 2 atan 2 = 126.86989764584402.
        assert!(close(fov_from_angle(90.0, 2), 126.86989764584402));
        // H = 1: the angle itself.
        assert_eq!(fov_from_angle(45.0, 1), 45.0);
    }

    #[test]
    fn resolution_height_is_the_one_converted_with() {
        // 8 x 2, angle 90: tan(fov/2) = 1 * 2/1 = 2, fov = 126.86989764584402;
        // the width does not enter.
        let text = VIEW
            .replace("resolution 512 512", "resolution 8 2")
            .replace("angle 45", "angle 90");
        let scene = parse_str(&text).unwrap();
        assert_eq!((scene.width, scene.height), (8, 2));
        assert!(close(scene.camera.fov, 126.86989764584402));
    }

    #[test]
    fn three_lights_share_the_spd_grey() {
        // n = 3: I_a = sqrt 3 / 6 = 0.28867513459481287.
        let scene = parse_str(&format!("{VIEW}l 1 0 0\nl 0 1 0\nl 0 0 1 1 1 1\n")).unwrap();
        let grey = 3f64.sqrt() / 6.0;
        assert!(close(grey, 0.28867513459481287));
        assert_eq!(scene.settings.ambient, Color::splat(grey));
        assert_eq!(scene.lights[0].color, Color::splat(grey));
        assert_eq!(scene.lights[1].color, Color::splat(grey));
        // A coloured light keeps its colour.
        assert_eq!(scene.lights[2].color, Color::ONE);
    }

    #[test]
    fn no_lights_no_ambient_default_background() {
        let scene = parse_str(VIEW).unwrap();
        assert_eq!(scene.settings.ambient, Color::ZERO);
        assert_eq!(scene.settings.background, Color::ZERO);
        assert!(scene.lights.is_empty() && scene.objects.is_empty() && scene.materials.is_empty());
    }

    #[test]
    fn default_white_only_when_used() {
        let scene = parse_str(&format!("{VIEW}f 1 1 1 1 0 0 0 0\ns 0 0 0 1\n")).unwrap();
        assert_eq!(scene.materials.len(), 1);
        assert_eq!(scene.materials[0].name, "f 0");
        assert_eq!(scene.objects[0].material, 0);
    }

    #[test]
    fn cone_on_one_line_or_three() {
        let one = parse_str(&format!("{VIEW}c 1 2 3 0.5 4 5 6 0.25\n")).unwrap();
        let three = parse_str(&format!("{VIEW}c\n1 2 3 0.5\n4 5 6 0.25\n")).unwrap();
        assert_eq!(one.objects, three.objects);
        assert_eq!(one.objects[0].name, "cone 0");
        let Shape::Cone(cone) = &one.objects[0].shape else {
            panic!()
        };
        assert_eq!(cone.base, DVec3::new(1.0, 2.0, 3.0));
        assert_eq!(cone.apex, DVec3::new(4.0, 5.0, 6.0));
        assert_eq!((cone.base_radius, cone.apex_radius), (0.5, 0.25));
        // Equal radii (after the absolute value) make a cylinder.
        let cylinder = parse_str(&format!("{VIEW}c 0 0 0 -1 0 0 1 1\n")).unwrap();
        assert_eq!(cylinder.objects[0].name, "cylinder 0");
    }

    #[test]
    fn comments_run_to_the_end_of_the_line() {
        let text = format!(
            "# a scene\n{VIEW}#s 9 9 9 9\ns 0 0 0 1 # the only sphere\n#\n  # indented\ns 0 0 0 2#glued\n"
        );
        let scene = parse_str(&text).unwrap();
        assert_eq!(scene.objects.len(), 2);
        // A comment inside an entity is skipped too.
        let scene = parse_str(&format!("{VIEW}s 0 0 0 # centre\n 3 # radius\n")).unwrap();
        let Shape::Sphere(sphere) = &scene.objects[0].shape else {
            panic!()
        };
        assert_eq!(sphere.radius, 3.0);
    }

    #[test]
    fn crlf_tabs_bom_and_exponents() {
        let text = format!(
            "\u{feff}{}s\t1e-1 -2.55836e-17 +3 .5\r\n",
            VIEW.replace('\n', "\r\n")
        );
        let scene = parse_str(&text).unwrap();
        let Shape::Sphere(sphere) = &scene.objects[0].shape else {
            panic!()
        };
        assert_eq!(sphere.center, DVec3::new(0.1, -2.55836e-17, 3.0));
        assert_eq!(sphere.radius, 0.5);
    }

    #[test]
    fn viewpoint_on_one_line_in_any_order() {
        let scene =
            parse_str("v resolution 10 20 up 0 1 0 angle 30 at 0 0 0 from 0 0 1\n").unwrap();
        assert_eq!((scene.width, scene.height), (10, 20));
        assert_eq!(scene.camera.eye, DVec3::Z);
    }

    // Errors, with the line and column they point at (both 1-based).
    // VIEW has 7 lines, so the first line after it is line 8.

    #[test]
    fn error_missing_number_names_the_token() {
        let (line, column, message) = error_of(&format!("{VIEW}s 0 0 0\np 3\n"));
        assert_eq!((line, column), (9, 1));
        assert_eq!(
            message,
            "expected a number for the sphere's radius, found `p`"
        );
    }

    #[test]
    fn error_end_of_file_points_after_the_last_token() {
        let (line, column, message) = error_of(&format!("{VIEW}p 3\n0 0 0\n1 0 0\n0 1\n\n"));
        // The last token is `1` on line 11, column 3: the error is right after it.
        assert_eq!((line, column), (11, 4));
        assert_eq!(
            message,
            "expected a number for the polygon's vertex 2 (z), found the end of the file"
        );
    }

    #[test]
    fn error_non_finite_numbers() {
        for (bad, column) in [("nan", 7), ("inf", 7), ("-infinity", 7), ("1e400", 7)] {
            let (line, col, message) = error_of(&format!("{VIEW}s 0 0 {bad} 1\n"));
            assert_eq!((line, col), (8, column), "{bad}");
            assert_eq!(
                message,
                format!("the sphere's centre (z) must be a finite number, got `{bad}`")
            );
        }
        let (line, column, message) = error_of(&format!("{VIEW}l 0 0 0 1 NaN 1\n"));
        assert_eq!((line, column), (8, 11));
        assert_eq!(
            message,
            "the light's colour (green) must be a finite number, got `NaN`"
        );
    }

    #[test]
    fn error_unknown_entity() {
        let (line, column, message) = error_of(&format!("{VIEW}s 0 0 0 1\n  tpp 3\n"));
        assert_eq!((line, column), (9, 3));
        assert_eq!(
            message,
            "unknown entity `tpp`: expected an entity keyword (v, b, l, f, c, s, p, pp)"
        );
        let (line, column, message) = error_of(&format!("{VIEW}s 0 0 0 1\nfrom 0 0 0\n"));
        assert_eq!((line, column), (9, 1));
        assert!(message.starts_with("unknown entity `from`"), "{message}");
        assert!(
            message.ends_with("(`from` belongs to a viewpoint and must follow a `v`)"),
            "{message}"
        );
    }

    #[test]
    fn error_extra_number() {
        let (line, column, message) = error_of(&format!("{VIEW}s 0 0 0 1 3.5\n"));
        assert_eq!((line, column), (8, 11));
        assert_eq!(
            message,
            "unexpected number `3.5`: expected an entity keyword (v, b, l, f, c, s, p, pp)"
        );
    }

    #[test]
    fn error_bad_vertex_counts() {
        for bad in ["0", "-3", "2.5", "1e1"] {
            let (line, column, message) =
                error_of(&format!("{VIEW}p {bad}\n0 0 0\n1 0 0\n0 1 0\n"));
            assert_eq!((line, column), (8, 3), "{bad}");
            assert_eq!(
                message,
                format!("the polygon's vertex count must be a positive integer, got `{bad}`")
            );
        }
        let (line, column, message) = error_of(&format!("{VIEW}pp x\n"));
        assert_eq!((line, column), (8, 4));
        assert_eq!(
            message,
            "expected a number for the patch's vertex count, found `x`"
        );
        // A count beyond memory is not allocated: the vertices run out first.
        let (line, column, message) =
            error_of(&format!("{VIEW}p 99999999999999999999999\n0 0 0\n"));
        assert_eq!((line, column), (9, 6));
        assert_eq!(
            message,
            "expected a number for the polygon's vertex 1 (x), found the end of the file"
        );
    }

    #[test]
    fn error_geometry_at_the_keyword() {
        let (line, column, message) = error_of(&format!("{VIEW}s 0 0 0 1\n s 1 1 1 0\n"));
        assert_eq!((line, column), (9, 2));
        assert_eq!(message, "sphere 1: sphere radius must be > 0, got 0");
        let (line, column, message) = error_of(&format!("{VIEW}p 3\n0 0 0\n1 0 0\n2 0 0\n"));
        assert_eq!((line, column), (8, 1));
        assert!(
            message.starts_with("polygon 0: vertices 0, 1 and 2 are collinear"),
            "{message}"
        );
        let (_, _, message) = error_of(&format!("{VIEW}p 2\n0 0 0\n1 0 0\n"));
        assert_eq!(
            message,
            "polygon 0: a polygon needs at least 3 vertices, got 2"
        );
        let (line, column, message) = error_of(&format!("{VIEW}c 1 1 1 1 1 1 1 1\n"));
        assert_eq!((line, column), (8, 1));
        assert_eq!(message, "cylinder 0: the cone's two ends coincide");
        let (_, _, message) = error_of(&format!("{VIEW}c 0 0 0 0 0 0 1 0\n"));
        assert_eq!(
            message,
            "cylinder 0: cone radii must be >= 0 and not both 0, got 0 and 0"
        );
        let (line, column, message) = error_of(&format!(
            "{VIEW}pp 3\n0 0 0 0 0 1\n1 0 0 0 0 0\n0 1 0 0 0 1\n"
        ));
        assert_eq!((line, column), (8, 1));
        assert_eq!(message, "patch 0: vertex normal 1 is zero");
    }

    #[test]
    fn error_transmitting_material_without_ior() {
        let (line, column, message) =
            error_of(&format!("{VIEW}f 1 1 1 0 0 0 0 -1\nf 1 1 1 0 0 0 0.8 0\n"));
        // The second `f` (index 1): its ior `0` is on line 9, column 19.
        assert_eq!((line, column), (9, 19));
        assert_eq!(
            message,
            "f 1: a transmitting material (T = 0.8) needs an index of refraction > 0, got 0"
        );
    }

    #[test]
    fn error_negative_coefficients() {
        let (line, column, message) = error_of(&format!("{VIEW}f 1 1 1 0.5 -0.5 3 0 0\n"));
        assert_eq!((line, column), (8, 13));
        assert_eq!(message, "the material's Ks must be >= 0, got `-0.5`");
        let (line, column, message) = error_of(&format!("{VIEW}f 1 1 1 0.5 0.5 3 1.5 1.5\n"));
        assert_eq!((line, column), (8, 19));
        assert_eq!(
            message,
            "the material's T must be between 0 and 1, got `1.5`"
        );
        let (line, column, message) = error_of(&format!("{VIEW}l 0 0 0 1 1 -1\n"));
        assert_eq!((line, column), (8, 13));
        assert_eq!(message, "the light's colour (blue) must be >= 0, got `-1`");
    }

    #[test]
    fn error_missing_or_second_viewpoint() {
        let (line, column, message) = error_of("s 0 0 0 1\n");
        assert_eq!((line, column), (1, 1));
        assert_eq!(
            message,
            "the file has no viewpoint `v`: an NFF file must have exactly one"
        );
        assert!(error_of("").2.contains("no viewpoint"));
        let (line, column, message) = error_of(&format!("{VIEW}s 0 0 0 1\n{VIEW}"));
        assert_eq!((line, column), (9, 1));
        assert_eq!(
            message,
            "a second viewpoint `v`: a file has exactly one (the first is on line 1)"
        );
        let (line, column, message) =
            error_of("b 0 0 0\n\nv\nfrom 0 0 1\nat 0 0 0\nup 0 1 0\nresolution 4 4\n");
        assert_eq!((line, column), (3, 1));
        assert_eq!(message, "the viewpoint `v` has no `angle`");
        let (line, column, message) = error_of(&VIEW.replace("hither 1", "from 1 1 1"));
        assert_eq!((line, column), (6, 1));
        assert_eq!(message, "the viewpoint gives `from` twice");
    }

    #[test]
    fn error_image_size_and_camera() {
        let (line, column, message) =
            error_of(&VIEW.replace("resolution 512 512", "resolution 0 512"));
        assert_eq!((line, column), (7, 1));
        assert_eq!(
            message,
            "image size 0x512 is empty: both sides must be at least 1"
        );
        let (line, column, message) =
            error_of(&VIEW.replace("resolution 512 512", "resolution 512 51.2"));
        assert_eq!((line, column), (7, 16));
        assert_eq!(
            message,
            "the viewpoint's resolution height must be a whole number of pixels, got `51.2`"
        );
        // Camera errors point at `v`.
        let (line, column, message) = error_of(&VIEW.replace("at 0 0 0", "at 0 0 5"));
        assert_eq!((line, column), (1, 1));
        assert!(
            message.starts_with("camera eye and look_at are the same point"),
            "{message}"
        );
        let (line, column, message) = error_of(&VIEW.replace("up 0 1 0", "up 0 0 -2"));
        assert_eq!((line, column), (1, 1));
        assert!(
            message.contains("parallel to the viewing direction"),
            "{message}"
        );
        let (line, column, message) = error_of(&VIEW.replace("angle 45", "angle 180"));
        assert_eq!((line, column), (5, 7));
        assert_eq!(
            message,
            "the viewpoint's `angle` must be between 0 and 180 degrees (exclusive), got 180"
        );
    }

    #[test]
    fn error_display_shows_the_line() {
        let error = parse_str(&format!("{VIEW}s 0 0 0 x\n")).unwrap_err();
        assert_eq!(
            error.to_string(),
            "t.nff:8:9: expected a number for the sphere's radius, found `x`\n  |\n8 | s 0 0 0 x\n  |         ^"
        );
    }

    #[test]
    fn never_panics_on_truncated_or_mangled_input() {
        let text = format!(
            "{VIEW}l 1 2 3\nl 1 2 3 1 1 1\nf 1 0 0 0.5 0.5 3 0.5 1.5\ns 0 0 0 1\nc 0 0 0 1 0 0 1 0.5\n\
             p 3\n0 0 0\n1 0 0\n0 1 0\npp 3\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n# é ü\n"
        );
        for end in (0..=text.len()).filter(|&i| text.is_char_boundary(i)) {
            let _ = parse_str(&text[..end]);
            let _ = parse_str(&text[end..]);
        }
        // Every token replaced, in turn, by awkward words.
        let tokens: Vec<&str> = text.split_ascii_whitespace().collect();
        for i in 0..tokens.len() {
            for odd in [
                "",
                "-0",
                "1e308",
                "-1e-320",
                "é",
                "#",
                "p",
                "pp",
                "v",
                "99999999999",
                "0.0",
                "\u{a0}",
            ] {
                let mut mangled = tokens.clone();
                mangled[i] = odd;
                let _ = parse_str(&mangled.join(" "));
            }
        }
    }

    mod properties {
        use proptest::prelude::*;

        use super::*;

        proptest! {
            #[test]
            fn random_token_soup_never_panics(
                words in proptest::collection::vec(
                    prop_oneof![
                        Just("v".to_string()), Just("b".to_string()), Just("l".to_string()),
                        Just("f".to_string()), Just("c".to_string()), Just("s".to_string()),
                        Just("p".to_string()), Just("pp".to_string()), Just("from".to_string()),
                        Just("at".to_string()), Just("up".to_string()), Just("angle".to_string()),
                        Just("resolution".to_string()), Just("hither".to_string()), Just("#".to_string()),
                        Just("\n".to_string()), Just("nan".to_string()),
                        (-3i32..5).prop_map(|n| n.to_string()),
                        any::<f64>().prop_map(|x| x.to_string()),
                        "\\PC{0,3}",
                    ],
                    0..60,
                )
            ) {
                let _ = parse_str(&words.join(" "));
            }
        }
    }
}
