//! Native scene files in TOML: comments, familiar syntax, and errors that
//! carry line and column. Unknown keys are errors, so a misspelt `radious`
//! never silently falls back to a default.
//!
//! ```toml
//! # A red ball under one light.
//! [camera]
//! eye = [0, 1, 6]
//! look_at = [0, 1, 0]
//! up = [0, 1, 0]
//! fov = 40
//!
//! [image]
//! width = 160
//! height = 120
//!
//! [settings]
//! background = [0.1, 0.1, 0.2]
//! ambient = [0.2, 0.2, 0.2]
//!
//! [materials.red]
//! color = [1, 0.1, 0.1]
//! kd = 0.7
//! ks = 0.3
//! n = 40
//!
//! [[light]]
//! name = "key"
//! position = [5, 8, 5]
//!
//! [[object]]
//! name = "ball"
//! material = "red"
//! sphere = { center = [0, 1, 0], radius = 1 }
//! ```

use std::collections::BTreeMap;
use std::fmt;
use std::ops::Range;
use std::path::Path;

use glam::DVec3;
use serde::Deserialize;
use toml::Spanned;

use super::{
    Light, MAX_RAYS_LIMIT, Material, Object, Scene, SceneError, Settings, SpecularModel,
    check_camera, check_image_size,
};
use crate::camera::Camera;
use crate::math::exceeds;
use crate::shapes::{Cone, GeometryError, Patch, Plane, Polygon, Shape, Sphere};

/// A number that must be finite: TOML allows `nan` and `inf`, scenes do not.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Finite(f64);

impl<'de> Deserialize<'de> for Finite {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let value = f64::deserialize(deserializer)?;
        if value.is_finite() {
            Ok(Finite(value))
        } else {
            Err(serde::de::Error::custom(format!(
                "numbers must be finite, got {value}"
            )))
        }
    }
}

type Vec3 = [Finite; 3];

fn vec3(v: Vec3) -> DVec3 {
    DVec3::new(v[0].0, v[1].0, v[2].0)
}

