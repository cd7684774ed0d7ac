//! The closed set of primitives, dispatched with one `match` (no virtual calls).
//! Every primitive answers three questions: where a ray first hits it, every
//! place a shadow segment crosses it, and the lecture's working for one ray.

mod cone;
mod crossing;
mod ellipsoid;
mod patch;
mod plane;
mod polygon;
mod sphere;

use glam::DVec3;
use serde::Serialize;

pub use cone::Cone;
pub use cone::ConeWorking;
pub use crossing::CrossingFigure;
pub use ellipsoid::{Ellipsoid, EllipsoidWorking, placed_sphere};
pub use patch::Patch;
pub use patch::{PatchWorking, blended_normal};
pub use plane::Plane;
pub use plane::PlaneWorking;
pub use polygon::{Axis, Polygon, crosses};
pub use polygon::{PolygonWorking, count_crossings};
pub use sphere::SphereWorking;
pub use sphere::{RootChoice, Sphere};

use crate::math::{Interval, Ray};

/// Every object holds one, so its size is paid by every triangle of a mesh:
/// the largest variant sets it. A cone (96 bytes) is boxed so a polygon or
/// patch (a boxed slice or two, the plane and the dropped axis) sets it;
/// so is an ellipsoid (its matrices).
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    Sphere(Sphere),
    Plane(Plane),
    Polygon(Polygon),
    Patch(Patch),
    Cone(Box<Cone>),
    Ellipsoid(Box<Ellipsoid>),
}

/// Geometry that cannot be intersected: the message says what is wrong.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct GeometryError(pub String);

/// The lecture's working for one ray and one primitive, kept for the ray tree.
/// Every hit, blocker and near miss holds one, so the largest variant sets
/// the trees' size: an ellipsoid's (its own-space numbers) is boxed.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "shape", rename_all = "snake_case")]
pub enum Working {
    Sphere(SphereWorking),
    Plane(PlaneWorking),
    Polygon(PolygonWorking),
    Patch(PatchWorking),
    Cone(ConeWorking),
    /// A sphere's working done in the sphere's own space (MODEL §3).
    Ellipsoid(Box<EllipsoidWorking>),
}

impl Working {
    /// A quadratic's two roots (sphere, ellipsoid, cylinder, cone) and which of them,
    /// 0 or 1, is nearer `t` (0 on a tie); none for a plane or polygon, or
    /// without real roots.
    pub fn nearer_root(&self, t: f64) -> Option<(usize, [f64; 2])> {
        let roots = match self {
            Working::Sphere(w) => [w.t0?, w.t1?],
            Working::Cone(w) => [w.t0?, w.t1?],
            Working::Ellipsoid(w) => [w.quadratic.t0?, w.quadratic.t1?],
            _ => return None,
        };
        let nearer = usize::from((t - roots[0]).abs() > (t - roots[1]).abs());
        Some((nearer, roots))
    }
}

/// Up to two ray distances where a segment crosses a surface, in increasing order.
#[derive(Clone, Copy, Debug)]
pub struct Roots {
    ts: [f64; 2],
    count: usize,
}

impl Roots {
    pub const NONE: Roots = Roots {
        ts: [0.0; 2],
        count: 0,
    };

    #[inline]
    pub fn of_one(t: Option<f64>) -> Roots {
        let mut roots = Roots::NONE;
        if let Some(t) = t {
            roots.push(t);
        }
        roots
    }

    /// The roots t0 <= t1 that lie in the range; a double root counts once.
    #[inline]
    fn of_pair(t0: f64, t1: f64, range: Interval) -> Roots {
        let mut roots = Roots::NONE;
        if range.surrounds(t0) {
            roots.push(t0);
        }
        if range.surrounds(t1) && t1 != t0 {
            roots.push(t1);
        }
        roots
    }

    #[inline]
    fn push(&mut self, t: f64) {
        self.ts[self.count] = t;
        self.count += 1;
    }

    #[inline]
    pub fn as_slice(&self) -> &[f64] {
        &self.ts[..self.count]
    }
}

impl Shape {
    /// The nearest distance in `range` where the ray hits the surface.
    #[inline]
    pub fn intersect(&self, ray: &Ray, range: Interval) -> Option<f64> {
        match self {
            Shape::Sphere(s) => s.solve(ray, range).t(),
            Shape::Plane(p) => p.solve(ray, range).hit_t(),
            Shape::Polygon(p) => p.solve(ray, range).hit_t(),
            Shape::Patch(p) => p.polygon.solve(ray, range).hit_t(),
            Shape::Cone(c) => c.solve(ray, range).t(),
            Shape::Ellipsoid(e) => e.solve(ray, range).t(),
        }
    }

    /// Every crossing of the segment `range` of the ray, for shadow rays.
    #[inline]
    pub fn roots(&self, ray: &Ray, range: Interval) -> Roots {
        match self {
            Shape::Sphere(s) => s.roots(ray, range),
            Shape::Plane(p) => p.roots(ray, range),
            Shape::Polygon(p) => p.roots(ray, range),
            Shape::Patch(p) => p.polygon.roots(ray, range),
            Shape::Cone(c) => c.roots(ray, range),
            Shape::Ellipsoid(e) => e.roots(ray, range),
        }
    }

