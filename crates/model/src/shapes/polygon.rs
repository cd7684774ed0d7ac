//! Polygon/ray intersection as the course notes teach it (MODEL §1, §3): the
//! polygon's plane first, then the Jordan-curve crossing test in 2-D after
//! dropping the axis of the normal's largest component. Polygons may be
//! concave; they are never triangulated.

use glam::{DVec2, DVec3};
use serde::Serialize;

use super::plane::{Plane, PlaneWorking};
use super::{Aabb, GeometryError, Roots};
use crate::math::{Interval, Ray, exceeds};

/// The projected vertices are not kept: a mesh has hundreds of thousands of
/// polygons, and the accelerator's leaf record already holds a triangle's
/// (`accel::leaf_shapes`). The lecture's working projects them as it goes.
#[derive(Clone, Debug, PartialEq)]
pub struct Polygon {
    /// A boxed slice, not a `Vec`: no capacity word, 8 bytes a polygon.
    pub vertices: Box<[DVec3]>,
    /// The polygon's plane; its normal is the normalized (v1 - v0) x (v2 - v0).
    pub plane: Plane,
    pub dropped: Axis,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Axis {
    X,
    Y,
    Z,
}

/// The working of the lecture for one ray.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PolygonWorking {
    /// Step one: the polygon's plane.
    pub plane: PlaneWorking,
    /// Step two, only when the plane is hit: the crossing test.
    pub crossing: Option<CrossingTest>,
}

#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct CrossingTest {
    pub dropped_axis: Axis,
    /// The plane's hit point projected to (U, V); the vertices are translated by its negation.
    pub projected_point: [f64; 2],
    /// How many edges cross the +U axis: odd means inside.
    pub crossings: u32,
    pub inside: bool,
}

impl PolygonWorking {
    pub fn hit_t(&self) -> Option<f64> {
        match self.crossing {
            Some(test) if test.inside => self.plane.hit_t(),
            _ => None,
        }
    }
}

impl Axis {
    /// The axis of the largest absolute component; on a tie the first of x, y, z.
    pub(crate) fn dominant(v: DVec3) -> Axis {
        let a = v.abs();
        if a.x >= a.y && a.x >= a.z {
            Axis::X
        } else if a.y >= a.z {
            Axis::Y
        } else {
            Axis::Z
        }
    }

    /// (U, V): the two remaining coordinates in x-y-z order.
    pub fn project(self, p: DVec3) -> DVec2 {
        match self {
            Axis::X => DVec2::new(p.y, p.z),
            Axis::Y => DVec2::new(p.x, p.z),
            Axis::Z => DVec2::new(p.x, p.y),
        }
    }
}

/// Whether the edge from a to b (relative to the point) meets the line
/// V = 0: one end has V >= 0 and the other V < 0, so a vertex on the line
/// counts as above it.
#[inline]
pub(crate) fn straddles(a: DVec2, b: DVec2) -> bool {
    (a.y >= 0.0) != (b.y >= 0.0)
}

/// The U where a straddling edge from a to b meets V = 0.
#[inline]
pub(crate) fn u_at_axis(a: DVec2, b: DVec2) -> f64 {
    a.x - a.y * (b.x - a.x) / (b.y - a.y)
}

/// Whether the edge from a to b (relative to the point) crosses the +U axis.
#[inline]
pub fn crosses(a: DVec2, b: DVec2) -> bool {
    straddles(a, b) && u_at_axis(a, b) > 0.0
}

/// How many edges of the projected polygon cross the +U axis from `p`.
/// `projected` yields the vertices in (U, V), in order (at least one).
#[inline]
pub fn count_crossings(projected: impl DoubleEndedIterator<Item = DVec2> + Clone, p: DVec2) -> u32 {
    let mut crossings = 0;
    let Some(last) = projected.clone().next_back() else {
        return 0;
    };
    let mut a = last - p;
    for vertex in projected {
        let b = vertex - p;
        crossings += u32::from(crosses(a, b));
        a = b;
    }
    crossings
}

