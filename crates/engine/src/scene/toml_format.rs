//! Native scene files in TOML: comments, familiar syntax, and errors that
//! carry line and column. Unknown keys are errors, so a misspelt `radious`
//! never silently falls back to a default. The file's schema, what serde
//! reads, is `schema.rs`; this file turns it into the engine's scene.
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

use std::collections::HashSet;
use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};

use glam::{DMat3, DMat4, DVec3};
use serde::Deserialize;
use toml::Spanned;

use super::toml_sections;
use super::{
    Light, MAX_RAYS_LIMIT, Material, Object, ObjectName, Profile, SceneError, SceneParts, Settings,
    check_camera, check_image_size,
};
use raystep_model::camera::Camera;
use raystep_model::math::Color;
use raystep_model::shapes::{
    Cone, GeometryError, Patch, Plane, Polygon, Shape, Sphere, placed_sphere,
};

mod bounds;
mod schema;

use schema::{
    CameraDef, FileDef, LightDef, MaterialDef, MeshDef, ObjectDef, ObjectSectionDef, SettingsDef,
    SphereDef, Vec3, number, triple, vec3,
};

/// The default image size when a file has no `[image]` table.
pub(crate) const DEFAULT_SIZE: (u32, u32) = (320, 240);
/// The default vertical field of view in degrees.
pub(crate) const DEFAULT_FOV: f64 = 45.0;
/// Deeper recursion than this is refused as a mistake.
pub(crate) const MAX_DEPTH_LIMIT: u32 = 64;

/// Collects the file's context so that every check can point into it.
#[derive(Clone, Copy)]
struct Source<'a> {
    path: &'a Path,
    text: &'a str,
    /// Where the part being read starts in `text`: spans are relative to it.
    offset: usize,
}

impl Source<'_> {
    fn error(&self, span: Range<usize>, message: impl fmt::Display) -> SceneError {
        let span = span.start + self.offset..span.end + self.offset;
        SceneError::at(self.path, self.text, span, message.to_string())
    }

    /// The same file, reading the part that starts at `offset`.
    fn at(self, offset: usize) -> Self {
        Self { offset, ..self }
    }

    /// Deserializes `part`, which starts at `self.offset` in the file.
    fn read<'de, T: Deserialize<'de>>(&self, part: &'de str) -> Result<T, SceneError> {
        toml::from_str(part).map_err(|e| {
            let message = e.message().trim_end().to_string();
            match e.span() {
                Some(span) => self.error(span, message),
                None => SceneError::plain(format!("{}: {message}", self.path.display())),
            }
        })
    }
}

/// The file's objects: read with the rest, or still to be read section by section.
enum ObjectDefs {
    Read(Vec<Spanned<ObjectDef>>),
    Sections(Vec<Range<usize>>),
}

/// Reads everything but the objects, and the objects too when the file could
/// not be cut into sections (`toml_sections`).
fn read_file(source: &Source) -> Result<(FileDef, ObjectDefs), SceneError> {
    let split = toml_sections::split(source.text).map_err(|span| {
        source.error(
            span,
            format!(
                "a dotted key of {} or more parts: the TOML reader takes at most {}",
                toml_sections::MAX_KEY_PARTS,
                toml_sections::MAX_KEY_PARTS - 1
            ),
        )
    })?;
    if let Some(sections) = split
        && !sections.objects.is_empty()
    {
        let file: FileDef = source.read(&sections.rest)?;
        if file.objects.is_none() {
            return Ok((file, ObjectDefs::Sections(sections.objects)));
        }
        // `object` is also written some other way: read the whole file at
        // once, so that its reader judges (and reports) the clash.
    }
    let mut file: FileDef = source.read(source.text)?;
    let objects = file.objects.take().unwrap_or_default();
    Ok((file, ObjectDefs::Read(objects)))
}

pub(crate) fn parse(path: &Path, text: &str) -> Result<SceneParts, SceneError> {
    let source = Source {
        path,
        text,
        offset: 0,
    };
    let (file, object_defs) = read_file(&source)?;
    bounds::file(&source, &file)?;
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
    unclamped_attenuations(&source, &file, settings.profile)?;
    let mut materials = Vec::new();
    for (name, def) in &file.materials {
        materials.push(material(name, def.get_ref()));
    }
    let mut lights: Vec<Light> = file
        .lights
        .iter()
        .enumerate()
        .map(|(i, def)| light(&source, i, def))
        .collect::<Result<_, _>>()?;
    let mut meshes = Meshes::default();
    let objects = match object_defs {
        ObjectDefs::Read(defs) => {
            let defs = defs.into_iter().map(|def| Ok((source, def)));
            objects(defs, &mut materials, &mut meshes)?
        }
        ObjectDefs::Sections(ranges) => {
            let defs = ranges.into_iter().map(|range| {
                let part = source.at(range.start);
                let section: ObjectSectionDef = part.read(&text[range])?;
                let [def] = <[_; 1]>::try_from(section.objects).map_err(|_| {
                    part.error(0..0, "internal error: an object section holds one object")
                })?;
                Ok((part, def))
            });
            objects(defs, &mut materials, &mut meshes)?
        }
    };
    lights.extend(meshes.lights);
    Ok(SceneParts {
        camera,
        size: (width, height),
        settings,
        materials,
        lights,
        objects,
        warnings: meshes.warnings,
        files: meshes.files,
    })
}

