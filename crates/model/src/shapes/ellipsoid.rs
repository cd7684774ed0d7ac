//! A sphere under an affine transform M (an ellipsoid), worked the way
//! CSE 167 teaches it (MODEL §3): the ray is moved into the sphere's own
//! space by M⁻¹ (its origin as a point, its direction as a vector, not
//! renormalised, so t is the same in both spaces), the sphere's quadratic
//! is solved there, and the normal is carried back by the inverse
//! transpose: N_g = normalize(M⁻ᵀ (p' − c) / r).

use glam::{DAffine3, DMat3, DMat4, DVec3, DVec4};
use serde::Serialize;

use super::{Aabb, GeometryError, Roots, Shape, Sphere, SphereWorking};
use crate::math::{Interval, Ray};

#[derive(Clone, Debug, PartialEq)]
pub struct Ellipsoid {
    /// The sphere in its own space (centre c, radius r).
    pub sphere: Sphere,
    /// M: the sphere's own space to world space.
    pub to_world: DAffine3,
    /// M⁻¹, precomputed: every ray tested is moved by it.
    pub to_object: DAffine3,
    /// M⁻ᵀ's linear part. N_g = M⁻ᵀ n' is the gradient of |M⁻¹ p − c|²
    /// (halved), so it points outwards even when M mirrors.
    pub normal_matrix: DMat3,
}

/// A sphere's working, done in the sphere's own space, and at a hit the
/// normal's working: what the recording shows for an ellipsoid.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct EllipsoidWorking {
    /// o' = M⁻¹ o.
    pub object_origin: DVec3,
    /// d' = M⁻¹ d, as a vector, not renormalised.
    pub object_direction: DVec3,
    /// The sphere's centre c and radius r in its own space.
    pub object_center: DVec3,
    pub object_radius: f64,
    /// A = |d'|², B = 2 d'·(o' − c), C = |o' − c|² − r², its roots.
    #[serde(flatten)]
    pub quadratic: SphereWorking,
    /// At a hit: p' = M⁻¹ p, the hit point in the sphere's own space.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub object_point: Option<DVec3>,
    /// At a hit: n' = (p' − c) / r, the sphere's normal there.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub object_normal: Option<DVec3>,
    /// At a hit: N_g = normalize(M⁻ᵀ n').
    #[serde(skip_serializing_if = "Option::is_none")]
    pub normal: Option<DVec3>,
}

/// The shape of a sphere (centre, radius) placed by the affine `transform`:
/// a plain sphere when the transform scales it the same way along every
/// axis, however it moves and turns it (faster, and what a student expects
/// to see named "sphere"), else an ellipsoid.
pub fn placed_sphere(center: DVec3, radius: f64, transform: DMat4) -> Result<Shape, GeometryError> {
    if transform.row(3) == DVec4::W
        && let Some(s) = uniform_scale(DMat3::from_mat4(transform))
    {
        return Sphere::new(transform.transform_point3(center), s * radius).map(Shape::Sphere);
    }
    Ellipsoid::new(center, radius, transform).map(|e| Shape::Ellipsoid(Box::new(e)))
}

/// s when `linear` is s times a rotation (or a mirror): exactly, for a
/// diagonal s I, else when L Lᵀ is s² I to within a rounding (a rotation's
/// sines and cosines are rounded, so its columns are not exactly unit).
fn uniform_scale(linear: DMat3) -> Option<f64> {
    let s = linear.x_axis.x;
    if linear == DMat3::from_diagonal(DVec3::splat(s)) {
        return (s != 0.0).then_some(s.abs());
    }
    let squares = linear * linear.transpose();
    let s2 = (squares.x_axis.x + squares.y_axis.y + squares.z_axis.z) / 3.0;
    let off = (squares - DMat3::from_diagonal(DVec3::splat(s2))).to_cols_array();
    let close = off.iter().all(|x| x.abs() <= 1e-12 * s2);
    (close && s2 > 0.0 && s2.is_finite()).then(|| s2.sqrt())
}

