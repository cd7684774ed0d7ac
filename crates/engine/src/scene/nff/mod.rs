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

use super::limits::{COLOR, COORDINATE, SIZE, check_cone_length};
use super::{
    Light, Material, Object, ObjectName, SceneError, SceneParts, Settings, check_camera,
    check_image_size,
};
use raystep_model::camera::Camera;
use raystep_model::math::Color;
use raystep_model::shapes::{Cone, GeometryError, Patch, Polygon, Shape, Sphere};

/// The entity keywords, as listed in messages.
const ENTITIES: &str = "v, b, l, f, c, s, p, pp";
const XYZ: [&str; 3] = ["x", "y", "z"];
const RGB: [&str; 3] = ["red", "green", "blue"];
/// Vertex lists are preallocated up to this many vertices; a larger count in
/// the file is trusted only as far as the file actually holds vertices.
const MAX_PREALLOCATED_VERTICES: usize = 4096;

/// Parses NFF text; `path` names it in messages.
pub(crate) fn parse(path: &Path, text: &str) -> Result<SceneParts, SceneError> {
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
            "b" => {
                scene.background = parser.vec3(RGB, COLOR, |c| format!("the background's {c}"))?
            }
            "l" => {
                let position =
                    parser.vec3(XYZ, COORDINATE, |c| format!("the light's position ({c})"))?;
                let color = if parser.peek().is_some_and(|t| t.text.parse::<f64>().is_ok()) {
                    Some(parser.vec3(RGB, COLOR, |c| format!("the light's colour ({c})"))?)
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
                let center =
                    parser.vec3(XYZ, COORDINATE, |c| format!("the sphere's centre ({c})"))?;
                let radius = parser.radius(SIZE, false, || "the sphere's radius".into())?;
                let shape = Sphere::new(center, radius).map(Shape::Sphere);
                scene.add(&parser, &keyword, "sphere", shape)?;
            }
            "c" => {
                let base = parser.vec3(XYZ, COORDINATE, |c| format!("the cone's base ({c})"))?;
                let base_radius = parser.radius(SIZE, true, || "the cone's base radius".into())?;
                let apex = parser.vec3(XYZ, COORDINATE, |c| format!("the cone's apex ({c})"))?;
                let apex_radius = parser.radius(SIZE, true, || "the cone's apex radius".into())?;
                let kind = if base_radius == apex_radius {
                    "cylinder"
                } else {
                    "cone"
                };
                let shape = check_cone_length(base, apex)
                    .map_err(GeometryError)
                    .and_then(|()| Cone::new(base, base_radius, apex, apex_radius))
                    .map(|cone| Shape::Cone(Box::new(cone)));
                scene.add(&parser, &keyword, kind, shape)?;
            }
            "p" => {
                let count = parser.count("the polygon's vertex count")?;
                let mut vertices = Vec::with_capacity(count.min(MAX_PREALLOCATED_VERTICES));
                for i in 0..count {
                    vertices.push(parser.vec3(XYZ, COORDINATE, |c| {
                        format!("the polygon's vertex {i} ({c})")
                    })?);
                }
                let shape = Polygon::new(vertices).map(Shape::Polygon);
                scene.add(&parser, &keyword, "polygon", shape)?;
            }
            "pp" => {
                let count = parser.count("the patch's vertex count")?;
                let mut vertices = Vec::with_capacity(count.min(MAX_PREALLOCATED_VERTICES));
                let mut normals = Vec::with_capacity(count.min(MAX_PREALLOCATED_VERTICES));
                for i in 0..count {
                    vertices.push(
                        parser
                            .vec3(XYZ, COORDINATE, |c| format!("the patch's vertex {i} ({c})"))?,
                    );
                    normals.push(
                        parser
                            .vec3(XYZ, COORDINATE, |c| format!("the patch's normal {i} ({c})"))?,
                    );
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

#[cfg(test)]
mod tests;
mod tokens;

use tokens::{Parser, Token};

/// A viewpoint `v` as read, before it becomes a camera.
struct Viewpoint {
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
    view: Option<Viewpoint>,
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
            name: ObjectName::numbered(shape.kind(), index),
            shape,
            material,
        });
        Ok(())
    }

    fn finish(self, parser: &Parser) -> Result<SceneParts, SceneError> {
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
            .map(|(i, (position, color))| {
                Light::point(format!("light {i}"), position, color.unwrap_or(grey))
            })
            .collect();
        let settings = Settings {
            background: self.background,
            ambient: grey,
            // SPD's convention: depth 5 and no weight cutoff, so ray counts
            // stay comparable with the published ones.
            min_weight: 0.0,
            ..Settings::default()
        };
        Ok(SceneParts {
            camera,
            size: (width, height),
            settings,
            materials: self.materials,
            lights,
            objects: self.objects,
            warnings: Vec::new(),
            files: Vec::new(),
        })
    }
}
