//! Open cylinder or truncated cone between two end circles (NFF `c`): the
//! lateral surface only, no end caps. Substituting the ray into the surface
//! gives a quadratic, solved in the same spirit as the sphere's.

use glam::DVec3;
use serde::Serialize;

use super::{Aabb, GeometryError, Roots};
use crate::math::{Interval, Ray, exceeds};

#[derive(Clone, Debug, PartialEq)]
pub struct Cone {
    pub base: DVec3,
    pub base_radius: f64,
    pub apex: DVec3,
    pub apex_radius: f64,
    /// Unit axis from base to apex, and the distance between them.
    pub axis: DVec3,
    height: f64,
    /// How fast the radius grows per unit along the axis (0 for a cylinder).
    slope: f64,
}

/// The working: with s the height of a point along the axis and r(s) the radius
/// there, |p_perp|^2 = r(s)^2 becomes A t^2 + B t + C = 0; a root counts only
/// when its height lies between the two ends, 0 <= s <= h.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ConeWorking {
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub discriminant: f64,
    pub t0: Option<f64>,
    pub t1: Option<f64>,
    /// The heights of the two roots along the axis (0 at the base, h at the apex end).
    pub s0: Option<f64>,
    pub s1: Option<f64>,
    pub height: f64,
    /// Whether each root is in front of the ray and between the two ends.
    pub on_surface: [bool; 2],
}

impl ConeWorking {
    /// The root taken: the nearer one that lies on the surface.
    pub(crate) fn t(&self) -> Option<f64> {
        match self.on_surface {
            [true, _] => self.t0,
            [false, true] => self.t1,
            [false, false] => None,
        }
    }
}

impl Cone {
    pub fn new(
        base: DVec3,
        base_radius: f64,
        apex: DVec3,
        apex_radius: f64,
    ) -> Result<Self, GeometryError> {
        let height = (apex - base).length();
        if !exceeds(height, 0.0) {
            return Err(GeometryError("the cone's two ends coincide".into()));
        }
        if base_radius < 0.0 || apex_radius < 0.0 || !exceeds(base_radius.max(apex_radius), 0.0) {
            return Err(GeometryError(format!(
                "cone radii must be >= 0 and not both 0, got {base_radius} and {apex_radius}"
            )));
        }
        Ok(Self {
            base,
            base_radius,
            apex,
            apex_radius,
            axis: (apex - base) / height,
            height,
            slope: (apex_radius - base_radius) / height,
        })
    }

    pub fn is_cylinder(&self) -> bool {
        self.base_radius == self.apex_radius
    }

    pub(crate) fn solve(&self, ray: &Ray, range: Interval) -> ConeWorking {
        let delta = ray.origin - self.base;
        let (delta_s, d_s) = (delta.dot(self.axis), ray.direction.dot(self.axis));
        let delta_perp = delta - delta_s * self.axis;
        let d_perp = ray.direction - d_s * self.axis;
        // r(s(t)) = r0 + rk t, with s(t) = delta_s + t d_s.
        let r0 = self.base_radius + self.slope * delta_s;
        let rk = self.slope * d_s;
        let a = d_perp.length_squared() - rk * rk;
        let b = 2.0 * (delta_perp.dot(d_perp) - r0 * rk);
        let c = delta_perp.length_squared() - r0 * r0;
        let discriminant = b * b - 4.0 * a * c;
        let mut working = ConeWorking {
            a,
            b,
            c,
            discriminant,
            t0: None,
            t1: None,
            s0: None,
            s1: None,
            height: self.height,
            on_surface: [false, false],
        };
        let (t0, t1) = if a == 0.0 {
            // The ray runs parallel to a line of the surface: B t + C = 0.
            if b == 0.0 {
                return working;
            }
            let t = -c / b;
            (t, t)
        } else if discriminant < 0.0 {
            return working;
        } else {
            let root = discriminant.sqrt();
            let (ta, tb) = ((-b - root) / (2.0 * a), (-b + root) / (2.0 * a));
            (ta.min(tb), ta.max(tb))
        };
        let height_at = |t: f64| delta_s + t * d_s;
        let valid = |t: f64| {
            let s = height_at(t);
            // r0 + rk t >= 0 keeps the nappe of the cone that lies between the ends.
            range.surrounds(t) && (0.0..=self.height).contains(&s) && r0 + rk * t >= 0.0
        };
        working.t0 = Some(t0);
        working.t1 = Some(t1);
        working.s0 = Some(height_at(t0));
        working.s1 = Some(height_at(t1));
        working.on_surface = [valid(t0), valid(t1) && t1 != t0];
        working
    }

    #[inline]
    pub(crate) fn roots(&self, ray: &Ray, range: Interval) -> Roots {
        let w = self.solve(ray, range);
        let mut roots = Roots::NONE;
        for (t, on_surface) in [w.t0, w.t1].into_iter().zip(w.on_surface) {
            if let (Some(t), true) = (t, on_surface) {
                roots.push(t);
            }
        }
        roots
    }

    /// The outward normal of the lateral surface: radial, tilted along the axis
    /// by the slope for a cone.
    pub(crate) fn normal_at(&self, point: DVec3) -> DVec3 {
        let delta = point - self.base;
        let radial = delta - delta.dot(self.axis) * self.axis;
        (radial.normalize_or_zero() - self.slope * self.axis).normalize_or_zero()
    }