impl Ellipsoid {
    /// Refuses a transform that is not affine (its last row is not
    /// (0, 0, 0, 1)) or is singular (a zero scale flattens the sphere: no
    /// M⁻¹), naming the value.
    pub fn new(center: DVec3, radius: f64, transform: DMat4) -> Result<Self, GeometryError> {
        let sphere = Sphere::new(center, radius)?;
        if transform.row(3) != DVec4::W {
            return Err(GeometryError(format!(
                "a sphere's transform must be affine (last row 0 0 0 1), got {}",
                transform.row(3)
            )));
        }
        let to_world = DAffine3::from_mat4(transform);
        let determinant = to_world.matrix3.determinant();
        let to_object = to_world.inverse();
        if determinant == 0.0 || !determinant.is_finite() || !to_object.is_finite() {
            return Err(GeometryError(format!(
                "a sphere's transform must be invertible, but its determinant is {determinant} \
                 (a zero scale flattens the sphere)"
            )));
        }
        let normal_matrix = to_object.matrix3.transpose();
        Ok(Self {
            sphere,
            to_world,
            to_object,
            normal_matrix,
        })
    }

    /// The ray in the sphere's own space: o' = M⁻¹ o, d' = M⁻¹ d.
    #[inline]
    fn object_ray(&self, ray: &Ray) -> Ray {
        Ray::new(
            self.to_object.transform_point3(ray.origin),
            self.to_object.transform_vector3(ray.direction),
        )
    }

    /// The sphere's quadratic, solved in its own space.
    #[inline]
    pub fn solve(&self, ray: &Ray, range: Interval) -> SphereWorking {
        self.sphere.solve(&self.object_ray(ray), range)
    }

    pub fn roots(&self, ray: &Ray, range: Interval) -> Roots {
        self.sphere.roots(&self.object_ray(ray), range)
    }

    /// The whole working, the normal's included when the ray hits.
    pub fn working(&self, ray: &Ray, range: Interval) -> EllipsoidWorking {
        let object = self.object_ray(ray);
        let quadratic = self.sphere.solve(&object, range);
        let point = quadratic
            .t()
            .map(|t| self.to_object.transform_point3(ray.at(t)));
        EllipsoidWorking {
            object_origin: object.origin,
            object_direction: object.direction,
            object_center: self.sphere.center,
            object_radius: self.sphere.radius,
            quadratic,
            object_point: point,
            object_normal: point.map(|p| self.sphere.normal_at(p)),
            normal: point.map(|p| self.normal_of(p)),
        }
    }

    /// N_g at a world point of the surface: normalize(M⁻ᵀ (p' − c) / r).
    pub fn normal_at(&self, point: DVec3) -> DVec3 {
        self.normal_of(self.to_object.transform_point3(point))
    }

    fn normal_of(&self, object_point: DVec3) -> DVec3 {
        (self.normal_matrix * self.sphere.normal_at(object_point)).normalize()
    }

    /// The world centre M c.
    pub fn center(&self) -> DVec3 {
        self.to_world.transform_point3(self.sphere.center)
    }

    /// The exact box: along world axis i the ellipsoid reaches r |row i of
    /// M's linear part| either side of its centre.
    pub fn bounds(&self) -> Aabb {
        let m = self.to_world.matrix3;
        let half = self.sphere.radius
            * DVec3::new(m.row(0).length(), m.row(1).length(), m.row(2).length());
        Aabb::new(self.center() - half, self.center() + half)
    }
}

