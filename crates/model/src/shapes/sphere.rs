//! Sphere/ray intersection with the quadratic of the course notes (MODEL §1).

use glam::DVec3;
use serde::Serialize;

use super::{Aabb, GeometryError, Roots};
use crate::math::{Interval, Ray, exceeds};

#[derive(Clone, Debug, PartialEq)]
pub struct Sphere {
    pub center: DVec3,
    pub radius: f64,
}

/// Which root of the quadratic a ray took, and so why.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum RootChoice {
    /// The discriminant is negative: the ray's line misses the sphere.
    NoRealRoots,
    /// t0 is in front of the ray: it enters the sphere there.
    NearerRoot,
    /// t0 is behind (or at) the origin but t1 is in front: the ray starts inside.
    FartherRoot,
    /// Both roots are behind the ray's origin.
    BothBehind,
}

/// The working of the lecture: A t^2 + B t + C = 0 and its roots t0 <= t1.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SphereWorking {
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub discriminant: f64,
    /// Both roots, or `None` when the discriminant is negative.
    pub t0: Option<f64>,
    pub t1: Option<f64>,
    pub choice: RootChoice,
}

impl Sphere {
    pub fn new(center: DVec3, radius: f64) -> Result<Self, GeometryError> {
        if !exceeds(radius, 0.0) {
            return Err(GeometryError(format!(
                "sphere radius must be > 0, got {radius}"
            )));
        }
        Ok(Self { center, radius })
    }

    /// A = |d|^2, B = 2 d·(o - c), C = |o - c|^2 - r^2, the discriminant and roots.
    pub fn solve(&self, ray: &Ray, range: Interval) -> SphereWorking {
        let oc = ray.origin - self.center;
        let a = ray.direction.length_squared();
        let b = 2.0 * ray.direction.dot(oc);
        let c = oc.length_squared() - self.radius * self.radius;
        let discriminant = b * b - 4.0 * a * c;
        if discriminant < 0.0 {
            return SphereWorking {
                a,
                b,
                c,
                discriminant,
                t0: None,
                t1: None,
                choice: RootChoice::NoRealRoots,
            };
        }
        let root = discriminant.sqrt();
        let t0 = (-b - root) / (2.0 * a);
        let t1 = (-b + root) / (2.0 * a);
        let choice = if range.surrounds(t0) {
            RootChoice::NearerRoot
        } else if range.surrounds(t1) {
            RootChoice::FartherRoot
        } else {
            RootChoice::BothBehind
        };
        SphereWorking {
            a,
            b,
            c,
            discriminant,
            t0: Some(t0),
            t1: Some(t1),
            choice,
        }
    }

    pub fn roots(&self, ray: &Ray, range: Interval) -> Roots {
        let w = self.solve(ray, range);
        match (w.t0, w.t1) {
            (Some(t0), Some(t1)) => Roots::of_pair(t0, t1, range),
            _ => Roots::NONE,
        }
    }

    pub fn normal_at(&self, point: DVec3) -> DVec3 {
        (point - self.center) / self.radius
    }

    pub fn bounds(&self) -> Aabb {
        Aabb::new(
            self.center - DVec3::splat(self.radius),
            self.center + DVec3::splat(self.radius),
        )
    }
}