impl Polygon {
    pub fn new(vertices: Vec<DVec3>) -> Result<Self, GeometryError> {
        if vertices.len() < 3 {
            return Err(GeometryError(format!(
                "a polygon needs at least 3 vertices, got {}",
                vertices.len()
            )));
        }
        let cross = (vertices[1] - vertices[0]).cross(vertices[2] - vertices[0]);
        let extent = Aabb::around(&vertices).diagonal();
        if !exceeds(cross.length(), 1e-12 * extent * extent) {
            return Err(GeometryError(
                "vertices 0, 1 and 2 are collinear, so the normal (v1 - v0) x (v2 - v0) is undefined"
                    .into(),
            ));
        }
        let plane = Plane::new(cross, vertices[0])?;
        let tolerance = 1e-4 * extent;
        for (i, v) in vertices.iter().enumerate() {
            let distance = plane.normal.dot(*v) + plane.d;
            if distance.abs() > tolerance {
                return Err(GeometryError(format!(
                    "the polygon is not planar: vertex {i} lies {distance:.3e} from the plane of vertices 0, 1, 2"
                )));
            }
        }
        let dropped = Axis::dominant(plane.normal);
        Ok(Self {
            vertices: vertices.into_boxed_slice(),
            plane,
            dropped,
        })
    }

    pub fn solve(&self, ray: &Ray, range: Interval) -> PolygonWorking {
        let plane = self.plane.solve(ray, range);
        let crossing = plane.hit_t().map(|t| self.crossing_test(ray.at(t)));
        PolygonWorking { plane, crossing }
    }

    #[inline]
    pub(crate) fn roots(&self, ray: &Ray, range: Interval) -> Roots {
        Roots::of_one(self.solve(ray, range).hit_t())
    }

    /// Counts the edges that cross the +U axis once the point is moved to the
    /// origin. A vertex with V >= 0 is above the axis, so a vertex lying on it
    /// is counted once.
    #[inline]
    pub fn crossing_test(&self, point: DVec3) -> CrossingTest {
        let p = self.dropped.project(point);
        let crossings = count_crossings(self.projected(), p);
        CrossingTest {
            dropped_axis: self.dropped,
            projected_point: [p.x, p.y],
            crossings,
            inside: crossings % 2 == 1,
        }
    }

