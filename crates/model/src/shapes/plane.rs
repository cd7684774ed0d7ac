//! Infinite plane A x + B y + C z + D = 0 (MODEL §1). It has no bounds, so the
//! acceleration structure keeps planes aside and tests them on every ray.

use glam::DVec3;
use serde::Serialize;

use super::{GeometryError, Roots};
use crate::math::{Interval, Ray, exceeds};

#[derive(Clone, Debug, PartialEq)]
pub struct Plane {
    /// P_n = [A, B, C], unit length.
    pub normal: DVec3,
    pub d: f64,
}

/// The working of the lecture: v_d = P_n·d, v_0 = -(P_n·o + D), t = v_0 / v_d.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PlaneWorking {
    pub v_d: f64,
    pub v_0: f64,
    /// v_d = 0: the ray runs parallel to the plane.
    pub parallel: bool,
    /// v_d > 0: the plane faces away from the ray (still hit: surfaces are two-sided).
    pub faces_away: bool,
    /// The distance to the plane, when not parallel (negative: behind the ray).
    pub t: Option<f64>,
    /// t lies outside the accepted interval (behind the ray, or too far).
    pub behind: bool,
}

impl PlaneWorking {
    pub fn hit_t(&self) -> Option<f64> {
        if self.behind { None } else { self.t }
    }
}

impl Plane {
    /// The plane through `point` with the given normal (normalized here).
    pub fn new(normal: DVec3, point: DVec3) -> Result<Self, GeometryError> {
        let length = normal.length();
        if !exceeds(length, 0.0) || !length.is_finite() {
            return Err(GeometryError(format!(
                "plane normal must be non-zero, got {normal}"
            )));
        }
        let normal = normal / length;
        Ok(Self {
            normal,
            d: -normal.dot(point),
        })
    }

    pub fn solve(&self, ray: &Ray, range: Interval) -> PlaneWorking {
        let v_d = self.normal.dot(ray.direction);
        let v_0 = -(self.normal.dot(ray.origin) + self.d);
        if v_d == 0.0 {
            return PlaneWorking {
                v_d,
                v_0,
                parallel: true,
                faces_away: false,
                t: None,
                behind: true,
            };
        }
        let t = v_0 / v_d;
        PlaneWorking {
            v_d,
            v_0,
            parallel: false,
            faces_away: v_d > 0.0,
            t: Some(t),
            behind: !range.surrounds(t),
        }
    }

    #[inline]
    pub(crate) fn roots(&self, ray: &Ray, range: Interval) -> Roots {
        Roots::of_one(self.solve(ray, range).hit_t())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The floor y = -1: P_n = (0, 1, 0), D = 1.
    fn floor() -> Plane {
        Plane::new(DVec3::new(0.0, 2.0, 0.0), DVec3::new(5.0, -1.0, 3.0)).unwrap()
    }

    #[test]
    fn plane_in_front_facing_the_ray() {
        assert_eq!((floor().normal, floor().d), (DVec3::Y, 1.0));
        // o = (0, 1, 0), d = (0, -1, 0): v_d = -1, v_0 = -(1 + 1) = -2, t = 2.
        let ray = Ray::new(DVec3::new(0.0, 1.0, 0.0), DVec3::new(0.0, -1.0, 0.0));
        let w = floor().solve(&ray, Interval::in_front());
        assert_eq!((w.v_d, w.v_0, w.t), (-1.0, -2.0, Some(2.0)));
        assert!(!w.faces_away && !w.parallel && !w.behind);
        assert_eq!(w.hit_t(), Some(2.0));
    }

    #[test]
    fn parallel_ray_misses() {
        // d = (1, 0, 0): v_d = 0.
        let ray = Ray::new(DVec3::ZERO, DVec3::X);
        let w = floor().solve(&ray, Interval::in_front());
        assert!(w.parallel);
        assert_eq!(w.hit_t(), None);
    }

    #[test]
    fn plane_facing_away_is_still_hit() {
        // From below: o = (0, -3, 0), d = (0, 1, 0): v_d = 1 > 0 (faces away),
        // v_0 = -(-3 + 1) = 2, t = 2.
        let ray = Ray::new(DVec3::new(0.0, -3.0, 0.0), DVec3::Y);
        let w = floor().solve(&ray, Interval::in_front());
        assert!(w.faces_away);
        assert_eq!(w.hit_t(), Some(2.0));
    }

    #[test]
    fn plane_behind_the_ray_is_not_hit() {
        // o = (0, 1, 0), d = (0, 1, 0): v_d = 1, v_0 = -2, t = -2 < 0.
        let ray = Ray::new(DVec3::new(0.0, 1.0, 0.0), DVec3::Y);
        let w = floor().solve(&ray, Interval::in_front());
        assert_eq!(w.t, Some(-2.0));
        assert!(w.behind);
        assert_eq!(w.hit_t(), None);
    }

    #[test]
    fn zero_normal_is_rejected() {
        assert!(Plane::new(DVec3::ZERO, DVec3::ZERO).is_err());
    }
}