fn triple(v: Vec3) -> [f64; 3] {
    [v[0].0, v[1].0, v[2].0]
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileDef {
    camera: Spanned<CameraDef>,
    image: Option<Spanned<ImageDef>>,
    #[serde(default)]
    settings: SettingsDef,
    #[serde(default)]
    materials: BTreeMap<String, Spanned<MaterialDef>>,
    #[serde(default, rename = "light")]
    lights: Vec<Spanned<LightDef>>,
    #[serde(default, rename = "object")]
    objects: Vec<Spanned<ObjectDef>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CameraDef {
    eye: Vec3,
    look_at: Vec3,
    up: Option<Vec3>,
    fov: Option<Finite>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ImageDef {
    width: u32,
    height: u32,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct SettingsDef {
    background: Option<Vec3>,
    ambient: Option<Vec3>,
    light_attenuation: Option<Vec3>,
    ray_attenuation: Option<Vec3>,
    max_depth: Option<Spanned<u32>>,
    min_weight: Option<Spanned<Finite>>,
    max_rays: Option<Spanned<u32>>,
    specular: Option<SpecularModel>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MaterialDef {
    color: Option<Vec3>,
    kd: Option<Finite>,
    ks: Option<Finite>,
    n: Option<Finite>,
    kt: Option<Finite>,
    ior: Option<Finite>,
    ka: Option<Finite>,
    specular: Option<SpecularModel>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LightDef {
    name: Option<String>,
    position: Vec3,
    color: Option<Vec3>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ObjectDef {
    name: Option<Spanned<String>>,
    material: Spanned<String>,
    sphere: Option<Spanned<SphereDef>>,
    plane: Option<Spanned<PlaneDef>>,
    polygon: Option<Spanned<PolygonDef>>,
    patch: Option<Spanned<PatchDef>>,
    cylinder: Option<Spanned<CylinderDef>>,
    cone: Option<Spanned<ConeDef>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SphereDef {
    center: Vec3,
    radius: Finite,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PlaneDef {
    normal: Vec3,
    point: Vec3,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PolygonDef {
    vertices: Vec<Vec3>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PatchDef {
    vertices: Vec<Vec3>,
    normals: Vec<Vec3>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CylinderDef {
    base: Vec3,
    apex: Vec3,
    radius: Finite,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ConeDef {
    base: Vec3,
    base_radius: Finite,
    apex: Vec3,
    apex_radius: Finite,
}

/// The default image size when a file has no `[image]` table.
pub const DEFAULT_SIZE: (u32, u32) = (320, 240);
/// The default vertical field of view in degrees.
pub const DEFAULT_FOV: f64 = 45.0;
/// Deeper recursion than this is refused as a mistake.
pub const MAX_DEPTH_LIMIT: u32 = 64;

/// Collects the file's context so that every check can point into it.
struct Source<'a> {
    path: &'a Path,
    text: &'a str,
}

impl Source<'_> {
    fn error(&self, span: Range<usize>, message: impl fmt::Display) -> SceneError {
        SceneError::at(self.path, self.text, span, message.to_string())
    }
}

pub fn parse(path: &Path, text: &str) -> Result<Scene, SceneError> {
    let source = Source { path, text };
    let file: FileDef = toml::from_str(text).map_err(|e| {
        let message = e.message().trim_end().to_string();
        match e.span() {
            Some(span) => source.error(span, message),
            None => SceneError::plain(format!("{}: {message}", path.display())),
        }
    })?;
    let camera = camera(&source, &file.camera)?;
    let (width, height) = match &file.image {
        Some(image) => {
            check_image_size(image.get_ref().width, image.get_ref().height)
                .map_err(|m| source.error(image.span(), m))?;
            (image.get_ref().width, image.get_ref().height)
        }
        None => DEFAULT_SIZE,
    };
    let settings = settings(&source, &file.settings)?;
    let mut materials = Vec::new();
    for (name, def) in &file.materials {
        materials.push(material(&source, name, def)?);
    }
    let lights = file
        .lights
        .iter()
        .enumerate()
        .map(|(i, def)| light(&source, i, def))
        .collect::<Result<Vec<_>, _>>()?;
    let mut objects: Vec<Object> = Vec::with_capacity(file.objects.len());
    for def in &file.objects {
        let object = object(&source, objects.len(), def, &materials)?;
        if let Some(name) = &def.get_ref().name
            && objects.iter().any(|o| o.name == object.name)
        {
            return Err(source.error(
                name.span(),
                format!("object name `{}` is used twice", object.name),
            ));
        }
        objects.push(object);
    }
    Ok(Scene::new(
        camera,
        (width, height),
        settings,
        materials,
        lights,
        objects,
    ))
}

fn camera(source: &Source, def: &Spanned<CameraDef>) -> Result<Camera, SceneError> {
    let c = def.get_ref();
    let camera = Camera {
        eye: vec3(c.eye),
        look_at: vec3(c.look_at),
        up: c.up.map_or(DVec3::Y, vec3),
        fov: c.fov.map_or(DEFAULT_FOV, |f| f.0),
    };
    check_camera(&camera).map_err(|m| source.error(def.span(), m))?;
    Ok(camera)
}

fn settings(source: &Source, def: &SettingsDef) -> Result<Settings, SceneError> {
    let defaults = Settings::default();
    let max_depth = match &def.max_depth {
        Some(depth) if !(1..=MAX_DEPTH_LIMIT).contains(depth.get_ref()) => {
            return Err(source.error(
                depth.span(),
                format!(
                    "max_depth must be between 1 and {MAX_DEPTH_LIMIT}, got {}",
                    depth.get_ref()
                ),
            ));
        }
        Some(depth) => *depth.get_ref(),
        None => defaults.max_depth,
    };
    Ok(Settings {
        background: def.background.map_or(defaults.background, vec3),
        ambient: def.ambient.map_or(defaults.ambient, vec3),
        light_attenuation: def
            .light_attenuation
            .map_or(defaults.light_attenuation, triple),
        ray_attenuation: def.ray_attenuation.map_or(defaults.ray_attenuation, triple),
        max_depth,
        min_weight: min_weight(source, def)?,
        max_rays: max_rays(source, def)?,
        specular: def.specular.unwrap_or_default(),
        switches: defaults.switches,
    })
}

/// `min_weight`, a weight cutoff between 0 (none) and 1 (MODEL §5).
fn min_weight(source: &Source, def: &SettingsDef) -> Result<f64, SceneError> {
    let Some(value) = &def.min_weight else {
        return Ok(Settings::default().min_weight);
    };
    let weight = value.get_ref().0;
    if (0.0..=1.0).contains(&weight) {
        Ok(weight)
    } else {
        Err(source.error(
            value.span(),
            format!("min_weight must be between 0 and 1, got {weight}"),
        ))
    }
}

/// `max_rays`, the per-pixel ray budget, from 1 to `MAX_RAYS_LIMIT` (MODEL §5).
fn max_rays(source: &Source, def: &SettingsDef) -> Result<u32, SceneError> {
    let Some(value) = &def.max_rays else {
        return Ok(Settings::default().max_rays);
    };
    let rays = *value.get_ref();
    if (1..=MAX_RAYS_LIMIT).contains(&rays) {
        Ok(rays)
    } else {
        Err(source.error(
            value.span(),
            format!("max_rays must be between 1 and {MAX_RAYS_LIMIT}, got {rays}"),
        ))
    }
}

fn material(
    source: &Source,
    name: &str,
    def: &Spanned<MaterialDef>,
) -> Result<Material, SceneError> {
    let m = def.get_ref();
    let material = Material {
        name: name.to_string(),
        color: m.color.map_or(DVec3::ONE, vec3),
        kd: m.kd.map_or(1.0, |v| v.0),
        ks: m.ks.map_or(0.0, |v| v.0),
        shininess: m.n.map_or(20.0, |v| v.0),
        kt: m.kt.map_or(0.0, |v| v.0),
        ior: m.ior.map_or(1.0, |v| v.0),
        ka: m.ka.map_or(1.0, |v| v.0),
        specular: m.specular,
    };
    let fail = |what: String| Err(source.error(def.span(), format!("material `{name}`: {what}")));
    if material.color.min_element() < 0.0 {
        return fail(format!(
            "color components must be >= 0, got {}",
            material.color
        ));
    }
    for (key, value) in [
        ("kd", material.kd),
        ("ks", material.ks),
        ("n", material.shininess),
        ("kt", material.kt),
        ("ka", material.ka),
    ] {
        if value < 0.0 {
            return fail(format!("{key} must be >= 0, got {value}"));
        }
    }
    if material.kt > 1.0 {
        return fail(format!("kt must be at most 1, got {}", material.kt));
    }
    if !exceeds(material.ior, 0.0) {
        return fail(format!("ior must be > 0, got {}", material.ior));
    }
    Ok(material)
}

fn light(source: &Source, index: usize, def: &Spanned<LightDef>) -> Result<Light, SceneError> {
    let l = def.get_ref();
    let color = l.color.map_or(DVec3::ONE, vec3);
    if color.min_element() < 0.0 {
        return Err(source.error(
            def.span(),
            format!("light color components must be >= 0, got {color}"),
        ));
    }
    Ok(Light {
        name: l.name.clone().unwrap_or_else(|| format!("light {index}")),
        position: vec3(l.position),
        color,
    })
}

fn object(
    source: &Source,
    index: usize,
    def: &Spanned<ObjectDef>,
    materials: &[Material],
) -> Result<Object, SceneError> {
    let o = def.get_ref();
    let material = materials
        .iter()
        .position(|m| &m.name == o.material.get_ref())
        .ok_or_else(|| {
            let known: Vec<&str> = materials.iter().map(|m| m.name.as_str()).collect();
            source.error(
                o.material.span(),
                format!(
                    "unknown material `{}`; the materials defined are: {}",
                    o.material.get_ref(),
                    if known.is_empty() {
                        "none".to_string()
                    } else {
                        known.join(", ")
                    }
                ),
            )
        })?;
    let (shape, span) = shape(o).ok_or_else(|| {
        source.error(
            def.span(),
            "an object needs exactly one shape: sphere, plane, polygon, patch, cylinder or cone",
        )
    })?;
    let shape = shape.map_err(|e| source.error(span, e))?;
    let name = o.name.as_ref().map_or_else(
        || format!("{} {index}", shape.kind()),
        |n| n.get_ref().clone(),
    );
    Ok(Object {
        name,
        shape,
        material,
    })
}

/// The object's one shape and where it is written, or `None` when there is
/// not exactly one.
fn shape(o: &ObjectDef) -> Option<(Result<Shape, GeometryError>, Range<usize>)> {
    let points = |v: &[Vec3]| v.iter().copied().map(vec3).collect::<Vec<_>>();
    let mut shapes = Vec::new();
    if let Some(s) = &o.sphere {
        let d = s.get_ref();
        shapes.push((
            Sphere::new(vec3(d.center), d.radius.0).map(Shape::Sphere),
            s.span(),
        ));
    }
    if let Some(s) = &o.plane {
        let d = s.get_ref();
        shapes.push((
            Plane::new(vec3(d.normal), vec3(d.point)).map(Shape::Plane),
            s.span(),
        ));
    }
    if let Some(s) = &o.polygon {
        shapes.push((
            Polygon::new(points(&s.get_ref().vertices)).map(Shape::Polygon),
            s.span(),
        ));
    }
    if let Some(s) = &o.patch {
        let d = s.get_ref();
        shapes.push((
            Patch::new(points(&d.vertices), points(&d.normals)).map(Shape::Patch),
            s.span(),
        ));
    }
    if let Some(s) = &o.cylinder {
        let d = s.get_ref();
        shapes.push((
            Cone::new(vec3(d.base), d.radius.0, vec3(d.apex), d.radius.0).map(Shape::Cone),
            s.span(),
        ));
    }
    if let Some(s) = &o.cone {
        let d = s.get_ref();
        let cone = Cone::new(vec3(d.base), d.base_radius.0, vec3(d.apex), d.apex_radius.0);
        shapes.push((cone.map(Shape::Cone), s.span()));
    }
    if shapes.len() == 1 {
        shapes.pop()
    } else {
        None
    }
}
