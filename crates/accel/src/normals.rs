//! A compact copy of what a shape's geometric normal is computed from.
//!
//! The tracer asks for the normal at every hit. The objects themselves are
//! spread over more memory than a core's cache holds (about 1.4 MB for an
//! SPD scene: each object is 144 bytes, and a polygon's vertices lie
//! elsewhere on the heap), so reading them missed the cache at most hits.
//! The recipes of all objects sit side by side, 8 bytes each, and give the
//! same normal to the bit, computed by the same code. A triangle's or a
//! sphere's recipe is its leaf record in the hierarchy, which its hit has
//! just read (a recipe of its own was 40 bytes a triangle, a tenth of a
//! mesh's memory); other flat shapes' normals sit in a table of their own.

use glam::{DVec2, DVec3};

use raystep_model::shapes::{Axis, Shape, blended_normal};

#[derive(Clone, Debug)]
pub(crate) enum NormalRecipe {
    /// Triangles and spheres: the hierarchy's leaf record of the object
    /// holds what the normal is computed from (`Accel::leaf_normal`).
    FromLeaf,
    /// Planes and other polygons: the same normal everywhere, at this index
    /// of the table of flat normals.
    Flat(u32),
    /// A patch of three vertices (the SPD's smooth triangles).
    SmoothTriangle(Box<SmoothTriangle>),
    /// Anything else is computed from the shape itself.
    FromShape,
}

/// What `Patch::normal_at` reads of a patch of three vertices.
#[derive(Clone, Debug)]
pub(crate) struct SmoothTriangle {
    dropped: Axis,
    projected: [DVec2; 3],
    normals: [DVec3; 3],
    pub(crate) flat: DVec3,
}

impl NormalRecipe {
    /// The recipe of `shape`; a flat normal goes to the end of `flats`.
    pub(crate) fn of(shape: &Shape, flats: &mut Vec<DVec3>) -> NormalRecipe {
        let mut flat = |normal: DVec3| {
            flats.push(normal);
            NormalRecipe::Flat(
                u32::try_from(flats.len() - 1).expect("fewer objects than a u32 counts"),
            )
        };
        match shape {
            Shape::Plane(p) => flat(p.normal),
            // The leaf record of a polygon of three vertices is its triangle test.
            Shape::Polygon(p) if p.vertices.len() == 3 => NormalRecipe::FromLeaf,
            Shape::Polygon(p) => flat(p.plane.normal),
            Shape::Sphere(_) => NormalRecipe::FromLeaf,
            Shape::Patch(p) => {
                let (Ok(vertices), Ok(normals)) = (
                    <[DVec3; 3]>::try_from(&*p.polygon.vertices),
                    <[DVec3; 3]>::try_from(&*p.normals),
                ) else {
                    return NormalRecipe::FromShape;
                };
                let projected = vertices.map(|v| p.polygon.dropped.project(v));
                NormalRecipe::SmoothTriangle(Box::new(SmoothTriangle {
                    dropped: p.polygon.dropped,
                    projected,
                    normals,
                    flat: p.polygon.plane.normal,
                }))
            }
            Shape::Cone(_) | Shape::Ellipsoid(_) => NormalRecipe::FromShape,
        }
    }
}

impl SmoothTriangle {
    /// `Patch::normal_at(point)` of the patch this was made of.
    #[inline]
    pub(crate) fn normal_at(&self, point: DVec3) -> DVec3 {
        blended_normal(
            3,
            |i| self.projected[i],
            self.dropped,
            &self.normals,
            self.flat,
            point,
        )
    }
}
