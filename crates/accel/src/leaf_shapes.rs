//! Beside each entry of the leaves' object list, what its test reads, packed
//! in one record: a leaf's shapes are then tested from neighbouring memory,
//! without going through each object (its enum, and for polygons their
//! vertex `Vec`). Each record's test is the shape's own test, run on the same
//! numbers, so the answers are the same to the bit. Many-sided polygons are
//! tested through their object, with their edges sorted into bands.

use glam::{DVec2, DVec3};

use super::cylinder_reach::CylinderReach;
use super::edge_bands::EdgeBands;
use raystep_model::math::{Interval, Ray};
use raystep_model::object::Object;
use raystep_model::shapes::{Axis, Plane, Polygon, Roots, Shape, Sphere, count_crossings};

#[derive(Clone, Debug)]
pub(super) enum LeafShape {
    /// A polygon or patch of three vertices (most of the SPD's objects).
    Triangle(TriangleTest),
    Sphere(Sphere),
    /// A polygon or patch of many vertices (the SPD gears' faces): its
    /// edges sorted into bands of V.
    Banded(Box<EdgeBands>),
    /// A cylinder (the SPD rings): most rays that reach one's box pass
    /// clear of it, and are told so here (`cylinder_reach`); the others
    /// are tested through the object.
    Cylinder(CylinderReach),
    /// Anything else is tested through its object.
    Other,
}

impl LeafShape {
    pub(crate) fn of(shape: &Shape) -> LeafShape {
        let polygon = match shape {
            Shape::Polygon(polygon) => polygon,
            Shape::Patch(patch) => &patch.polygon,
            Shape::Sphere(sphere) => return LeafShape::Sphere(sphere.clone()),
            Shape::Cone(cone) => {
                return CylinderReach::of(cone).map_or(LeafShape::Other, LeafShape::Cylinder);
            }
            _ => return LeafShape::Other,
        };
        if let Some(triangle) = TriangleTest::of(polygon) {
            return LeafShape::Triangle(triangle);
        }
        EdgeBands::new(polygon.projected().collect())
            .map_or(LeafShape::Other, |bands| LeafShape::Banded(Box::new(bands)))
    }

    /// `Shape::geometric_normal(point)` of the triangle or sphere whose
    /// record this is (the same numbers, so the same bits); `None` for the
    /// others.
    #[inline]
    pub(crate) fn normal_at(&self, point: DVec3) -> Option<DVec3> {
        match self {
            LeafShape::Triangle(triangle) => Some(triangle.plane.normal),
            LeafShape::Sphere(sphere) => Some(sphere.normal_at(point)),
            LeafShape::Banded(_) | LeafShape::Cylinder(_) | LeafShape::Other => None,
        }
    }

    /// `Shape::intersect` of `objects[object]`, whose record this is.
    #[inline(always)]
    pub(crate) fn intersect(
        &self,
        objects: &[Object],
        object: usize,
        ray: &Ray,
        range: Interval,
    ) -> Option<f64> {
        match self {
            LeafShape::Triangle(triangle) => triangle.hit_t(ray, range),
            LeafShape::Sphere(sphere) => sphere.solve(ray, range).t(),
            LeafShape::Banded(bands) => banded_hit_t(&objects[object].shape, bands, ray, range),
            LeafShape::Cylinder(reach) if reach.misses(ray) => None,
            LeafShape::Cylinder(_) | LeafShape::Other => {
                objects[object].shape.intersect(ray, range)
            }
        }
    }

    /// `Shape::roots` of `objects[object]`, whose record this is.
    #[inline(always)]
    pub(crate) fn roots(
        &self,
        objects: &[Object],
        object: usize,
        ray: &Ray,
        range: Interval,
    ) -> Roots {
        match self {
            LeafShape::Triangle(triangle) => Roots::of_one(triangle.hit_t(ray, range)),
            LeafShape::Sphere(sphere) => sphere.roots(ray, range),
            LeafShape::Cylinder(reach) if reach.misses(ray) => Roots::NONE,
            LeafShape::Banded(_) | LeafShape::Cylinder(_) | LeafShape::Other => {
                self.rare_roots(objects, object, ray, range)
            }
        }
    }

