//! Objects' outlines in the diagram's plane: where the plane cuts them.

use glam::{DMat2, DVec2, DVec3};

use super::projection::Projection;
use raystep_model::shapes::Shape;

/// An object's outline in the plane.
#[derive(Clone, Debug, PartialEq)]
pub enum Outline {
    Circle {
        center: DVec2,
        radius: f64,
    },
    /// An infinite line a·(x, y) + c = 0 (a plane cut by the view plane).
    Line {
        normal: DVec2,
        c: f64,
    },
    Polyline(Vec<DVec2>),
}

impl Outline {
    /// The points that bound the outline, for fitting the view: a circle's
    /// box corners, a polyline's points; none for an infinite line, which is
    /// drawn across whatever the view holds.
    pub(crate) fn points(&self) -> Vec<DVec2> {
        match self {
            Outline::Circle { center, radius } => {
                vec![
                    *center - DVec2::splat(*radius),
                    *center + DVec2::splat(*radius),
                ]
            }
            Outline::Polyline(points) => points.clone(),
            Outline::Line { .. } => Vec::new(),
        }
    }
}

/// The outline of one shape: spheres as circles, ellipsoids as the ellipse
/// they show seen along the view plane's normal (as a sphere shows its
/// circle; drawn as a polygon of `ELLIPSE_SIDES` sides), polygons as their edges,
/// cones as their two side lines and end caps, planes as the line where they
/// cut the view plane (none when parallel to it).
pub(crate) fn outline(shape: &Shape, projection: &Projection) -> Vec<Outline> {
    let p = |v: DVec3| projection.project(v);
    match shape {
        Shape::Sphere(s) => vec![Outline::Circle {
            center: p(s.center),
            radius: s.radius,
        }],
        Shape::Plane(plane) => {
            let normal = DVec2::new(
                plane.normal.dot(projection.right),
                plane.normal.dot(projection.up),
            );
            let c = plane.normal.dot(projection.origin) + plane.d;
            if normal.length() < 1e-9 {
                vec![]
            } else {
                vec![Outline::Line { normal, c }]
            }
        }
        Shape::Polygon(polygon) => vec![closed(polygon.vertices.iter().map(|&v| p(v)).collect())],
        Shape::Patch(patch) => vec![closed(
            patch.polygon.vertices.iter().map(|&v| p(v)).collect(),
        )],
        Shape::Cone(cone) => {
            let (base, apex) = (p(cone.base), p(cone.apex));
            let axis = apex - base;
            if axis.length() < 1e-9 {
                let r = cone.base_radius.max(cone.apex_radius);
                return vec![Outline::Circle {
                    center: base,
                    radius: r,
                }];
            }
            let side = axis.perp().normalize();
            let (b0, b1) = (
                base + side * cone.base_radius,
                base - side * cone.base_radius,
            );
            let (a0, a1) = (
                apex + side * cone.apex_radius,
                apex - side * cone.apex_radius,
            );
            vec![Outline::Polyline(vec![b0, a0, a1, b1, b0])]
        }
        Shape::Ellipsoid(e) => vec![ellipse(e, projection)],
    }
}

/// How many sides the polygon drawn for an ellipsoid's ellipse has.
pub(crate) const ELLIPSE_SIDES: usize = 64;

/// The ellipsoid's silhouette in the plane, exactly an ellipse: its points
/// are M c + L u with |u| <= r (L the linear part of M), which project to
/// c2 + P L u, P the plane's two axes: the ellipse y^T S^-1 y <= 1 around
/// c2 with S = r^2 (P L)(P L)^T, whose rim is c2 + sqrt(S) (cos a, sin a).
/// sqrt of a 2x2 positive definite S: (S + sqrt(det S) I) / sqrt(tr S + 2 sqrt(det S)).
fn ellipse(e: &raystep_model::shapes::Ellipsoid, projection: &Projection) -> Outline {
    let l = e.to_world.matrix3;
    let r = e.sphere.radius;
    let rows = [projection.right, projection.up].map(|axis| r * (l.transpose() * axis));
    let s = DMat2::from_cols(
        DVec2::new(rows[0].dot(rows[0]), rows[1].dot(rows[0])),
        DVec2::new(rows[0].dot(rows[1]), rows[1].dot(rows[1])),
    );
    let root_det = s.determinant().max(0.0).sqrt();
    let scale = (s.x_axis.x + s.y_axis.y + 2.0 * root_det).sqrt();
    let root = (s + DMat2::from_diagonal(DVec2::splat(root_det))) * (1.0 / scale);
    let center = projection.project(e.center());
    closed(
        (0..ELLIPSE_SIDES)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / ELLIPSE_SIDES as f64;
                center + root * DVec2::new(a.cos(), a.sin())
            })
            .collect(),
    )
}

