//! A quick "certainly missed" for cylinders, tested before the cylinder's
//! own quadratic: a ray whose line passes farther from the cylinder's axis
//! line than its radius, by a wide margin, meets no point of it.
//!
//! The line o + t d passes at distance D = |w . n| / |n| from the axis line
//! through the base b along the unit axis a, with w = b - o and n = d x a.
//! Every point of the cylinder lies within its radius R of that line. So
//! when D > R no root exists; and the lecture's test (`Cone::solve`) finds
//! none either, as long as D^2 - R^2 exceeds the rounding of its
//! discriminant: B^2 - 4AC, whose two terms are each at most
//! 4 |d_perp|^2 |w|^2 and are rounded to about 2^-51 of that, against an
//! exact value of -4 |d_perp|^2 (D^2 - R^2). The reject asks for
//! D^2 > R^2 (1 + 2^-20) + 2^-40 |w|^2, a margin some 2^9 times that
//! rounding, and so stays clear of it with the rounding of its own few
//! products too; and only where the ray is not nearly parallel to the
//! axis (|n|^2 > 2^-30 |d|^2), where the error of w . n (about 2^-50
//! |w| |d|) could otherwise reach the margin. Rays it does not reject are
//! tested by the lecture's code, so the answers are the same bits.
//!
//! Cones are left to their own test: near a ray parallel to one of the
//! cone's lines, its roots are ill-conditioned, and a margin on the axis
//! distance alone would not bound where they land.

use glam::DVec3;

use raystep_model::math::Ray;
use raystep_model::shapes::Cone;

/// Relative margins of the reject (see the module's comment).
const RADIUS_MARGIN: f64 = 1.0 + 1.0 / (1u64 << 20) as f64;
const DISTANCE_MARGIN: f64 = 1.0 / (1u64 << 40) as f64;
const PARALLEL: f64 = 1.0 / (1u64 << 30) as f64;

#[derive(Clone, Debug)]
pub(super) struct CylinderReach {
    base: DVec3,
    axis: DVec3,
    /// R^2 (1 + 2^-20).
    reach_squared: f64,
}

impl CylinderReach {
    /// The reject of a cylinder with finite numbers; `None` for a cone.
    pub(crate) fn of(cone: &Cone) -> Option<CylinderReach> {
        let reach = CylinderReach {
            base: cone.base,
            axis: cone.axis,
            reach_squared: cone.base_radius * cone.base_radius * RADIUS_MARGIN,
        };
        (cone.is_cylinder()
            && reach.base.is_finite()
            && reach.axis.is_finite()
            && reach.reach_squared.is_finite())
        .then_some(reach)
    }

    /// Whether the ray's line certainly misses the cylinder; `false` also
    /// where it cannot tell (then the cylinder's own test decides).
    #[inline(always)]
    pub(crate) fn misses(&self, ray: &Ray) -> bool {
        let d = ray.direction;
        let n = d.cross(self.axis);
        let w = self.base - ray.origin;
        let along = w.dot(n);
        let n_squared = n.length_squared();
        // NaN anywhere makes a comparison false: no reject.
        n_squared > PARALLEL * d.length_squared()
            && along * along
                > (self.reach_squared + DISTANCE_MARGIN * w.length_squared()) * n_squared
    }
}

#[cfg(test)]
mod tests {
    use super::super::Numbers;
    use super::*;
    use raystep_model::math::Interval;
    use raystep_model::shapes::Shape;

    impl Numbers {
        /// A point of the cube of half side `scale` around the origin.
        fn spread(&mut self, scale: f64) -> DVec3 {
            DVec3::new(self.next() - 0.5, self.next() - 0.5, self.next() - 0.5) * 2.0 * scale
        }
    }

    #[test]
    fn a_cone_gets_no_reject_and_a_cylinder_does() {
        let cone = Cone::new(DVec3::ZERO, 0.2, DVec3::Z, 0.1).unwrap();
        assert!(CylinderReach::of(&cone).is_none());
        let cylinder = Cone::new(DVec3::ZERO, 0.2, DVec3::Z, 0.2).unwrap();
        let reach = CylinderReach::of(&cylinder).unwrap();
        // Along x at height 0.5: 0.3 from the axis misses, 0.1 does not.
        let ray = |y: f64| Ray::new(DVec3::new(-5.0, y, 0.5), DVec3::X);
        assert!(reach.misses(&ray(0.3)));
        assert!(!reach.misses(&ray(0.1)));
        // Within the margin of tangent (0.2 + 1e-9): not rejected.
        assert!(!reach.misses(&ray(0.2 + 1e-9)));
        // Parallel to the axis, even far away: left to the cylinder's test.
        assert!(!reach.misses(&Ray::new(DVec3::new(3.0, 0.0, -1.0), DVec3::Z)));
    }

    #[test]
    fn a_rejected_ray_never_has_a_root_and_most_misses_are_rejected() {
        // Random cylinders and rays, many of them grazing: rays aimed at a
        // point at radius R (1 + e) from the axis, e from -1e-6 to 1e-6,
        // where the reject's margin and the quadratic's rounding meet.
        let mut numbers = Numbers(5);
        let (mut rejected, mut grazing_rejected, mut clear_missed) = (0, 0, 0);
        for _ in 0..200_000 {
            let base = numbers.spread(50.0);
            let axis = numbers.spread(1.0);
            if axis.length() < 0.05 {
                continue;
            }
            let height = 0.01 + 10.0 * numbers.next();
            let radius = 10f64.powf(-3.0 + 4.0 * numbers.next());
            let apex = base + axis.normalize() * height;
            let cylinder = Cone::new(base, radius, apex, radius).unwrap();
            let reach = CylinderReach::of(&cylinder).unwrap();
            let a = (apex - base) / height;
            let side = a.any_orthonormal_vector();
            let grazing = numbers.next() < 0.5;
            let offset = if grazing {
                radius * (1.0 + (numbers.next() - 0.5) * 2e-6)
            } else {
                radius * 3.0 * numbers.next()
            };
            // The line passes closest to the axis at `target`, `offset` from
            // it: its direction has no part along `side`.
            let target = base + a * (height * numbers.next()) + side * offset;
            let d = a * ((numbers.next() - 0.5) * 4.0) + a.cross(side) * (0.05 + numbers.next());
            let origin = target - d * (0.5 + 100.0 * numbers.next());
            let ray = Ray::new(origin, d);
            let shape = Shape::Cone(Box::new(cylinder));
            let roots = shape.roots(&ray, Interval::new(-f64::INFINITY, f64::INFINITY));
            let hit = shape.intersect(&ray, Interval::in_front());
            if reach.misses(&ray) {
                assert!(
                    roots.as_slice().is_empty() && hit.is_none(),
                    "{ray:?} {shape:?}"
                );
                rejected += 1;
                grazing_rejected += usize::from(grazing);
            }
            // (A ray through the inside may miss too, past an end: no reject
            // can tell that from the distance to the axis.)
            clear_missed += usize::from(!grazing && offset > radius);
        }
        // Not vacuous: many rejects, including grazing rays within 1e-6 of
        // tangent; and nearly every ray that misses clearly is rejected.
        assert!(
            rejected > 40_000 && grazing_rejected > 2_000,
            "{rejected} {grazing_rejected}"
        );
        let clear_rejected = rejected - grazing_rejected;
        assert!(
            clear_rejected * 1000 > clear_missed * 999,
            "{clear_rejected} of {clear_missed}"
        );
    }
}