    /// `roots` of the records tested through their object, out of line:
    /// inlined, they kept the shadow walk's leaf loop from being inlined,
    /// which cost 2 % of the instructions of a scene of triangles.
    #[inline(never)]
    fn rare_roots(&self, objects: &[Object], object: usize, ray: &Ray, range: Interval) -> Roots {
        let shape = &objects[object].shape;
        match self {
            LeafShape::Banded(bands) => Roots::of_one(banded_hit_t(shape, bands, ray, range)),
            _ => shape.roots(ray, range),
        }
    }
}

/// A three-vertex polygon's test with everything it reads in one place: the
/// BVH keeps these beside its leaves, so a leaf's triangles are tested from
/// neighbouring memory instead of through each object's own allocations.
/// It runs the same steps on the same numbers as `Polygon::solve`, so it
/// answers the same to the bit (a test checks).
#[derive(Clone, Debug)]
pub(super) struct TriangleTest {
    pub(super) plane: Plane,
    pub(super) dropped: Axis,
    pub(super) projected: [DVec2; 3],
}

impl TriangleTest {
    /// The test of a polygon that is a triangle.
    pub(crate) fn of(polygon: &Polygon) -> Option<TriangleTest> {
        Some(TriangleTest {
            plane: polygon.plane.clone(),
            dropped: polygon.dropped,
            projected: <[DVec3; 3]>::try_from(&*polygon.vertices)
                .ok()?
                .map(|v| polygon.dropped.project(v)),
        })
    }

    /// `Polygon::solve(ray, range).hit_t()`.
    #[inline(always)]
    pub(crate) fn hit_t(&self, ray: &Ray, range: Interval) -> Option<f64> {
        let t = self.plane.solve(ray, range).hit_t()?;
        let p = self.dropped.project(ray.at(t));
        (count_crossings(self.projected.iter().copied(), p) % 2 == 1).then_some(t)
    }

    /// `Plane::solve`'s v_0 for rays from `origin`, the same for every ray
    /// of a packet (`packet`): -(N . o + d).
    #[inline(always)]
    pub(crate) fn v_0(&self, origin: DVec3) -> f64 {
        -(self.plane.normal.dot(origin) + self.plane.d)
    }

    /// `hit_t(ray, range)` given `v_0(ray.origin)`: the same steps
    /// (`Plane::solve`'s, then the crossings), the same bits. The scalar
    /// reference of the packets' test (`packet_triangles`), which its
    /// tests compare it with.
    #[cfg(test)]
    pub(crate) fn hit_t_given(&self, v_0: f64, ray: &Ray, range: Interval) -> Option<f64> {
        let v_d = self.plane.normal.dot(ray.direction);
        if v_d == 0.0 {
            return None;
        }
        let t = v_0 / v_d;
        if !range.surrounds(t) {
            return None;
        }
        let p = self.dropped.project(ray.at(t));
        (count_crossings(self.projected.iter().copied(), p) % 2 == 1).then_some(t)
    }
}

