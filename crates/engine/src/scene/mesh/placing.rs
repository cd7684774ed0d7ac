//! A loaded mesh placed in the scene, step by step: its MTL materials join
//! the scene's, each triangle is moved into place, checked against the
//! scene's bounds, made a polygon or patch (or skipped when degenerate),
//! given its material and its name; then each MTL emitter becomes a point
//! light at the area-weighted centre of its triangles.

use std::fmt::Write as _;
use std::sync::Arc;

use glam::{DMat3, DVec3};

use super::{EMITTER_OFFSET, Loaded, Placed, Placement, Request, Triangle, mtl};
use crate::scene::limits::COORDINATE;
use crate::scene::{Light, Material, Object, ObjectName, SceneError};
use raystep_model::object::MeshNames;
use raystep_model::shapes::{Aabb, Patch, Polygon, Shape};

/// Places `loaded` as `request` asks.
pub(super) fn place(request: &Request, loaded: Loaded) -> Result<Placed, SceneError> {
    let Loaded {
        triangles,
        groups,
        materials: mtl_materials,
        warnings,
        libraries,
    } = loaded;
    let path = request.path;
    let mut placed = Placed {
        warnings,
        files: std::iter::once(path.to_owned()).chain(libraries).collect(),
        ..Placed::default()
    };
    let mut materials = MeshMaterials::add(request, &mtl_materials, &mut placed);
    let prefix = request.name.map(|n| format!("{n} ")).unwrap_or_default();
    // A mesh named as its own group ("pyramid" holding solid "pyramid") is
    // not named twice.
    placed.groups = groups
        .iter()
        .map(|g| match request.name {
            Some(name) if name == g => g.clone(),
            _ => format!("{prefix}{g}"),
        })
        .collect();
    // Triangles are numbered per group name: tobj starts the same object
    // again at each `usemtl`, and its numbers started again from 0 ("crate
    // triangle 1" named three triangles).
    let first_of_name: Vec<usize> = {
        let mut first = std::collections::HashMap::new();
        (groups.iter().enumerate())
            .map(|(g, name)| *first.entry(name.as_str()).or_insert(g))
            .collect()
    };
    let transform = Transform::new(&request.placement);
    let mut naming = Naming::new(&placed.groups, &mtl_materials);
    let mut emitters = vec![EmitterSums::default(); mtl_materials.len()];
    let mut per_group = vec![0usize; groups.len()];
    let mut degenerate = 0usize;
    placed.objects.reserve(triangles.len());
    for t in &triangles {
        // A triangle's number in its group counts the skipped ones too.
        let number = per_group[first_of_name[t.group]];
        per_group[first_of_name[t.group]] += 1;
        let vertices = t.vertices.map(|p| transform.point(p));
        check_bounds(&vertices, || {
            format!("{}: {} triangle {number}", path.display(), groups[t.group])
        })?;
        let Some(shape) = shape(t, vertices, &transform) else {
            degenerate += 1;
            continue;
        };
        // The MTL material the triangle keeps: none when the scene's
        // material overrides the file's.
        let own = t.material.filter(|_| request.material.is_none());
        let material = materials.scene_index(request.material, own, &mut placed.materials);
        if let Some(m) = own
            && mtl_materials[m].emission.is_some()
        {
            emitters[m].add(&vertices);
        }
        naming.push(placed.objects.len(), t.group, number, own);
        placed.objects.push(Object {
            // Set by `naming.name`, once the mesh's names are complete.
            name: ObjectName::Given(Box::default()),
            shape,
            material,
        });
    }
    naming.name(&mut placed.objects);
    if degenerate > 0 {
        placed.warnings.push(format!(
            "{}: {degenerate} degenerate triangle(s) skipped (their vertices are collinear)",
            path.display()
        ));
    }
    for (read, sums) in mtl_materials.iter().zip(&emitters) {
        if read.emission.is_some() {
            placed.lights.extend(sums.light(&prefix, read));
        }
    }
    Ok(placed)
}

/// Scale, then rotation, then translation (`Placement`).
struct Transform {
    rotation: DMat3,
    scale: f64,
    translate: DVec3,
}

impl Transform {
    fn new(placement: &Placement) -> Transform {
        Transform {
            rotation: placement.rotation(),
            scale: placement.scale,
            translate: placement.translate,
        }
    }

    /// A point of the file in the scene.
    fn point(&self, p: DVec3) -> DVec3 {
        self.rotation * (p * self.scale) + self.translate
    }

    /// A normal of the file in the scene: the scale is uniform, so only
    /// the rotation turns it.
    fn normal(&self, n: DVec3) -> DVec3 {
        self.rotation * n
    }
}

/// Refuses a placed triangle with a vertex outside the scene's bounds,
/// naming it by `triangle()`.
fn check_bounds(
    vertices: &[DVec3; 3],
    triangle: impl FnOnce() -> String,
) -> Result<(), SceneError> {
    let outside = |v: &&DVec3| v.to_array().iter().any(|c| COORDINATE.check(*c).is_err());
    match vertices.iter().find(outside) {
        None => Ok(()),
        Some(v) => Err(SceneError::plain(format!(
            "{}: vertex {v} lies outside the scene's bounds once placed (coordinates {}..{})",
            triangle(),
            COORDINATE.min,
            COORDINATE.max
        ))),
    }
}