    pub(crate) fn bounds(&self) -> Aabb {
        // Each end circle lies in the box centre +- r * sqrt(1 - axis_i^2).
        let extent = |r: f64| {
            r * (DVec3::ONE - self.axis * self.axis)
                .max(DVec3::ZERO)
                .powf(0.5)
        };
        let (eb, ea) = (extent(self.base_radius), extent(self.apex_radius));
        Aabb::new(
            (self.base - eb).min(self.apex - ea),
            (self.base + eb).max(self.apex + ea),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cylinder_hit_from_the_side() {
        // Cylinder along +z from z = 0 to z = 2, radius 1. Ray o = (-3, 0, 1), d = (1, 0, 0).
        // delta = (-3,0,1), delta_s = 1, d_s = 0; delta_perp = (-3,0,0), d_perp = (1,0,0).
        // slope 0: r0 = 1, rk = 0. A = 1, B = 2 * (-3) = -6, C = 9 - 1 = 8.
        // disc = 36 - 32 = 4; t0 = (6 - 2) / 2 = 2, t1 = 4; heights s = 1 for both.
        let cylinder = Cone::new(DVec3::ZERO, 1.0, DVec3::new(0.0, 0.0, 2.0), 1.0).unwrap();
        assert!(cylinder.is_cylinder());
        let ray = Ray::new(DVec3::new(-3.0, 0.0, 1.0), DVec3::X);
        let w = cylinder.solve(&ray, Interval::in_front());
        assert_eq!((w.a, w.b, w.c, w.discriminant), (1.0, -6.0, 8.0, 4.0));
        assert_eq!((w.t0, w.t1, w.s0), (Some(2.0), Some(4.0), Some(1.0)));
        assert_eq!(w.t(), Some(2.0));
        // Hit point (-1, 0, 1): outward normal (-1, 0, 0).
        assert_eq!(cylinder.normal_at(ray.at(2.0)), DVec3::new(-1.0, 0.0, 0.0));
        assert_eq!(
            cylinder.roots(&ray, Interval::in_front()).as_slice(),
            &[2.0, 4.0]
        );
    }

    #[test]
    fn open_cylinder_seen_past_its_end_is_missed() {
        // Same cylinder, ray at height 3 (above the top end): both roots have s = 3 > 2.
        let cylinder = Cone::new(DVec3::ZERO, 1.0, DVec3::new(0.0, 0.0, 2.0), 1.0).unwrap();
        let ray = Ray::new(DVec3::new(-3.0, 0.0, 3.0), DVec3::X);
        assert_eq!(cylinder.solve(&ray, Interval::in_front()).t(), None);
    }

    #[test]
    fn open_cylinder_seen_down_its_axis_hits_the_inside() {
        // Ray from (0.5, 0, 5) down -z, inside the tube: delta_perp = (.5,0,0), d_perp = 0.
        // A = 0 and B = 0: parallel to the surface lines, no hit.
        let cylinder = Cone::new(DVec3::ZERO, 1.0, DVec3::new(0.0, 0.0, 2.0), 1.0).unwrap();
        let ray = Ray::new(DVec3::new(0.5, 0.0, 5.0), DVec3::new(0.0, 0.0, -1.0));
        assert_eq!(cylinder.solve(&ray, Interval::in_front()).t(), None);
        // A slanted ray entering the open top from (0, 0, 3) towards (1, 0, 1):
        // d = (1, 0, -2)/sqrt5. It first meets the wall at x = 1, inside the tube.
        let d = DVec3::new(1.0, 0.0, -2.0).normalize();
        let ray = Ray::new(DVec3::new(0.0, 0.0, 3.0), d);
        let t = cylinder.solve(&ray, Interval::in_front()).t().unwrap();
        // x = t / sqrt5 = 1 -> t = sqrt5; z = 3 - 2 = 1, within the ends.
        assert!((t - 5f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn cone_hit_and_tilted_normal() {
        // Cone from base (0,0,0) radius 1 to apex (0,0,1) radius 0: slope = -1.
        // Ray o = (-2, 0, 0.5), d = (1,0,0). delta_s = 0.5, d_s = 0.
        // r0 = 1 - 0.5 = 0.5, rk = 0. A = 1, B = 2 * (-2) = -4, C = 4 - 0.25 = 3.75.
        // disc = 16 - 15 = 1; t0 = (4 - 1)/2 = 1.5, t1 = 2.5. Hit (-0.5, 0, 0.5).
        let cone = Cone::new(DVec3::ZERO, 1.0, DVec3::Z, 0.0).unwrap();
        let ray = Ray::new(DVec3::new(-2.0, 0.0, 0.5), DVec3::X);
        let w = cone.solve(&ray, Interval::in_front());
        assert_eq!((w.a, w.b, w.c, w.discriminant), (1.0, -4.0, 3.75, 1.0));
        assert_eq!(w.t(), Some(1.5));
        // Normal: radial (-1,0,0) minus slope * axis = (-1, 0, 1), normalized.
        let n = cone.normal_at(ray.at(1.5));
        assert!((n - DVec3::new(-1.0, 0.0, 1.0) / 2f64.sqrt()).length() < 1e-15);
    }

    #[test]
    fn the_other_nappe_is_not_hit() {
        // Beyond the apex the quadratic describes a mirrored cone; with s > h it is cut anyway.
        let cone = Cone::new(DVec3::ZERO, 1.0, DVec3::Z, 0.0).unwrap();
        let ray = Ray::new(DVec3::new(-2.0, 0.0, 1.5), DVec3::X);
        assert_eq!(cone.solve(&ray, Interval::in_front()).t(), None);
    }

    #[test]
    fn degenerate_cones_are_rejected() {
        assert!(
            Cone::new(DVec3::ONE, 1.0, DVec3::ONE, 1.0)
                .unwrap_err()
                .0
                .contains("coincide")
        );
        assert!(Cone::new(DVec3::ZERO, 0.0, DVec3::Z, 0.0).is_err());
        assert!(Cone::new(DVec3::ZERO, -1.0, DVec3::Z, 1.0).is_err());
    }
}
