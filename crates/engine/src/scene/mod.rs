//! The scene as the tracer sees it: camera, settings, materials, lights and
//! named objects, whatever file format it was read from.

pub mod builtin;
mod error;
mod light;
pub(crate) mod limits;
pub mod mesh;
pub(crate) mod nff;
pub mod overrides;
mod profile;
mod switches;
pub mod test_format;
pub(crate) mod toml_format;
mod toml_sections;

use std::borrow::Cow;
use std::path::{Path, PathBuf};

use glam::DVec3;
use serde::Serialize;

pub use error::SceneError;
pub use light::{Light, LightKind};
pub use profile::Profile;
pub use switches::{DEEPEST_TOGGLED_DEPTH, Switch, Switches};

use crate::input_file::{self, Cap};
use raystep_accel::{Accel, ObjectTables};
use raystep_model::camera::Camera;
use raystep_model::math::Color;
use raystep_model::math::exceeds;
use raystep_model::mistakes::Mistakes;
pub use raystep_model::object::{Object, ObjectName};

/// The largest image side accepted; beyond it a render would take minutes and
/// gigabytes, which is never what a teaching scene wants.
pub(crate) const MAX_IMAGE_SIDE: u32 = 16_384;
/// The largest number of pixels accepted (a 8192 x 8192 image).
pub(crate) const MAX_IMAGE_PIXELS: u64 = 8192 * 8192;

/// The largest scene file read (TOML or NFF): a million spheres take 76 MB
/// of TOML, a million triangles 88 MB of NFF (BENCHMARKS.md), and a device
/// such as `/dev/zero` is refused before this matters.
pub(crate) const SCENE_CAP: Cap = Cap {
    bytes: 256 << 20,
    of: "a scene file",
};

/// Below half an 8-bit step, like POV-Ray's adc_bailout (1/255): a ray worth
/// less than this changes a pixel by at most about half a step per unit of colour.
pub(crate) const DEFAULT_MIN_WEIGHT: f64 = 1.0 / 512.0;
/// Rays per pixel tree by default: a full binary tree of depth 12 has 4095.
pub(crate) const DEFAULT_MAX_RAYS: u32 = 4096;
/// The largest `max_rays` accepted: bounds a pixel's time and recording.
pub(crate) const MAX_RAYS_LIMIT: u32 = 65_536;

/// Blinn's N·H (the default) or Phong's R·V for the specular term (MODEL §1, §4).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SpecularModel {
    #[default]
    Blinn,
    Phong,
}

/// Scene-wide constants of the illumination model. The scene carries its
/// file's; the tracer takes the ones to use beside the scene, so the
/// debugger's toggles never copy the scene.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Settings {
    pub background: Color,
    /// I_a.
    pub ambient: Color,
    /// (c1, c2, c3) of f_att for lights.
    pub light_attenuation: [f64; 3],
    /// (a1, a2, a3) of the distance attenuation of secondary rays.
    pub ray_attenuation: [f64; 3],
    /// The primary ray has depth 1; hits at depth < max_depth spawn secondary rays.
    pub max_depth: u32,
    /// A secondary ray whose accumulated weight (the product of the weights
    /// from the primary ray down) is below this is not cast (MODEL §5).
    pub min_weight: f64,
    /// The most rays (primary, reflected, transmitted) one pixel's tree may
    /// hold; further secondary rays are not cast (MODEL §5).
    pub max_rays: u32,
    pub specular: SpecularModel,
    /// Which equation the scene means (MODEL §11); the lecture's by default,
    /// which JSON leaves out, as files written before profiles had it.
    #[serde(skip_serializing_if = "Profile::is_lecture")]
    pub profile: Profile,
    pub switches: Switches,
    /// Classic student mistakes to trace with (none in a scene file; `compare`
    /// and the debugger set them).
    pub mistakes: Mistakes,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            background: Color::ZERO,
            ambient: Color::ZERO,
            light_attenuation: [1.0, 0.0, 0.0],
            ray_attenuation: [1.0, 0.0, 0.0],
            max_depth: 5,
            min_weight: DEFAULT_MIN_WEIGHT,
            max_rays: DEFAULT_MAX_RAYS,
            specular: SpecularModel::Blinn,
            profile: Profile::Lecture,
            switches: Switches::default(),
            mistakes: Mistakes::NONE,
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    pub name: String,
    /// O_d, the object's diffuse colour.
    pub color: Color,
    pub kd: f64,
    pub ks: f64,
    /// The specular exponent n.
    pub(crate) shininess: f64,
    pub kt: f64,
    pub ior: f64,
    pub ka: f64,
    /// Overrides the scene's specular model for this material (to show both side by side).
    pub specular: Option<SpecularModel>,
    /// Whether k_s also weights a mirror-reflected ray (MODEL §5); false for
    /// a material with highlights but no mirror (TOML `reflect = false`,
    /// MTL `illum` 2).
    pub reflects: bool,
    /// The ambient term as it is, in place of k_a I_a O_d (MODEL §1): a
    /// material's own ambient colour (TOML `ambient`, CSE 167's `ambient`).
    pub ambient: Option<Color>,
    /// E, a colour the surface adds as it is (TOML `emission`); it lights
    /// nothing else. `None` for black, so that the lecture's materials
    /// cost the tracer one test.
    pub emission: Option<Color>,
    /// O_s, the specular term's colour (TOML `specular_color`); under the
    /// cse167 profile it weighs the mirror ray too. `None` for white.
    pub specular_color: Option<Color>,
}