    /// The vertices projected to (U, V) by dropping `dropped`, in order.
    pub fn projected(
        &self,
    ) -> impl DoubleEndedIterator<Item = DVec2> + ExactSizeIterator + Clone + '_ {
        self.vertices.iter().map(|v| self.dropped.project(*v))
    }

    pub fn bounds(&self) -> Aabb {
        Aabb::around(&self.vertices)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn polygon(points: &[[f64; 3]]) -> Polygon {
        Polygon::new(points.iter().map(|p| DVec3::from_array(*p)).collect()).unwrap()
    }

    /// A ray straight down -z onto the z = 0 plane at (x, y).
    fn down_at(x: f64, y: f64) -> Ray {
        Ray::new(DVec3::new(x, y, 5.0), DVec3::new(0.0, 0.0, -1.0))
    }

    #[test]
    fn convex_square_inside_and_outside() {
        // Unit square, counter-clockwise seen from +z: normal (0,0,1), D = 0, drop z.
        let square = polygon(&[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ]);
        assert_eq!(square.dropped, Axis::Z);
        // Point (0.5, 0.5): vertices translated are (-.5,-.5) (.5,-.5) (.5,.5) (-.5,.5).
        // Edges crossing V = 0: (.5,-.5)->(.5,.5) at U = .5 > 0 (counts),
        // (-.5,.5)->(-.5,-.5) at U = -.5 (does not). One crossing: inside.
        let w = square.solve(&down_at(0.5, 0.5), Interval::in_front());
        assert_eq!(w.plane.t, Some(5.0));
        let test = w.crossing.unwrap();
        assert_eq!((test.crossings, test.inside), (1, true));
        assert_eq!(w.hit_t(), Some(5.0));
        // Point (-1, 0.5): both crossing edges at U = 2 and U = 1: two, outside.
        let test = square
            .solve(&down_at(-1.0, 0.5), Interval::in_front())
            .crossing
            .unwrap();
        assert_eq!((test.crossings, test.inside), (2, false));
    }

    #[test]
    fn concave_polygon_notch_is_outside() {
        // A "U" shape, counter-clockwise: the notch is x in (1, 2), y in (1, 3).
        let u_shape = polygon(&[
            [0.0, 0.0, 0.0],
            [3.0, 0.0, 0.0],
            [3.0, 3.0, 0.0],
            [2.0, 3.0, 0.0],
            [2.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
            [1.0, 3.0, 0.0],
            [0.0, 3.0, 0.0],
        ]);
        // (1.5, 2): edges crossing V = 0 (y = 2) are x = 3, x = 2 (the notch's right
        // side), x = 1 and x = 0. Right of the point (U > 0): x = 3 and x = 2: two, outside.
        let test = u_shape
            .solve(&down_at(1.5, 2.0), Interval::in_front())
            .crossing
            .unwrap();
        assert_eq!((test.crossings, test.inside), (2, false));
        // (0.5, 2): right of it x = 1, 2, 3: three, inside the left arm.
        let test = u_shape
            .solve(&down_at(0.5, 2.0), Interval::in_front())
            .crossing
            .unwrap();
        assert_eq!((test.crossings, test.inside), (3, true));
    }

    #[test]
    fn vertex_on_the_axis_is_counted_once() {
        // A diamond with vertices on the +U axis through the point (0, 0):
        // (2,0) lies exactly on the axis. V >= 0 counts as above, so the edges
        // (0,-1)->(2,0) crosses (below -> above) and (2,0)->(0,1) does not
        // (above -> above): one crossing, inside.
        let diamond = polygon(&[
            [0.0, -1.0, 0.0],
            [2.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [-2.0, 0.0, 0.0],
        ]);
        let test = diamond
            .solve(&down_at(0.0, 0.0), Interval::in_front())
            .crossing
            .unwrap();
        // The edge (-2,0)->(0,-1) goes above -> below at U = -2: not counted.
        assert_eq!((test.crossings, test.inside), (1, true));
        // Point (-3, 0): edges at U = 5 via the vertex (2,0) once, and U = 1 via (-2,0): 2, outside.
        let test = diamond
            .solve(&down_at(-3.0, 0.0), Interval::in_front())
            .crossing
            .unwrap();
        assert_eq!((test.crossings, test.inside), (2, false));
    }

    #[test]
    fn dropped_axis_follows_the_largest_normal_component() {
        // The plane x + 2y + 0.5z = 2 has normal (1,2,.5)/|..|: y is largest, so drop y.
        let tilted = polygon(&[[2.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 4.0]]);
        assert_eq!(tilted.dropped, Axis::Y);
        // (U, V) = (x, z) keep x-y-z order.
        assert_eq!(
            Axis::Y.project(DVec3::new(1.0, 2.0, 3.0)),
            DVec2::new(1.0, 3.0)
        );
        // A tie between x and y drops x.
        assert_eq!(Axis::dominant(DVec3::new(1.0, -1.0, 0.5)), Axis::X);
    }

    #[test]
    fn polygon_seen_from_behind_is_hit() {
        let square = polygon(&[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ]);
        let from_below = Ray::new(DVec3::new(0.5, 0.5, -2.0), DVec3::Z);
        let w = square.solve(&from_below, Interval::in_front());
        assert!(w.plane.faces_away);
        assert_eq!(w.hit_t(), Some(2.0));
    }

    #[test]
    fn degenerate_polygons_are_rejected() {
        let two = vec![DVec3::ZERO, DVec3::X];
        assert!(Polygon::new(two).unwrap_err().0.contains("at least 3"));
        let collinear = vec![DVec3::ZERO, DVec3::X, DVec3::X * 2.0, DVec3::Y];
        assert!(Polygon::new(collinear).unwrap_err().0.contains("collinear"));
        let bent = vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.5),
        ];
        assert!(Polygon::new(bent).unwrap_err().0.contains("not planar"));
    }
}