impl EllipsoidWorking {
    pub fn t(&self) -> Option<f64> {
        self.quadratic.t()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const EXACT: f64 = 1e-12;

    /// The unit sphere at the origin stretched by `scale`, then turned
    /// `degrees` about z: M = R_z S.
    fn ellipsoid(scale: DVec3, degrees: f64) -> Ellipsoid {
        let m = DMat4::from_rotation_z(degrees.to_radians()) * DMat4::from_scale(scale);
        Ellipsoid::new(DVec3::ZERO, 1.0, m).unwrap()
    }

    fn down_z(x: f64, y: f64) -> Ray {
        Ray::new(DVec3::new(x, y, 5.0), DVec3::new(0.0, 0.0, -1.0))
    }

    fn close(a: DVec3, b: DVec3) -> bool {
        (a - b).abs().max_element() < EXACT
    }

    #[test]
    fn a_stretched_sphere_reaches_as_far_as_its_scale() {
        // x^2/4 + y^2 + z^2 = 1 reaches x = 2: a ray down -z at x = 1.9 hits
        // (1.9^2/4 = 0.9025 < 1), one at x = 2.1 misses (1.1025 > 1), though
        // the unit sphere it was made of ends at x = 1.
        let e = ellipsoid(DVec3::new(2.0, 1.0, 1.0), 0.0);
        assert!(
            e.solve(&down_z(1.9, 0.0), Interval::in_front())
                .t()
                .is_some()
        );
        assert_eq!(
            e.solve(&down_z(2.1, 0.0), Interval::in_front()).choice,
            super::super::RootChoice::NoRealRoots
        );
    }

    #[test]
    fn the_quadratic_is_solved_in_the_spheres_own_space_with_the_same_t() {
        // The ray from (1, 0, 5) down -z meets x^2/4 + z^2 = 1 where
        // z^2 = 1 - 1/4, z = sqrt(0.75): t = 5 - sqrt(0.75) and 5 + sqrt(0.75).
        // In the sphere's own space M^-1 = diag(1/2, 1, 1): o' = (0.5, 0, 5),
        // d' = (0, 0, -1) (a vector: no translation, not renormalised);
        // A = 1, B = 2 d'·o' = -10, C = 0.25 + 25 - 1 = 24.25,
        // discriminant 100 - 97 = 3, t0 = (10 - sqrt 3) / 2 = 5 - sqrt(0.75).
        let e = ellipsoid(DVec3::new(2.0, 1.0, 1.0), 0.0);
        let w = e.working(&down_z(1.0, 0.0), Interval::in_front());
        assert_eq!(w.object_origin, DVec3::new(0.5, 0.0, 5.0));
        assert_eq!(w.object_direction, DVec3::new(0.0, 0.0, -1.0));
        let q = w.quadratic;
        assert_eq!((q.a, q.b, q.c, q.discriminant), (1.0, -10.0, 24.25, 3.0));
        let root = 0.75f64.sqrt();
        assert!((w.t().unwrap() - (5.0 - root)).abs() < EXACT);
        let roots = e.roots(&down_z(1.0, 0.0), Interval::new(1e-4, 10.0));
        assert!((roots.as_slice()[0] - (5.0 - root)).abs() < EXACT);
        assert!((roots.as_slice()[1] - (5.0 + root)).abs() < EXACT);
        // The hit point's own-space image lies on the unit sphere.
        let p = w.object_point.unwrap();
        assert!((p.length() - 1.0).abs() < EXACT);
    }

    #[test]
    fn the_normal_comes_from_the_inverse_transpose_not_from_the_centre() {
        // p = (sqrt 2, sqrt 0.5, 0) is on x^2/4 + y^2 = 1 (2/4 + 0.5 = 1).
        // p' = M^-1 p = (sqrt 2 / 2, sqrt 0.5, 0); M^-T = diag(1/2, 1, 1), so
        // M^-T p' = (sqrt 2 / 4, sqrt 0.5, 0), the gradient (x/2, 2y, 0) of
        // x^2/4 + y^2 halved; its length is sqrt(1/8 + 1/2) = sqrt(5/8):
        // N_g = (1/sqrt 5, 2/sqrt 5, 0).
        // The direction from the centre, (p - c)/|p - c| = (2, 1, 0)/sqrt 5,
        // is not it: only a sphere's normal points away from its centre.
        let e = ellipsoid(DVec3::new(2.0, 1.0, 1.0), 0.0);
        let p = DVec3::new(2f64.sqrt(), 0.5f64.sqrt(), 0.0);
        let expected = DVec3::new(1.0, 2.0, 0.0) / 5f64.sqrt();
        assert!(close(e.normal_at(p), expected));
        let from_centre = DVec3::new(2.0, 1.0, 0.0) / 5f64.sqrt();
        assert!(e.normal_at(p).dot(from_centre) < 0.9);
        // The recorded working gives the same normal, and n' = p'.
        let ray = Ray::new(p + DVec3::Z, -DVec3::Z);
        let w = e.working(&ray, Interval::in_front());
        assert!(close(w.normal.unwrap(), expected));
        assert!(close(
            w.object_normal.unwrap(),
            DVec3::new(0.5f64.sqrt(), 0.5f64.sqrt(), 0.0)
        ));
    }

    #[test]
    fn a_turned_ellipsoid_lies_along_its_turned_axis() {
        // The same x^2/4 + y^2 + z^2 = 1 turned 90 degrees about z lies along
        // y: y^2/4 + x^2 + z^2 = 1. Down -z at y = 1.9 it is hit, at x = 1.9
        // missed. The point (sqrt 2, sqrt 0.5, 0) turns to (-sqrt 0.5, sqrt 2, 0)
        // and its normal (1, 2, 0)/sqrt 5 to (-2, 1, 0)/sqrt 5.
        let e = ellipsoid(DVec3::new(2.0, 1.0, 1.0), 90.0);
        assert!(
            e.solve(&down_z(0.0, 1.9), Interval::in_front())
                .t()
                .is_some()
        );
        assert!(
            e.solve(&down_z(1.9, 0.0), Interval::in_front())
                .t()
                .is_none()
        );
        let p = DVec3::new(-(0.5f64.sqrt()), 2f64.sqrt(), 0.0);
        assert!(close(
            e.normal_at(p),
            DVec3::new(-2.0, 1.0, 0.0) / 5f64.sqrt()
        ));
    }

    #[test]
    fn the_box_is_the_ellipsoids_exact_extent() {
        // S = diag(2, 1, 1) turned 45 degrees about z: L = R S has rows
        // (2c, -s, 0), (2s, c, 0), (0, 0, 1) with c = s = sqrt 0.5, so the
        // half-extents are sqrt(4/2 + 1/2) = sqrt 2.5 along x and y, 1 along
        // z: the ellipse's reach sqrt(a^2 cos^2 + b^2 sin^2) at 45 degrees.
        // Moved to (1, 2, 3), the box is centred there.
        let m = DMat4::from_translation(DVec3::new(1.0, 2.0, 3.0))
            * DMat4::from_rotation_z(45f64.to_radians())
            * DMat4::from_scale(DVec3::new(2.0, 1.0, 1.0));
        let b = Ellipsoid::new(DVec3::ZERO, 1.0, m).unwrap().bounds();
        let half = DVec3::new(2.5f64.sqrt(), 2.5f64.sqrt(), 1.0);
        assert!(close(b.min, DVec3::new(1.0, 2.0, 3.0) - half));
        assert!(close(b.max, DVec3::new(1.0, 2.0, 3.0) + half));
    }

    #[test]
    fn a_mirrored_ellipsoids_normal_still_points_out() {
        // scale (-2, 1, 1) mirrors x (det M = -2 < 0). At p = (-2, 0, 0),
        // p' = M^-1 p = (1, 0, 0) and M^-T p' = (-1/2, 0, 0): N_g = (-1, 0, 0),
        // outwards still (M^-T p' is half the gradient of |M^-1 p|^2), not
        // flipped as a cross product of mirrored edges would be.
        let e = ellipsoid(DVec3::new(-2.0, 1.0, 1.0), 0.0);
        assert!(close(e.normal_at(DVec3::new(-2.0, 0.0, 0.0)), -DVec3::X));
        assert!(close(e.normal_at(DVec3::new(2.0, 0.0, 0.0)), DVec3::X));
    }

    #[test]
    fn a_uniform_scale_makes_a_plain_sphere_and_a_zero_one_is_refused() {
        // translate (1, 2, 3), scale 2: the sphere (1, 0, 0) r 0.5 becomes
        // the sphere at (1, 2, 3) + 2 (1, 0, 0) = (3, 2, 3) of radius 1.
        let m = DMat4::from_translation(DVec3::new(1.0, 2.0, 3.0))
            * DMat4::from_scale(DVec3::splat(2.0));
        let Shape::Sphere(s) = placed_sphere(DVec3::X, 0.5, m).unwrap() else {
            panic!("a uniform scale is a sphere");
        };
        assert_eq!((s.center, s.radius), (DVec3::new(3.0, 2.0, 3.0), 1.0));
        // Turned as well, it is still a sphere, of radius 3 r.
        let turned = DMat4::from_rotation_y(0.3) * DMat4::from_scale(DVec3::splat(3.0));
        let Shape::Sphere(s) = placed_sphere(DVec3::ZERO, 1.0, turned).unwrap() else {
            panic!("a turned uniform scale is a sphere");
        };
        assert!((s.radius - 3.0).abs() < EXACT);
        // Stretched, it is an ellipsoid.
        let stretched = DMat4::from_scale(DVec3::new(1.0, 2.0, 1.0));
        let shape = placed_sphere(DVec3::ZERO, 1.0, stretched).unwrap();
        assert_eq!(shape.kind(), "ellipsoid");
        // A zero scale has no inverse: refused, with the determinant.
        let flat = DMat4::from_scale(DVec3::new(1.0, 0.0, 1.0));
        let error = placed_sphere(DVec3::ZERO, 1.0, flat).unwrap_err();
        assert!(error.0.contains("determinant is 0"), "{error}");
    }
}