/// `Polygon::solve(ray, range).hit_t()` of the polygon (or patch) `shape`,
/// whose edges `bands` sorts: the same steps, inside or outside read from
/// the bands' grid, or where it cannot tell, the crossings counted over the
/// edges of the hit's band only.
fn banded_hit_t(shape: &Shape, bands: &EdgeBands, ray: &Ray, range: Interval) -> Option<f64> {
    let polygon = match shape {
        Shape::Polygon(polygon) => polygon,
        Shape::Patch(patch) => &patch.polygon,
        _ => unreachable!("bands are made of polygons and patches only"),
    };
    let t = polygon.plane.solve(ray, range).hit_t()?;
    let p = polygon.dropped.project(ray.at(t));
    bands.inside(p).then_some(t)
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use raystep_model::shapes::{Cone, Polygon};

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
            Shape::Cone(Box::new(
                Cone::new(DVec3::ZERO, 0.5, DVec3::new(0.0, 0.0, 1.0), 0.2).unwrap(),
            )),
            Shape::Cone(Box::new(
                Cone::new(
                    DVec3::new(0.1, 0.0, 0.0),
                    0.3,
                    DVec3::new(0.2, 0.1, 0.9),
                    0.3,
                )
                .unwrap(),
            )),
            // A concave star of 24 points around (0.2, 0.2) at z = 0.2, radii
            // alternating 0.5 and 0.2: many-sided, so its edges are banded.
            Shape::Polygon(
                Polygon::new(
                    (0..24)
                        .map(|i| {
                            let angle = f64::from(i) * std::f64::consts::TAU / 24.0;
                            let r = if i % 2 == 0 { 0.5 } else { 0.2 };
                            DVec3::new(0.2 + r * angle.cos(), 0.2 + r * angle.sin(), 0.2)
                        })
                        .collect(),
                )
                .unwrap(),
            ),
        ];
        let kinds: Vec<&str> = shapes
            .iter()
            .map(|shape| match LeafShape::of(shape) {
                LeafShape::Triangle(_) => "triangle",
                LeafShape::Sphere(_) => "sphere",
                LeafShape::Banded(_) => "banded",
                LeafShape::Cylinder(_) => "cylinder",
                LeafShape::Other => "other",
            })
            .collect();
        assert_eq!(
            kinds,
            ["sphere", "triangle", "other", "other", "cylinder", "banded"]
        );
        let objects: Vec<Object> = shapes
            .into_iter()
            .map(|shape| Object {
                name: "".into(),
                shape,
                material: 0,
            })
            .collect();
        let mut hits = vec![0; objects.len()];
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
                    hits[object] += usize::from(expected.is_some());
                }
            }
        }
        // Every record is met, and missed, many times (of 800 queries each).
        assert!(hits.iter().all(|&h| h > 40 && h < 760), "{hits:?}");
    }

    #[test]
    fn the_triangle_test_answers_as_the_polygon_does_to_the_bit() {
        // Rays from a grid of origins through a grid of targets, some on the
        // triangles' vertices and edges, so that ties and the V >= 0 rule
        // are exercised as well as clear hits and misses.
        let polygon = |points: &[[f64; 3]]| {
            Polygon::new(points.iter().map(|p| DVec3::from_array(*p)).collect()).unwrap()
        };
        let triangles = [
            polygon(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]),
            polygon(&[[2.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 4.0]]),
            polygon(&[[0.3, -0.7, 0.2], [-0.4, 0.9, 0.5], [0.8, 0.6, -0.9]]),
        ];
        assert!(
            TriangleTest::of(&polygon(&[
                [0.0; 3],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0]
            ]))
            .is_none()
        );
        let (mut hits, mut misses) = (0, 0);
        for triangle in &triangles {
            let test = TriangleTest::of(triangle).unwrap();
            for i in 0..=20 {
                for j in 0..=20 {
                    let target = DVec3::new(i as f64 / 10.0 - 0.5, j as f64 / 10.0 - 0.5, 0.25);
                    for origin in [DVec3::new(0.1, 0.2, 3.0), DVec3::new(-2.0, 0.5, -1.0)] {
                        let ray = Ray::new(origin, target - origin);
                        for range in [Interval::in_front(), Interval::new(1e-4, 0.9)] {
                            let expected = triangle.solve(&ray, range).hit_t();
                            let got = test.hit_t(&ray, range);
                            assert_eq!(
                                got.map(f64::to_bits),
                                expected.map(f64::to_bits),
                                "{ray:?}"
                            );
                            if expected.is_some() {
                                hits += 1;
                            } else {
                                misses += 1;
                            }
                        }
                    }
                }
            }
            // Through each vertex and each edge's midpoint exactly.
            let v = &triangle.vertices;
            for point in [v[0], v[1], v[2], (v[0] + v[1]) / 2.0, (v[1] + v[2]) / 2.0] {
                let ray = Ray::new(
                    point + DVec3::new(0.3, 0.1, 2.0),
                    -DVec3::new(0.3, 0.1, 2.0),
                );
                let expected = triangle.solve(&ray, Interval::in_front()).hit_t();
                let got = test.hit_t(&ray, Interval::in_front());
                assert_eq!(got.map(f64::to_bits), expected.map(f64::to_bits), "{ray:?}");
            }
        }
        assert!(hits > 200 && misses > 200, "{hits} hits, {misses} misses");
    }
}