impl Material {
    /// NFF's material before the first `f` line: white, k_d = 1, all else 0 (MODEL §4).
    pub(crate) fn default_white() -> Self {
        Self {
            name: "default".into(),
            color: Color::ONE,
            kd: 1.0,
            ks: 0.0,
            shininess: 0.0,
            kt: 0.0,
            ior: 1.0,
            ka: 1.0,
            specular: None,
            reflects: true,
            ambient: None,
            emission: None,
            specular_color: None,
        }
    }
}

/// A scene ready to trace: validated, with its acceleration structure built.
#[derive(Clone, Debug)]
pub struct Scene {
    pub camera: Camera,
    pub width: u32,
    pub height: u32,
    pub settings: Settings,
    pub materials: Vec<Material>,
    pub lights: Vec<Light>,
    pub objects: Vec<Object>,
    pub(crate) accel: Accel,
    /// Each object's material and normal recipe, read without the object.
    tables: ObjectTables,
    /// What reading the scene's meshes warned about, each once (MODEL §4).
    pub warnings: Vec<String>,
    /// The files it was read from: the scene file, then every mesh and MTL
    /// file it names (an MTL even when missing), so that no output of a
    /// command can replace one of them. None for the built-in scene.
    pub files: Vec<PathBuf>,
}

/// A scene as read from its file, before its acceleration structure is
/// built: `load` frees the file's text first, so that text and structure
/// are never in memory together (the text of a big mesh is about 90 bytes a
/// triangle).
pub(crate) struct SceneParts {
    pub(crate) camera: Camera,
    pub(crate) size: (u32, u32),
    pub(crate) settings: Settings,
    pub(crate) materials: Vec<Material>,
    pub(crate) lights: Vec<Light>,
    pub(crate) objects: Vec<Object>,
    pub(crate) warnings: Vec<String>,
    /// `Scene::files`.
    pub(crate) files: Vec<PathBuf>,
}

impl SceneParts {
    pub(crate) fn build(self) -> Scene {
        let mut scene = Scene::new(
            self.camera,
            self.size,
            self.settings,
            self.materials,
            self.lights,
            self.objects,
        );
        scene.warnings = self.warnings;
        scene.files = self.files;
        scene
    }
}

impl Scene {
    /// The scene of a file's parts, with its acceleration structure built.
    pub(crate) fn new(
        camera: Camera,
        (width, height): (u32, u32),
        settings: Settings,
        materials: Vec<Material>,
        lights: Vec<Light>,
        objects: Vec<Object>,
    ) -> Scene {
        let accel = Accel::build(&objects);
        let tables = ObjectTables::build(&objects);
        Scene {
            camera,
            width,
            height,
            settings,
            materials,
            lights,
            objects,
            accel,
            tables,
            warnings: Vec::new(),
            files: Vec::new(),
        }
    }

    /// The same scene rendered at another size (the field of view is kept).
    pub fn with_size(mut self, width: u32, height: u32) -> Result<Scene, SceneError> {
        check_image_size(width, height).map_err(SceneError::plain)?;
        self.width = width;
        self.height = height;
        Ok(self)
    }

    /// The same scene without one object (the others keep their order, one
    /// place lower past it): what a ray that misses the object meets.
    pub fn without(&self, object: usize) -> Scene {
        let mut objects = self.objects.clone();
        objects.remove(object);
        let size = (self.width, self.height);
        let (materials, lights) = (self.materials.clone(), self.lights.clone());
        Scene::new(self.camera, size, self.settings, materials, lights, objects)
    }

    pub fn material_of(&self, object: usize) -> &Material {
        &self.materials[self.tables.material(object)]
    }

    /// An object's name for messages, "?" for an index the scene lacks.
    pub fn object_name(&self, object: usize) -> Cow<'_, str> {
        self.objects
            .get(object)
            .map_or(Cow::Borrowed("?"), |o| o.name.text())
    }

    /// `object`'s N_g at `point` and, for a patch, its plane normal (its
    /// side, MODEL §3), in one look-up of the object tables.
    #[inline]
    pub(crate) fn normals(&self, object: usize, point: DVec3) -> (DVec3, Option<DVec3>) {
        self.tables
            .normals(&self.objects, &self.accel, object, point)
    }
}