fn closed(mut points: Vec<DVec2>) -> Outline {
    if let Some(&first) = points.first() {
        points.push(first);
    }
    Outline::Polyline(points)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagram::DiagramPlane;
    use raystep_engine::test_scenes::ball;

    #[test]
    fn a_sphere_is_a_circle_and_a_plane_its_cut() {
        let (scene, tree) = ball();
        let top = Projection::new(DiagramPlane::Top, &scene, &tree);
        // The centre (0, 0, 0) is 1 ahead of the hit point: up in the top view.
        assert_eq!(
            outline(&scene.objects[0].shape, &top),
            [Outline::Circle {
                center: DVec2::new(0.0, 1.0),
                radius: 1.0
            }]
        );
        // The floor y = -1 (y + 1 = 0) lies flat in the top view: no line;
        // from the right it is the line y + 1 = 0 (c = N·origin + d = 0 + 1).
        let floor = Shape::Plane(raystep_model::shapes::Plane {
            normal: DVec3::Y,
            d: 1.0,
        });
        assert_eq!(outline(&floor, &top), []);
        let side = Projection::new(DiagramPlane::Side, &scene, &tree);
        assert_eq!(
            outline(&floor, &side),
            [Outline::Line {
                normal: DVec2::new(0.0, 1.0),
                c: 1.0
            }]
        );
    }

    #[test]
    fn an_ellipsoid_is_the_ellipse_it_shows() {
        use glam::DMat4;
        use raystep_model::shapes::placed_sphere;
        // The unit sphere stretched to x^2/4 + y^2 + z^2 = 1, turned 90
        // degrees about z (y^2/4 + x^2 + z^2 = 1), moved to (5, 0, 0); seen
        // on the x-y plane through the origin it shows (x - 5)^2 + y^2/4 = 1:
        // every drawn point on it, reaching y = 2 and x = 6.
        let m = DMat4::from_translation(DVec3::new(5.0, 0.0, 0.0))
            * DMat4::from_rotation_z(std::f64::consts::FRAC_PI_2)
            * DMat4::from_scale(DVec3::new(2.0, 1.0, 1.0));
        let shape = placed_sphere(DVec3::ZERO, 1.0, m).unwrap();
        let plane = Projection {
            origin: DVec3::ZERO,
            right: DVec3::X,
            up: DVec3::Y,
        };
        let [Outline::Polyline(points)] = &outline(&shape, &plane)[..] else {
            panic!("an ellipse drawn as a polygon");
        };
        assert_eq!(points.len(), ELLIPSE_SIDES + 1);
        for p in points {
            let on = (p.x - 5.0).powi(2) + p.y * p.y / 4.0;
            assert!((on - 1.0).abs() < 1e-12, "{p} is off the ellipse");
        }
        let top = points.iter().map(|p| p.y).fold(f64::MIN, f64::max);
        let right = points.iter().map(|p| p.x).fold(f64::MIN, f64::max);
        assert!((top - 2.0).abs() < 1e-3 && (right - 6.0).abs() < 1e-12);
        // Turned 45 degrees in the view, the same ellipse tilts: each point
        // satisfies the turned equation (u^2/4 + v^2 = 1 in the turned axes).
        let tilted = DMat4::from_rotation_z(std::f64::consts::FRAC_PI_4)
            * DMat4::from_scale(DVec3::new(2.0, 1.0, 1.0));
        let shape = placed_sphere(DVec3::ZERO, 1.0, tilted).unwrap();
        let [Outline::Polyline(points)] = &outline(&shape, &plane)[..] else {
            panic!("an ellipse drawn as a polygon");
        };
        let c = std::f64::consts::FRAC_1_SQRT_2;
        for p in points {
            let (u, v) = (c * (p.x + p.y), c * (p.y - p.x));
            assert!(
                (u * u / 4.0 + v * v - 1.0).abs() < 1e-12,
                "{p} is off the ellipse"
            );
        }
    }
}