/// What the scene's meshes add besides objects and materials.
#[derive(Default)]
struct Meshes {
    lights: Vec<Light>,
    warnings: Vec<String>,
    /// The mesh and MTL files read (`Scene::files`).
    files: Vec<PathBuf>,
}

/// Builds the objects in file order, refusing a name used twice.
fn objects<'a>(
    defs: impl ExactSizeIterator<Item = Result<(Source<'a>, Spanned<ObjectDef>), SceneError>>,
    materials: &mut Vec<Material>,
    meshes: &mut Meshes,
) -> Result<Vec<Object>, SceneError> {
    let mut objects: Vec<Object> = Vec::with_capacity(defs.len());
    let mut given_names = HashSet::new();
    let mut mesh_groups = HashSet::new();
    for (i, def) in defs.enumerate() {
        let (source, def) = def?;
        let key = format!("object[{i}]");
        bounds::object(&source, &key, def.get_ref())?;
        if let Some(mesh_def) = &def.get_ref().mesh {
            let mut placed = mesh(&source, &def, mesh_def, materials)?;
            // An unnamed mesh is named by its file's groups; a second one
            // with the same groups (the same file placed twice) is told
            // apart by its place in the list, as an unnamed sphere is.
            if def.get_ref().name.is_none() && placed.groups.iter().any(|g| mesh_groups.contains(g))
            {
                placed.prefix_names(&format!("mesh {i} "));
            }
            mesh_groups.extend(placed.groups.iter().cloned());
            if let Some(name) = &def.get_ref().name
                && !given_names.insert(name.get_ref().clone())
            {
                return Err(source.error(
                    name.span(),
                    format!("object name `{}` is used twice", name.get_ref()),
                ));
            }
            objects.extend(placed.objects);
            materials.extend(placed.materials);
            meshes.lights.extend(placed.lights);
            meshes.warnings.extend(placed.warnings);
            meshes.files.extend(placed.files);
            continue;
        }
        let object = object(&source, objects.len(), &def, materials)?;
        let used = |name: &str| is_default_name(&objects, name);
        if let Some(name) = &def.get_ref().name
            && (!given_names.insert(object.name.to_string()) || used(&object.name.text()))
        {
            return Err(source.error(
                name.span(),
                format!("object name `{}` is used twice", object.name),
            ));
        }
        objects.push(object);
    }
    Ok(objects)
}

/// Whether `name` is the default name of one of `objects`, "sphere 3" for
/// an unnamed sphere at index 3 (named objects are in the set of given names).
fn is_default_name(objects: &[Object], name: &str) -> bool {
    name.rsplit_once(' ')
        .and_then(|(_, index)| index.parse::<usize>().ok())
        .and_then(|index| objects.get(index))
        .is_some_and(|o| o.name == name)
}

fn camera(source: &Source, def: &Spanned<CameraDef>) -> Result<Camera, SceneError> {
    let c = def.get_ref();
    let camera = Camera {
        eye: vec3(&c.eye),
        look_at: vec3(&c.look_at),
        up: c.up.as_ref().map_or(DVec3::Y, vec3),
        fov: c.fov.as_ref().map_or(DEFAULT_FOV, number),
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
        background: def.background.as_ref().map_or(defaults.background, vec3),
        ambient: def.ambient.as_ref().map_or(defaults.ambient, vec3),
        light_attenuation: def
            .light_attenuation
            .as_ref()
            .map_or(defaults.light_attenuation, triple),
        ray_attenuation: def
            .ray_attenuation
            .as_ref()
            .map_or(defaults.ray_attenuation, triple),
        max_depth,
        min_weight: def.min_weight.as_ref().map_or(defaults.min_weight, number),
        max_rays: max_rays(source, def)?,
        specular: def.specular.unwrap_or_default(),
        profile: def.profile.unwrap_or_default(),
        ..defaults
    })
}

