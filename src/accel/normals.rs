//! A compact copy of what a shape's geometric normal is computed from.
//!
//! The tracer asks for the normal at every hit. The objects themselves are
//! spread over more memory than a core's cache holds (about 1.4 MB for an
//! SPD scene: each object is 152 bytes, and a patch's vertices and normals
//! lie elsewhere on the heap), so reading them missed the cache at most
//! hits. The recipes of all objects sit side by side, 40 bytes each, and give
//! the same normal to the bit, computed by the same code.

use glam::{DVec2, DVec3};

use crate::shapes::{Axis, Shape, Sphere, blended_normal};

#[derive(Clone, Debug)]
pub(crate) enum NormalRecipe {
    /// Planes and polygons: the same normal everywhere.
    Flat(DVec3),
    Sphere(Sphere),
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
    flat: DVec3,
}

impl NormalRecipe {
    pub(crate) fn of(shape: &Shape) -> NormalRecipe {
        match shape {
            Shape::Plane(p) => NormalRecipe::Flat(p.normal),
            Shape::Polygon(p) => NormalRecipe::Flat(p.plane.normal),
            Shape::Sphere(s) => NormalRecipe::Sphere(s.clone()),
            Shape::Patch(p) => {
                let (Ok(projected), Ok(normals)) = (
                    <[DVec2; 3]>::try_from(p.polygon.projected()),
                    <[DVec3; 3]>::try_from(p.normals.as_slice()),
                ) else {
                    return NormalRecipe::FromShape;
                };
                NormalRecipe::SmoothTriangle(Box::new(SmoothTriangle {
                    dropped: p.polygon.dropped,
                    projected,
                    normals,
                    flat: p.polygon.plane.normal,
                }))
            }
            Shape::Cone(_) => NormalRecipe::FromShape,
        }
    }

    /// `Shape::geometric_normal(point)` of the shape this recipe was made
    /// of, or `None` when it must be asked of the shape (`FromShape`).
    #[inline]
    pub(crate) fn normal_at(&self, point: DVec3) -> Option<DVec3> {
        match self {
            NormalRecipe::Flat(normal) => Some(*normal),
            NormalRecipe::Sphere(s) => Some(s.normal_at(point)),
            NormalRecipe::SmoothTriangle(t) => Some(blended_normal(
                &t.projected,
                t.dropped,
                &t.normals,
                t.flat,
                point,
            )),
            NormalRecipe::FromShape => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::{Cone, Patch, Plane, Polygon};

    #[test]
    fn each_recipe_gives_its_shapes_normal_to_the_bit() {
        let triangle = vec![
            DVec3::new(0.1, -0.2, 0.3),
            DVec3::new(1.3, 0.2, -0.1),
            DVec3::new(0.2, 0.9, 0.6),
        ];
        let normals = vec![
            DVec3::new(0.2, 0.1, 1.0),
            DVec3::new(-0.3, 0.4, 0.8),
            DVec3::new(0.1, -0.5, 0.9),
        ];
        let square = vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
        let shapes = [
            Shape::Sphere(Sphere::new(DVec3::new(0.2, -0.1, 0.3), 0.7).unwrap()),
            Shape::Plane(Plane::new(DVec3::new(0.3, 1.0, 0.2), DVec3::ZERO).unwrap()),
            Shape::Polygon(Polygon::new(triangle.clone()).unwrap()),
            Shape::Patch(Patch::new(triangle.clone(), normals).unwrap()),
            Shape::Patch(Patch::new(square.clone(), vec![DVec3::Z; 4]).unwrap()),
            Shape::Cone(Cone::new(DVec3::ZERO, 0.5, DVec3::Z, 0.2).unwrap()),
        ];
        let kinds: Vec<&str> = shapes
            .iter()
            .map(|shape| match NormalRecipe::of(shape) {
                NormalRecipe::Flat(_) => "flat",
                NormalRecipe::Sphere(_) => "sphere",
                NormalRecipe::SmoothTriangle(_) => "smooth triangle",
                NormalRecipe::FromShape => "from shape",
            })
            .collect();
        assert_eq!(
            kinds,
            [
                "sphere",
                "flat",
                "flat",
                "smooth triangle",
                "from shape",
                "from shape"
            ]
        );
        // Points on and off the triangle (its vertices, edges, inside and
        // outside, where the patch takes the nearest fan triangle).
        let mut compared = 0;
        for shape in &shapes {
            let recipe = NormalRecipe::of(shape);
            for i in 0..=12 {
                for j in 0..=12 {
                    let (u, v) = (f64::from(i) / 8.0 - 0.25, f64::from(j) / 8.0 - 0.25);
                    let point = triangle[0]
                        + u * (triangle[1] - triangle[0])
                        + v * (triangle[2] - triangle[0]);
                    let expected = shape.geometric_normal(point);
                    let got = recipe.normal_at(point).unwrap_or(expected);
                    let bits = |n: DVec3| n.to_array().map(f64::to_bits);
                    assert_eq!(bits(got), bits(expected), "{shape:?} at {point}");
                    compared += 1;
                }
            }
        }
        assert_eq!(compared, 6 * 13 * 13);
    }
}
