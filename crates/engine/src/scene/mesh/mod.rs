//! Course meshes: triangles read from an OBJ file (with its MTL materials) or
//! an STL file, placed in a scene as polygons (flat) or patches (with the
//! OBJ's vertex normals), one object per triangle (MODEL §2 "Meshes").
//!
//! Each loader gives plain triangles in the file's coordinates; `placing.rs`
//! places them (scale, then rotate about x, y, z, then translate), skips the
//! degenerate ones, names each one and turns MTL emitters into point lights.

pub(crate) mod alone;
mod mtl;
mod obj;
mod obj_lines;
mod placing;
mod stl;

use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::{DMat3, DVec3};

use super::{Light, Material, Object, ObjectName, SceneError};
use crate::input_file::{self, Cap};
use raystep_model::object::MeshNames;

/// The largest mesh or MTL file read: far above a course mesh (a million
/// triangles of OBJ take about 60 MB, BENCHMARKS.md).
pub(crate) const MESH_CAP: Cap = Cap {
    bytes: 1 << 30,
    of: "a mesh or MTL file",
};

/// How far off its emitter's faces an MTL emitter's point light sits, as a
/// share of the emitter's bounding-box diagonal.
pub(crate) const EMITTER_OFFSET: f64 = 1e-3;

/// Where a mesh goes in the scene: scaled (uniformly, so normals keep their
/// directions), then rotated about x, then y, then z (degrees), then moved.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Placement {
    pub(crate) scale: f64,
    pub(crate) rotate: DVec3,
    pub(crate) translate: DVec3,
}

impl Default for Placement {
    fn default() -> Self {
        Self {
            scale: 1.0,
            rotate: DVec3::ZERO,
            translate: DVec3::ZERO,
        }
    }
}

impl Placement {
    fn rotation(&self) -> DMat3 {
        let r = self.rotate * (std::f64::consts::PI / 180.0);
        DMat3::from_rotation_z(r.z) * DMat3::from_rotation_y(r.y) * DMat3::from_rotation_x(r.x)
    }
}

/// One triangle as a loader reads it, in the file's coordinates.
#[derive(Clone, Debug)]
pub(crate) struct Triangle {
    pub(crate) vertices: [DVec3; 3],
    /// The OBJ's vertex normals (`vn`), when every corner has one.
    pub(crate) normals: Option<[DVec3; 3]>,
    /// Index into `Loaded::groups`.
    pub(crate) group: usize,
    /// Index into `Loaded::materials`, `None` for the default material.
    pub(crate) material: Option<usize>,
}

/// What a loader read: triangles, their groups' names and the MTL's materials.
#[derive(Debug, Default)]
pub(crate) struct Loaded {
    pub(crate) triangles: Vec<Triangle>,
    pub(crate) groups: Vec<String>,
    pub(crate) materials: Vec<mtl::Read>,
    pub(crate) warnings: Vec<String>,
    /// The MTL files its `mtllib` lines name, read or not.
    pub(crate) libraries: Vec<PathBuf>,
}

/// A mesh ready to join a scene: its objects (their material indices already
/// counted from `first_material`), the materials it adds, the lights its
/// emitters make, and what to warn about.
#[derive(Debug, Default)]
pub(crate) struct Placed {
    pub(crate) objects: Vec<Object>,
    /// The names its triangles' names start with: one per OBJ group.
    pub(crate) groups: Vec<String>,
    pub(crate) materials: Vec<Material>,
    pub(crate) lights: Vec<Light>,
    pub(crate) warnings: Vec<String>,
    /// The mesh file, then the MTL files it names (`Scene::files`).
    pub(crate) files: Vec<PathBuf>,
}

/// What the scene asks of one mesh.
pub(crate) struct Request<'a> {
    pub(crate) path: &'a Path,
    /// The scene's name for the mesh, put before each triangle's name.
    pub(crate) name: Option<&'a str>,
    pub(crate) placement: Placement,
    /// The scene's material for every triangle (overrides the MTL), as an
    /// index into the scene's materials.
    pub(crate) material: Option<usize>,
    /// How many materials the scene has before this mesh's.
    pub(crate) first_material: usize,
}

