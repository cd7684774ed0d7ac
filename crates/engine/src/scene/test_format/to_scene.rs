//! A parsed `.test` file as raystep's scene, traced with the `cse167`
//! profile (MODEL §11, docs/CSE167.md): each object's material state
//! becomes its material (A, E, D, S and s as the course names them), each
//! light a light, the flattened transforms already in the shapes.
//!
//! Where the course's spec is silent, the choices (each in docs/CSE167.md):
//! - `maxdepth n` counts bounces ("the maximum depth (number of bounces)
//!   for a ray"), so the primary ray and n more: max_depth = n + 1 in
//!   MODEL §5's counting, where the primary ray has depth 1.
//! - `attenuation` is one global state, its last value (the course's
//!   skeleton keeps it in a global read before rendering); directional
//!   lights are never attenuated.
//! - No weight cutoff (the course's tracers recurse to `maxdepth`).
//! - A triangle whose vertices are collinear is skipped with a warning, as
//!   a mesh's are (MODEL §3).
//! - A sphere under a transform that scales alike on every axis is a
//!   sphere; under any other, an ellipsoid (MODEL §3).

use std::collections::HashMap;
use std::path::Path;

use glam::DVec3;

use super::{TestLightKind, TestMaterial, TestObject, TestScene, TestShape};
use crate::scene::{Light, Material, Profile, SceneError, SceneParts, Settings};
use raystep_model::camera::Camera;
use raystep_model::object::{Object, ObjectName};
use raystep_model::shapes::{Patch, Polygon, Shape, placed_sphere};

/// `scene`, read from `path`, as raystep's scene under the cse167 profile.
pub(crate) fn to_scene(path: &Path, scene: TestScene) -> Result<SceneParts, SceneError> {
    let at = |line: usize, message: String| {
        SceneError::plain(format!("{}:{line}: {message}", path.display()))
    };
    let a = scene.attenuation;
    let settings = Settings {
        profile: Profile::Cse167,
        max_depth: scene.maxdepth + 1,
        min_weight: 0.0,
        light_attenuation: [a.constant, a.linear, a.quadratic],
        ..Settings::default()
    };
    let mut materials = Materials::default();
    let mut objects = Vec::with_capacity(scene.objects.len());
    let mut warnings = Vec::new();
    for object in &scene.objects {
        let shape = match shape(object) {
            Ok(shape) => shape,
            Err(Skip::Degenerate(why)) => {
                warnings.push(format!(
                    "{}:{}: a triangle with no area ({why}): skipped",
                    path.display(),
                    object.line
                ));
                continue;
            }
            Err(Skip::Refused(why)) => return Err(at(object.line, why)),
        };
        objects.push(Object {
            name: ObjectName::Given(format!("{} (line {})", kind(object), object.line).into()),
            shape,
            material: materials.index(&object.material),
        });
    }
    let mut lights = Vec::with_capacity(scene.lights.len());
    for light in &scene.lights {
        let name = format!("{} light (line {})", kind_of_light(light.kind), light.line);
        lights.push(match light.kind {
            TestLightKind::Point { position } => Light::point(name, position, light.color),
            TestLightKind::Directional { direction } => {
                Light::directional(name, direction, light.color).ok_or_else(|| {
                    at(
                        light.line,
                        "a directional light needs a direction that is not zero".into(),
                    )
                })?
            }
        });
    }
    let c = scene.camera;
    Ok(SceneParts {
        camera: Camera {
            eye: c.eye,
            look_at: c.look_at,
            up: c.up,
            fov: c.fovy,
        },
        size: scene.size,
        settings,
        materials: materials.list,
        lights,
        objects,
        warnings,
        files: Vec::new(),
    })
}

fn kind(object: &TestObject) -> &'static str {
    match object.shape {
        TestShape::Sphere { .. } => "sphere",
        TestShape::Triangle { .. } => "tri",
        TestShape::NormalTriangle { .. } => "trinormal",
    }
}

fn kind_of_light(kind: TestLightKind) -> &'static str {
    match kind {
        TestLightKind::Point { .. } => "point",
        TestLightKind::Directional { .. } => "directional",
    }
}

enum Skip {
    /// A triangle without area: skipped with a warning.
    Degenerate(String),
    /// A shape raystep cannot hold: the file is refused.
    Refused(String),
}

fn shape(object: &TestObject) -> Result<Shape, Skip> {
    match &object.shape {
        // Turned and scaled alike on every axis it stays a sphere, else it
        // is an ellipsoid, intersected in its own space (MODEL §3).
        TestShape::Sphere {
            center,
            radius,
            transform,
            ..
        } => placed_sphere(*center, *radius, *transform).map_err(|e| Skip::Refused(e.0)),
        TestShape::Triangle { vertices } => Polygon::new(vertices.to_vec())
            .map(Shape::Polygon)
            .map_err(|e| Skip::Degenerate(e.0)),
        TestShape::NormalTriangle { vertices, normals } => {
            Patch::new(vertices.to_vec(), normals.to_vec())
                .map(Shape::Patch)
                .map_err(|e| Skip::Degenerate(e.0))
        }
    }
}

/// The materials of the objects, one for each distinct material state.
#[derive(Default)]
struct Materials {
    list: Vec<Material>,
    seen: HashMap<[u64; 13], usize>,
}

impl Materials {
    fn index(&mut self, m: &TestMaterial) -> usize {
        let key = bits(m);
        if let Some(&i) = self.seen.get(&key) {
            return i;
        }
        let i = self.list.len();
        self.list.push(material(i, m));
        self.seen.insert(key, i);
        i
    }
}

fn bits(m: &TestMaterial) -> [u64; 13] {
    let mut key = [0; 13];
    let values = [m.ambient, m.diffuse, m.specular, m.emission];
    for (i, v) in values.iter().flat_map(|v| v.to_array()).enumerate() {
        key[i] = v.to_bits();
    }
    key[12] = m.shininess.to_bits();
    key
}

/// CSE 167's material state in MODEL §1's terms: D = k_d O_d with k_d = 1,
/// S = k_s O_s with k_s = 1 (0 when S is black: no highlight and no
/// mirror ray), A the ambient term as it is, E added as it is.
fn material(index: usize, m: &TestMaterial) -> Material {
    let specular = m.specular != DVec3::ZERO;
    Material {
        name: format!("#{index}"),
        color: m.diffuse,
        kd: 1.0,
        ks: if specular { 1.0 } else { 0.0 },
        shininess: m.shininess,
        ambient: Some(m.ambient),
        emission: (m.emission != DVec3::ZERO).then_some(m.emission),
        specular_color: (specular && m.specular != DVec3::ONE).then_some(m.specular),
        ..Material::default_white()
    }
}