    /// The same computation as `intersect`, with every intermediate value kept.
    pub fn working(&self, ray: &Ray, range: Interval) -> Working {
        match self {
            Shape::Sphere(s) => Working::Sphere(s.solve(ray, range)),
            Shape::Plane(p) => Working::Plane(p.solve(ray, range)),
            Shape::Polygon(p) => Working::Polygon(p.solve(ray, range)),
            Shape::Patch(p) => {
                let polygon = p.polygon.solve(ray, range);
                let located = polygon.hit_t().map(|t| p.locate(ray.at(t)));
                Working::Patch(PatchWorking {
                    polygon,
                    fan_triangle: located.map(|(i, _)| i),
                    barycentric: located.map(|(_, w)| w),
                })
            }
            Shape::Cone(c) => Working::Cone(c.solve(ray, range)),
            Shape::Ellipsoid(e) => Working::Ellipsoid(Box::new(e.working(ray, range))),
        }
    }

    /// N_g at a point of the surface, unit length, before facing the ray (MODEL §3).
    pub fn geometric_normal(&self, point: DVec3) -> DVec3 {
        match self {
            Shape::Sphere(s) => s.normal_at(point),
            Shape::Plane(p) => p.normal,
            Shape::Polygon(p) => p.plane.normal,
            Shape::Patch(p) => p.normal_at(point),
            Shape::Cone(c) => c.normal_at(point),
            Shape::Ellipsoid(e) => e.normal_at(point),
        }
    }

    /// The bounding box, or `None` for an unbounded plane.
    pub fn bounds(&self) -> Option<Aabb> {
        match self {
            Shape::Sphere(s) => Some(s.bounds()),
            Shape::Plane(_) => None,
            Shape::Polygon(p) => Some(p.bounds()),
            Shape::Patch(p) => Some(p.polygon.bounds()),
            Shape::Cone(c) => Some(c.bounds()),
            Shape::Ellipsoid(e) => Some(e.bounds()),
        }
    }

    /// The kind's name as shown to users ("sphere", "cylinder", ...).
    pub fn kind(&self) -> &'static str {
        match self {
            Shape::Sphere(_) => "sphere",
            Shape::Plane(_) => "plane",
            Shape::Polygon(_) => "polygon",
            Shape::Patch(_) => "patch",
            Shape::Cone(c) if c.is_cylinder() => "cylinder",
            Shape::Cone(_) => "cone",
            Shape::Ellipsoid(_) => "ellipsoid",
        }
    }
}

/// An axis-aligned bounding box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: DVec3,
    pub max: DVec3,
}

impl Aabb {
    pub const EMPTY: Aabb = Aabb {
        min: DVec3::INFINITY,
        max: DVec3::NEG_INFINITY,
    };

    pub fn new(min: DVec3, max: DVec3) -> Self {
        Self { min, max }
    }

    pub fn around(points: &[DVec3]) -> Self {
        points
            .iter()
            .fold(Aabb::EMPTY, |b, p| b.union(&Aabb::new(*p, *p)))
    }

    pub fn union(&self, other: &Aabb) -> Aabb {
        Aabb::new(self.min.min(other.min), self.max.max(other.max))
    }

    pub fn diagonal(&self) -> f64 {
        (self.max - self.min).length()
    }

    /// True when the point lies in the box, its faces included.
    pub fn contains(&self, point: DVec3) -> bool {
        point.cmpge(self.min).all() && point.cmple(self.max).all()
    }

    /// Whether the ray meets the box, faces included, for some t in `range`
    /// (the slab test). Used by the recorder only, never by a render.
    pub fn crossed_by(&self, ray: &Ray, range: Interval) -> bool {
        let (mut near, mut far) = (range.min, range.max);
        for axis in 0..3 {
            let (o, d) = (ray.origin[axis], ray.direction[axis]);
            let (lo, hi) = (self.min[axis], self.max[axis]);
            if d == 0.0 {
                if o < lo || o > hi {
                    return false;
                }
                continue;
            }
            let (t0, t1) = ((lo - o) / d, (hi - o) / d);
            near = near.max(t0.min(t1));
            far = far.min(t0.max(t1));
        }
        near <= far
    }

    pub fn centroid(&self) -> DVec3 {
        0.5 * (self.min + self.max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ray_crosses_a_box_only_within_its_range() {
        // The unit box [-1, 1]^3; a ray from (0.9, 0.9, 5) down -z is inside
        // it for t in [4, 6]; from (1.5, 0, 5) it never is (x stays 1.5).
        let b = Aabb::new(DVec3::splat(-1.0), DVec3::splat(1.0));
        let down = |x, y| Ray::new(DVec3::new(x, y, 5.0), DVec3::new(0.0, 0.0, -1.0));
        assert!(b.crossed_by(&down(0.9, 0.9), Interval::in_front()));
        assert!(b.crossed_by(&down(0.9, 0.9), Interval::new(1e-4, 4.5)));
        assert!(!b.crossed_by(&down(0.9, 0.9), Interval::new(1e-4, 3.5)));
        assert!(!b.crossed_by(&down(1.5, 0.0), Interval::in_front()));
        // Behind the origin: the ray from (0, 0, 5) up +z meets it at t in [-6, -4].
        let up = Ray::new(DVec3::new(0.0, 0.0, 5.0), DVec3::Z);
        assert!(!b.crossed_by(&up, Interval::in_front()));
    }
}