/// Whether `path` names a mesh file (`.obj` or `.stl`, any case).
pub(crate) fn is_mesh_file(path: &Path) -> bool {
    kind(path).is_some()
}

#[derive(Clone, Copy)]
enum Kind {
    Obj,
    Stl,
}

fn kind(path: &Path) -> Option<Kind> {
    let ext = path.extension()?.to_str()?.to_ascii_lowercase();
    match ext.as_str() {
        "obj" => Some(Kind::Obj),
        "stl" => Some(Kind::Stl),
        _ => None,
    }
}

/// Reads a file whole, refusing anything but a regular file within `MESH_CAP`.
pub(crate) fn read_file(path: &Path, what: &str) -> Result<Vec<u8>, String> {
    input_file::read(path, what, MESH_CAP).map_err(|e| e.to_string())
}

/// Reads and places one mesh.
pub(crate) fn load(request: &Request) -> Result<Placed, SceneError> {
    let path = request.path;
    let loaded = match kind(path) {
        Some(Kind::Obj) => obj::load(path)?,
        Some(Kind::Stl) => stl::load(path)?,
        None => {
            return Err(SceneError::plain(format!(
                "mesh file {} is neither .obj nor .stl",
                path.display()
            )));
        }
    };
    let triangles = loaded.triangles.len();
    let placed = placing::place(request, loaded)?;
    // A mesh that draws nothing is refused, in a scene as alone: a scene
    // rendered without it (a reference image, a student's) would look
    // finished, and a warning is easily missed in a grader's log.
    if placed.objects.is_empty() {
        let why = if triangles == 0 {
            "the file holds none".to_string()
        } else {
            format!("all {triangles} are degenerate (their vertices are collinear)")
        };
        return Err(SceneError::plain(format!(
            "{}: the mesh has no triangles to show: {why}",
            path.display()
        )));
    }
    Ok(placed)
}

/// Reads a mesh from bytes already in memory (the fuzz target's way in):
/// `path` only names it and picks the format; an OBJ's `mtllib` is not read.
pub fn load_bytes(path: &Path, bytes: &[u8]) -> Result<usize, SceneError> {
    let loaded = match kind(path) {
        Some(Kind::Stl) => stl::parse(path, bytes)?,
        _ => obj::parse(path, bytes, &|_| Err(tobj::LoadError::OpenFileFailed))?,
    };
    let request = Request {
        path,
        name: None,
        placement: Placement::default(),
        material: None,
        first_material: 0,
    };
    Ok(placing::place(&request, loaded)?.objects.len())
}

impl Placed {
    /// Puts `prefix` before every name, so that a second unnamed copy of a
    /// mesh doesn't repeat the first one's names.
    pub(crate) fn prefix_names(&mut self, prefix: &str) {
        // A mesh's triangles share one record of names: prefixed once.
        let mut renamed: Option<(Arc<MeshNames>, Arc<MeshNames>)> = None;
        for object in &mut self.objects {
            object.name = match &object.name {
                ObjectName::MeshTriangle { names, index } => {
                    let new = match &renamed {
                        Some((old, new)) if Arc::ptr_eq(old, names) => Arc::clone(new),
                        _ => {
                            let new = Arc::new(names.prefixed(prefix));
                            renamed = Some((Arc::clone(names), Arc::clone(&new)));
                            new
                        }
                    };
                    ObjectName::MeshTriangle {
                        names: new,
                        index: *index,
                    }
                }
                name => format!("{prefix}{name}").as_str().into(),
            };
        }
        for name in self
            .lights
            .iter_mut()
            .map(|l| &mut l.name)
            .chain(self.groups.iter_mut())
        {
            name.insert_str(0, prefix);
        }
    }
}

#[cfg(test)]
mod mesh_tests;