/// Without the clamp (the cse167 profile, MODEL §11) f_att is 1 / (c1 +
/// c2 d + c3 d²) as it is: coefficients all 0 would divide by zero.
fn unclamped_attenuations(
    source: &Source,
    file: &FileDef,
    profile: Profile,
) -> Result<(), SceneError> {
    if profile.clamps_attenuation() {
        return Ok(());
    }
    let scene = file.settings.light_attenuation.iter();
    let lights = file
        .lights
        .iter()
        .filter_map(|l| l.get_ref().attenuation.as_ref());
    for coefficients in scene.chain(lights.map(|a| a.get_ref())) {
        if triple(coefficients) == [0.0; 3] {
            return Err(source.error(
                coefficients.0[0].span().start..coefficients.0[2].span().end,
                "attenuation (0, 0, 0) divides by zero: the cse167 profile does not clamp \
                 f_att = 1 / (c1 + c2 d + c3 d²) to 1, so some coefficient must be above 0",
            ));
        }
    }
    Ok(())
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

/// Reads a mesh object's file (relative to the scene file) and places it.
fn mesh(
    source: &Source,
    def: &Spanned<ObjectDef>,
    mesh_def: &Spanned<MeshDef>,
    materials: &[Material],
) -> Result<super::mesh::Placed, SceneError> {
    let o = def.get_ref();
    let m = mesh_def.get_ref();
    if shape_count(o) {
        return Err(source.error(
            def.span(),
            "an object with a `mesh` has no other shape (sphere, plane, polygon, patch, cylinder, cone)",
        ));
    }
    let material = match &o.material {
        Some(name) => Some(material_index(source, name, materials)?),
        None => None,
    };
    let file = m.file.get_ref();
    let dir = source.path.parent().unwrap_or(Path::new(""));
    let path = dir.join(file);
    if !super::mesh::is_mesh_file(&path) {
        return Err(source.error(
            m.file.span(),
            format!("mesh file `{file}` must end in .obj or .stl"),
        ));
    }
    let placement = super::mesh::Placement {
        scale: m.scale.as_ref().map_or(1.0, number),
        rotate: m.rotate.as_ref().map_or(DVec3::ZERO, vec3),
        translate: m.translate.as_ref().map_or(DVec3::ZERO, vec3),
    };
    let request = super::mesh::Request {
        path: &path,
        name: o.name.as_ref().map(|n| n.get_ref().as_str()),
        placement,
        material,
        first_material: materials.len(),
    };
    super::mesh::load(&request).map_err(|e| {
        if e.location.is_some() {
            e
        } else {
            source.error(m.file.span(), e.message)
        }
    })
}

/// Whether an object names any shape besides its mesh.
fn shape_count(o: &ObjectDef) -> bool {
    o.sphere.is_some()
        || o.plane.is_some()
        || o.polygon.is_some()
        || o.patch.is_some()
        || o.cylinder.is_some()
        || o.cone.is_some()
}

fn material_index(
    source: &Source,
    name: &Spanned<String>,
    materials: &[Material],
) -> Result<usize, SceneError> {
    materials
        .iter()
        .position(|m| &m.name == name.get_ref())
        .ok_or_else(|| {
            let known: Vec<&str> = materials.iter().map(|m| m.name.as_str()).collect();
            source.error(
                name.span(),
                format!(
                    "unknown material `{}`; the materials defined are: {}",
                    name.get_ref(),
                    if known.is_empty() {
                        "none".to_string()
                    } else {
                        known.join(", ")
                    }
                ),
            )
        })
}

fn material(name: &str, m: &MaterialDef) -> Material {
    Material {
        name: name.to_string(),
        color: m.color.as_ref().map_or(DVec3::ONE, vec3),
        kd: m.kd.as_ref().map_or(1.0, number),
        ks: m.ks.as_ref().map_or(0.0, number),
        shininess: m.n.as_ref().map_or(20.0, number),
        kt: m.kt.as_ref().map_or(0.0, number),
        ior: m.ior.as_ref().map_or(1.0, number),
        ka: m.ka.as_ref().map_or(1.0, number),
        specular: m.specular,
        reflects: m.reflect.unwrap_or(true),
        ambient: m.ambient.as_ref().map(vec3),
        // Black emission and a white specular colour are no colour at all.
        emission: m.emission.as_ref().map(vec3).filter(|e| *e != Color::ZERO),
        specular_color: (m.specular_color.as_ref().map(vec3)).filter(|s| *s != Color::ONE),
    }
}

/// A point light (`position`) or a directional one (`direction`, MODEL
/// §4): exactly one of the two, and a direction that is not zero.
fn light(source: &Source, index: usize, def: &Spanned<LightDef>) -> Result<Light, SceneError> {
    let l = def.get_ref();
    let color = l.color.as_ref().map_or(DVec3::ONE, vec3);
    let name = l.name.clone().unwrap_or_else(|| format!("light {index}"));
    match (&l.position, &l.direction) {
        (Some(position), None) => {
            let mut light = Light::point(name, vec3(position), color);
            light.attenuation = l.attenuation.as_ref().map(|a| triple(a.get_ref()));
            Ok(light)
        }
        (None, Some(_)) if l.attenuation.is_some() => Err(source.error(
            l.attenuation.as_ref().map_or(def.span(), |a| a.span()),
            "a directional light is never attenuated (MODEL §4): `attenuation` is a point light's",
        )),
        (None, Some(direction)) => {
            let d = vec3(direction.get_ref());
            Light::directional(name, d, color).ok_or_else(|| {
                source.error(
                    direction.span(),
                    format!("a directional light's `direction` must not be zero, got {d}"),
                )
            })
        }
        (Some(_), Some(_)) => Err(source.error(
            def.span(),
            "a light has either `position` (a point light) or `direction` (a directional light), not both",
        )),
        (None, None) => Err(source.error(
            def.span(),
            "a light needs `position` (a point light) or `direction` (a directional light, towards it)",
        )),
    }
}

fn object(
    source: &Source,
    index: usize,
    def: &Spanned<ObjectDef>,
    materials: &[Material],
) -> Result<Object, SceneError> {
    let o = def.get_ref();
    let Some(material_name) = &o.material else {
        return Err(source.error(def.span(), "missing field `material`"));
    };
    let material = material_index(source, material_name, materials)?;
    let (shape, span) = shape(o).ok_or_else(|| {
        source.error(
            def.span(),
            "an object needs exactly one shape: sphere, plane, polygon, patch, cylinder, cone or mesh",
        )
    })?;
    let shape = shape.map_err(|e| source.error(span, e))?;
    let name = o
        .name
        .as_ref()
        .map_or(ObjectName::numbered(shape.kind(), index), |n| {
            n.get_ref().as_str().into()
        });
    Ok(Object {
        name,
        shape,
        material,
    })
}

/// A sphere, or with a `scale` or `rotate` an ellipsoid: the sphere of
/// radius r about the origin of its own space, placed by
/// M = T(center) R S (MODEL §3). A sphere scaled the same along every axis
/// is a plain sphere of radius s r, however it is turned.
fn sphere(d: &SphereDef) -> Result<Shape, GeometryError> {
    let (center, radius) = (vec3(&d.center), number(&d.radius));
    if d.scale.is_none() && d.rotate.is_none() {
        return Sphere::new(center, radius).map(Shape::Sphere);
    }
    let scale = d.scale.as_ref().map_or(DVec3::ONE, vec3);
    if scale.x == scale.y && scale.y == scale.z {
        return Sphere::new(center, scale.x * radius).map(Shape::Sphere);
    }
    let r = d.rotate.as_ref().map_or(DVec3::ZERO, vec3) * (std::f64::consts::PI / 180.0);
    let rotation =
        DMat3::from_rotation_z(r.z) * DMat3::from_rotation_y(r.y) * DMat3::from_rotation_x(r.x);
    let transform =
        DMat4::from_translation(center) * DMat4::from_mat3(rotation) * DMat4::from_scale(scale);
    placed_sphere(DVec3::ZERO, radius, transform)
}

/// The object's one shape and where it is written, or `None` when there is
/// not exactly one.
fn shape(o: &ObjectDef) -> Option<(Result<Shape, GeometryError>, Range<usize>)> {
    let points = |v: &[Vec3]| v.iter().map(vec3).collect::<Vec<_>>();
    let mut shapes = Vec::new();
    if let Some(s) = &o.sphere {
        let d = s.get_ref();
        shapes.push((sphere(d), s.span()));
    }
    if let Some(s) = &o.plane {
        let d = s.get_ref();
        shapes.push((
            Plane::new(vec3(&d.normal), vec3(&d.point)).map(Shape::Plane),
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
            Cone::new(
                vec3(&d.base),
                number(&d.radius),
                vec3(&d.apex),
                number(&d.radius),
            )
            .map(|cone| Shape::Cone(Box::new(cone))),
            s.span(),
        ));
    }
    if let Some(s) = &o.cone {
        let d = s.get_ref();
        let cone = Cone::new(
            vec3(&d.base),
            number(&d.base_radius),
            vec3(&d.apex),
            number(&d.apex_radius),
        );
        shapes.push((cone.map(|cone| Shape::Cone(Box::new(cone))), s.span()));
    }
    if shapes.len() == 1 {
        shapes.pop()
    } else {
        None
    }
}