/// Reads a scene file, choosing the format by extension (`.nff`, a mesh
/// alone for `.obj` and `.stl`, else TOML).
pub fn load(path: &Path) -> Result<Scene, SceneError> {
    if mesh::is_mesh_file(path) {
        // Its files are the mesh's: the mesh itself first.
        return mesh::alone::scene(path);
    }
    let mut parts = {
        let bytes =
            input_file::read(path, "", SCENE_CAP).map_err(|e| SceneError::plain(e.to_string()))?;
        let text = String::from_utf8(bytes)
            .map_err(|e| invalid_utf8(path, e.as_bytes(), "scene files"))?;
        parse_parts(path, &text)?
    };
    parts.files.insert(0, path.to_owned());
    Ok(parts.build())
}

/// `bytes` as text, or where they stop being UTF-8 (`invalid_utf8`):
/// `files` says what must be text ("OBJ files").
pub(crate) fn utf8_text<'a>(
    path: &Path,
    bytes: &'a [u8],
    files: &str,
) -> Result<&'a str, SceneError> {
    std::str::from_utf8(bytes).map_err(|_| invalid_utf8(path, bytes, files))
}

/// Where a file stops being UTF-8 text: the first bad byte's line and column,
/// with the line shown with U+FFFD in place of its bad bytes.
fn invalid_utf8(path: &Path, bytes: &[u8], files: &str) -> SceneError {
    let Err(e) = std::str::from_utf8(bytes) else {
        unreachable!("called only on bytes that are not UTF-8")
    };
    let bad = e.valid_up_to();
    let line_end = bytes[bad..]
        .iter()
        .position(|&b| b == b'\n')
        .map_or(bytes.len(), |i| bad + i);
    // The valid prefix is unchanged by the lossy conversion, so `bad` is
    // where the first U+FFFD starts.
    let text = String::from_utf8_lossy(&bytes[..line_end]);
    SceneError::at(
        path,
        &text,
        bad..bad + char::REPLACEMENT_CHARACTER.len_utf8(),
        format!(
            "invalid UTF-8 (byte 0x{:02X}): {files} must be UTF-8 text",
            bytes[bad]
        ),
    )
}

/// Parses scene text; `path` names it in messages and picks the format.
pub fn parse(path: &Path, text: &str) -> Result<Scene, SceneError> {
    parse_parts(path, text).map(SceneParts::build)
}

/// `parse` without building the acceleration structure.
fn parse_parts(path: &Path, text: &str) -> Result<SceneParts, SceneError> {
    let is_nff = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("nff"));
    let is_test = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("test"));
    if is_test {
        return test_format::to_scene(path, test_format::parse(text, path)?);
    }
    if is_nff {
        nff::parse(path, text)
    } else {
        toml_format::parse(path, text)
    }
}

/// Refuses empty or absurd image sizes, saying why.
pub fn check_image_size(width: u32, height: u32) -> Result<(), String> {
    if width == 0 || height == 0 {
        return Err(format!(
            "image size {width}x{height} is empty: both sides must be at least 1"
        ));
    }
    if width > MAX_IMAGE_SIDE || height > MAX_IMAGE_SIDE {
        return Err(format!(
            "image size {width}x{height} is too large: each side may be at most {MAX_IMAGE_SIDE} pixels"
        ));
    }
    if width as u64 * height as u64 > MAX_IMAGE_PIXELS {
        return Err(format!(
            "image size {width}x{height} is too large: at most {MAX_IMAGE_PIXELS} pixels (8192 x 8192) are rendered"
        ));
    }
    Ok(())
}

/// Refuses a field of view outside (0, 180) degrees.
pub(crate) fn check_fov(fov: f64) -> Result<(), String> {
    if fov > 0.0 && fov < 180.0 {
        Ok(())
    } else {
        Err(format!(
            "fov must be between 0 and 180 degrees (exclusive), got {fov}"
        ))
    }
}

/// Refuses a camera whose frame is undefined.
pub(crate) fn check_camera(camera: &Camera) -> Result<(), String> {
    check_fov(camera.fov)?;
    let forward = camera.look_at - camera.eye;
    if !exceeds(forward.length(), 0.0) {
        return Err(format!(
            "camera eye and look_at are the same point {}",
            camera.eye
        ));
    }
    if !exceeds(
        forward.cross(camera.up).length(),
        1e-12 * forward.length() * camera.up.length(),
    ) {
        return Err(format!(
            "camera up {} is zero or parallel to the viewing direction {}",
            camera.up, forward
        ));
    }
    Ok(())
}