/// The placed triangle as a patch (with the file's vertex normals) or a
/// polygon; `None` when it is degenerate.
fn shape(t: &Triangle, vertices: [DVec3; 3], transform: &Transform) -> Option<Shape> {
    let shape = match t.normals {
        Some(normals) => Patch::new(
            vertices.to_vec(),
            normals.map(|n| transform.normal(n)).to_vec(),
        )
        .map(Shape::Patch),
        None => Polygon::new(vertices.to_vec()).map(Shape::Polygon),
    };
    shape.ok()
}

/// Where the mesh's materials are among the scene's.
struct MeshMaterials {
    /// The scene's index of each MTL material.
    of_mtl: Vec<usize>,
    /// The default white, once a triangle with no material asked for it.
    default: Option<usize>,
    /// How many materials the scene has before this mesh's.
    first: usize,
}

impl MeshMaterials {
    /// Adds the MTL's materials to `placed`, with their warnings.
    fn add(request: &Request, read: &[mtl::Read], placed: &mut Placed) -> MeshMaterials {
        let first = request.first_material;
        let mut of_mtl = Vec::with_capacity(read.len());
        for m in read {
            let (material, warnings) = mtl::to_model(m);
            for w in warnings {
                let path = request.path.display();
                (placed.warnings).push(format!("{path}: material `{}`: {w}", m.name));
            }
            of_mtl.push(first + placed.materials.len());
            placed.materials.push(material);
        }
        MeshMaterials {
            of_mtl,
            default: None,
            first,
        }
    }

    /// The scene's material for a triangle: the scene's own for the mesh
    /// (`forced`), else the triangle's MTL material (`own`), else the
    /// default white, added to `materials` the first time.
    fn scene_index(
        &mut self,
        forced: Option<usize>,
        own: Option<usize>,
        materials: &mut Vec<Material>,
    ) -> usize {
        match (forced, own) {
            (Some(m), _) => m,
            (None, Some(m)) => self.of_mtl[m],
            (None, None) => *self.default.get_or_insert_with(|| {
                materials.push(Material::default_white());
                self.first + materials.len() - 1
            }),
        }
    }
}

/// The triangles' names: most share one `MeshNames` record (the group,
/// the number in it, the MTL material); a triangle whose numbers do not
/// fit it is named in full.
struct Naming<'a> {
    names: MeshNames,
    groups: &'a [String],
    materials: &'a [mtl::Read],
    /// The objects named in full, by their place in the mesh's objects.
    in_full: Vec<(usize, String)>,
}

impl<'a> Naming<'a> {
    fn new(groups: &'a [String], materials: &'a [mtl::Read]) -> Naming<'a> {
        let names = MeshNames::new(
            groups.to_vec(),
            materials.iter().map(|m| m.name.clone()).collect(),
        );
        Naming {
            names,
            groups,
            materials,
            in_full: Vec::new(),
        }
    }

    /// Names the mesh's object `object`: triangle `number` of `group`,
    /// with its MTL `material`.
    fn push(&mut self, object: usize, group: usize, number: usize, material: Option<usize>) {
        if self.names.push(group, number, material).is_some() {
            return;
        }
        let mut name = format!("{} triangle {number}", self.groups[group]);
        if let Some(m) = material {
            let _ = write!(name, " (material {})", self.materials[m].name);
        }
        self.in_full.push((object, name));
    }

    /// Gives each of `objects` its name.
    fn name(self, objects: &mut [Object]) {
        let names = Arc::new(self.names);
        // `push` numbered the others in order from 0: object i is name i
        // less the objects named in full before it.
        let mut in_full = self.in_full.into_iter().peekable();
        let mut index = 0u32;
        for (i, object) in objects.iter_mut().enumerate() {
            object.name = match in_full.next_if(|(at, _)| *at == i) {
                Some((_, name)) => name.as_str().into(),
                None => {
                    index += 1;
                    ObjectName::MeshTriangle {
                        names: Arc::clone(&names),
                        index: index - 1,
                    }
                }
            };
        }
    }
}

/// What an MTL emitter's triangles add up to, for its light.
#[derive(Clone, Copy)]
struct EmitterSums {
    /// Each triangle's centre times its area.
    weighted_centres: DVec3,
    area: f64,
    /// The sum of its faces' (v1 - v0) x (v2 - v0): the side they face.
    normal: DVec3,
    bounds: Aabb,
}

impl Default for EmitterSums {
    fn default() -> Self {
        EmitterSums {
            weighted_centres: DVec3::ZERO,
            area: 0.0,
            normal: DVec3::ZERO,
            bounds: Aabb::EMPTY,
        }
    }
}

impl EmitterSums {
    fn add(&mut self, vertices: &[DVec3; 3]) {
        let cross = (vertices[1] - vertices[0]).cross(vertices[2] - vertices[0]);
        let area = cross.length() / 2.0;
        let centre = (vertices[0] + vertices[1] + vertices[2]) / 3.0;
        self.weighted_centres += centre * area;
        self.area += area;
        self.normal += cross;
        self.bounds = self.bounds.union(&Aabb::around(vertices));
    }

    /// The emitter `read`'s point light, `None` when it has no area. The
    /// light sits just off the emitter, on the side its faces' winding
    /// faces, so that its own faces never shadow what it lights.
    fn light(&self, prefix: &str, read: &mtl::Read) -> Option<Light> {
        if self.area <= 0.0 {
            return None;
        }
        let offset = self.normal.normalize_or_zero() * (EMITTER_OFFSET * self.bounds.diagonal());
        Some(Light::point(
            format!("{prefix}light (Ke of material {})", read.name),
            self.weighted_centres / self.area + offset,
            read.emission.unwrap_or_default() * mtl::EMITTER_INTENSITY,
        ))
    }
}
