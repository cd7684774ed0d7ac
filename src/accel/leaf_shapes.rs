//! Beside each entry of the leaves' object list, what its test reads, packed
//! in one record: a leaf's shapes are then tested from neighbouring memory,
//! without going through each object (its enum, and for polygons their
//! vertex `Vec`). Each record's test is the shape's own test, run on the same
//! numbers, so the answers are the same to the bit.

use crate::math::{Interval, Ray};
use crate::object::Object;
use crate::shapes::{Roots, Shape, Sphere, TriangleTest};

#[derive(Clone, Debug)]
pub(super) enum LeafShape {
    /// A polygon or patch of three vertices (most of the SPD's objects).
    Triangle(TriangleTest),
    Sphere(Sphere),
    /// Anything else is tested through its object.
    Other,
}

impl LeafShape {
    pub fn of(shape: &Shape) -> LeafShape {
        let triangle = match shape {
            Shape::Polygon(polygon) => TriangleTest::of(polygon),
            Shape::Patch(patch) => TriangleTest::of(&patch.polygon),
            Shape::Sphere(sphere) => return LeafShape::Sphere(sphere.clone()),
            _ => None,
        };
        triangle.map_or(LeafShape::Other, LeafShape::Triangle)
    }

    /// `Shape::intersect` of `objects[object]`, whose record this is.
    #[inline(always)]
    pub fn intersect(
        &self,
        objects: &[Object],
        object: usize,
        ray: &Ray,
        range: Interval,
    ) -> Option<f64> {
        match self {
            LeafShape::Triangle(triangle) => triangle.hit_t(ray, range),
            LeafShape::Sphere(sphere) => sphere.solve(ray, range).t(),
            LeafShape::Other => objects[object].shape.intersect(ray, range),
        }
    }

    /// `Shape::roots` of `objects[object]`, whose record this is.
    #[inline(always)]
    pub fn roots(&self, objects: &[Object], object: usize, ray: &Ray, range: Interval) -> Roots {
        match self {
            LeafShape::Triangle(triangle) => Roots::of_one(triangle.hit_t(ray, range)),
            LeafShape::Sphere(sphere) => sphere.roots(ray, range),
            LeafShape::Other => objects[object].shape.roots(ray, range),
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::shapes::{Cone, Polygon};

    #[test]
    fn each_record_answers_as_its_shape() {
        let shapes = [
            Shape::Sphere(Sphere::new(DVec3::new(0.2, -0.1, 0.3), 0.7).unwrap()),
            Shape::Polygon(
                Polygon::new(vec![
                    DVec3::ZERO,
                    DVec3::new(1.0, 0.2, 0.0),
                    DVec3::new(0.1, 1.0, 0.3),
                ])
                .unwrap(),
            ),
            Shape::Polygon(
                Polygon::new(vec![
                    DVec3::ZERO,
                    DVec3::X,
                    DVec3::new(1.0, 1.0, 0.0),
                    DVec3::Y,
                ])
                .unwrap(),
            ),
            Shape::Cone(Cone::new(DVec3::ZERO, 0.5, DVec3::new(0.0, 0.0, 1.0), 0.2).unwrap()),
        ];
        let kinds: Vec<&str> = shapes
            .iter()
            .map(|shape| match LeafShape::of(shape) {
                LeafShape::Triangle(_) => "triangle",
                LeafShape::Sphere(_) => "sphere",
                LeafShape::Other => "other",
            })
            .collect();
        assert_eq!(kinds, ["sphere", "triangle", "other", "other"]);
        let objects: Vec<Object> = shapes
            .into_iter()
            .map(|shape| Object {
                name: String::new(),
                shape,
                material: 0,
            })
            .collect();
        let mut hits = 0;
        for i in 0..400 {
            let f = f64::from(i);
            let origin = DVec3::new((f * 0.37).sin() * 3.0, (f * 0.23).cos() * 3.0, 2.0);
            let target = DVec3::new((f * 0.618).fract() - 0.3, (f * 0.414).fract() - 0.3, 0.2);
            let ray = Ray::new(origin, target - origin);
            for range in [Interval::in_front(), Interval::new(1e-4, 2.5)] {
                for (object, o) in objects.iter().enumerate() {
                    let record = LeafShape::of(&o.shape);
                    let expected = o.shape.intersect(&ray, range);
                    let got = record.intersect(&objects, object, &ray, range);
                    assert_eq!(got.map(f64::to_bits), expected.map(f64::to_bits), "{ray:?}");
                    let bits = |roots: Roots| {
                        roots
                            .as_slice()
                            .iter()
                            .map(|t| t.to_bits())
                            .collect::<Vec<_>>()
                    };
                    assert_eq!(
                        bits(record.roots(&objects, object, &ray, range)),
                        bits(o.shape.roots(&ray, range)),
                        "{ray:?}"
                    );
                    hits += usize::from(expected.is_some());
                }
            }
        }
        assert!(hits > 400, "{hits}");
    }
}