impl SphereWorking {
    /// The distance the ray takes, following `choice`.
    pub fn t(&self) -> Option<f64> {
        match self.choice {
            RootChoice::NearerRoot => self.t0,
            RootChoice::FartherRoot => self.t1,
            RootChoice::NoRealRoots | RootChoice::BothBehind => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_sphere_at_origin() -> Sphere {
        Sphere::new(DVec3::ZERO, 1.0).unwrap()
    }

    #[test]
    fn ray_from_outside_takes_the_nearer_root() {
        // o = (0,0,5), d = (0,0,-1), c = 0, r = 1.
        // A = 1, B = 2 * (0,0,-1)·(0,0,5) = -10, C = 25 - 1 = 24.
        // disc = 100 - 96 = 4; t0 = (10 - 2) / 2 = 4, t1 = (10 + 2) / 2 = 6.
        let ray = Ray::new(DVec3::new(0.0, 0.0, 5.0), DVec3::new(0.0, 0.0, -1.0));
        let w = unit_sphere_at_origin().solve(&ray, Interval::in_front());
        assert_eq!((w.a, w.b, w.c, w.discriminant), (1.0, -10.0, 24.0, 4.0));
        assert_eq!((w.t0, w.t1), (Some(4.0), Some(6.0)));
        assert_eq!(w.choice, RootChoice::NearerRoot);
        assert_eq!(w.t(), Some(4.0));
    }

    #[test]
    fn ray_from_inside_takes_the_farther_root() {
        // o = 0, d = (2,0,0) (not unit, as a secondary ray may be).
        // A = 4, B = 0, C = -1; disc = 0 + 16 = 16; t0 = -4/8 = -0.5, t1 = 0.5.
        let ray = Ray::new(DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0));
        let w = unit_sphere_at_origin().solve(&ray, Interval::in_front());
        assert_eq!((w.a, w.b, w.c, w.discriminant), (4.0, 0.0, -1.0, 16.0));
        assert_eq!((w.t0, w.t1), (Some(-0.5), Some(0.5)));
        assert_eq!(w.choice, RootChoice::FartherRoot);
        assert_eq!(w.t(), Some(0.5));
    }

    #[test]
    fn tangent_ray_has_a_double_root() {
        // o = (1,0,5), d = (0,0,-1): A = 1, B = -10, C = 1 + 25 - 1 = 25.
        // disc = 100 - 100 = 0; t0 = t1 = 5.
        let ray = Ray::new(DVec3::new(1.0, 0.0, 5.0), DVec3::new(0.0, 0.0, -1.0));
        let w = unit_sphere_at_origin().solve(&ray, Interval::in_front());
        assert_eq!(w.discriminant, 0.0);
        assert_eq!((w.t0, w.t1), (Some(5.0), Some(5.0)));
        assert_eq!(w.t(), Some(5.0));
    }

    #[test]
    fn missing_ray_has_a_negative_discriminant() {
        // o = (2,0,5), d = (0,0,-1): A = 1, B = -10, C = 4 + 25 - 1 = 28; disc = 100 - 112 = -12.
        let ray = Ray::new(DVec3::new(2.0, 0.0, 5.0), DVec3::new(0.0, 0.0, -1.0));
        let w = unit_sphere_at_origin().solve(&ray, Interval::in_front());
        assert_eq!(w.discriminant, -12.0);
        assert_eq!(w.choice, RootChoice::NoRealRoots);
        assert_eq!(w.t(), None);
    }

    #[test]
    fn sphere_behind_the_ray_is_not_hit() {
        // o = (0,0,5), d = (0,0,1): A = 1, B = 10, C = 24; disc = 4; t0 = -6, t1 = -4.
        let ray = Ray::new(DVec3::new(0.0, 0.0, 5.0), DVec3::new(0.0, 0.0, 1.0));
        let w = unit_sphere_at_origin().solve(&ray, Interval::in_front());
        assert_eq!((w.t0, w.t1), (Some(-6.0), Some(-4.0)));
        assert_eq!(w.choice, RootChoice::BothBehind);
        assert_eq!(w.t(), None);
    }

    #[test]
    fn shadow_ray_through_a_sphere_crosses_it_twice() {
        let ray = Ray::new(DVec3::new(0.0, 0.0, 5.0), DVec3::new(0.0, 0.0, -1.0));
        let roots = unit_sphere_at_origin().roots(&ray, Interval::new(1e-4, 10.0));
        assert_eq!(roots.as_slice(), &[4.0, 6.0]);
        // Only the first crossing lies before a light at distance 5.
        let roots = unit_sphere_at_origin().roots(&ray, Interval::new(1e-4, 5.0));
        assert_eq!(roots.as_slice(), &[4.0]);
    }

    #[test]
    fn non_positive_radius_is_rejected() {
        assert!(Sphere::new(DVec3::ZERO, 0.0).is_err());
        assert!(Sphere::new(DVec3::ZERO, -1.0).is_err());
        assert!(Sphere::new(DVec3::ZERO, f64::NAN).is_err());
    }
}
