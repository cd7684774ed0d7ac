//! The ray diagram's geometry: the plane a pixel's rays are drawn on, and
//! the 2-D shapes on it (object outlines and every ray), each already
//! projected. `assembly.rs` builds the diagram from these; no drawing
//! lives here.

use glam::{DVec2, DVec3};

use crate::record::{EventKind, NodeId, RayTree};
use crate::scene::Scene;
use crate::shapes::Shape;

/// Which plane the diagram shows, in the camera's frame (so a z-up NFF
/// scene is seen from above too).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DiagramPlane {
    /// Seen from above: the camera's right to the right, its forward up.
    Top,
    /// Seen from the camera's right: forward to the right, up up.
    Side,
    /// The plane of incidence of the primary ray, its normal upward.
    Primary,
}

impl DiagramPlane {
    pub fn next(self) -> DiagramPlane {
        match self {
            DiagramPlane::Top => DiagramPlane::Side,
            DiagramPlane::Side => DiagramPlane::Primary,
            DiagramPlane::Primary => DiagramPlane::Top,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            DiagramPlane::Top => "from above",
            DiagramPlane::Side => "from the right",
            DiagramPlane::Primary => "primary ray's plane",
        }
    }
}

/// An orthographic projection onto a plane through `origin`.
#[derive(Clone, Copy, Debug)]
pub struct Projection {
    pub origin: DVec3,
    pub right: DVec3,
    pub up: DVec3,
}

impl Projection {
    pub fn new(plane: DiagramPlane, scene: &Scene, tree: &RayTree) -> Self {
        let root = tree.root();
        let origin = root.hit.as_ref().map_or(root.origin, |h| h.point);
        let camera = &scene.camera;
        let frame = camera.frame();
        let (right, up) = match plane {
            DiagramPlane::Top => (frame.right, frame.forward),
            DiagramPlane::Side => (frame.forward, frame.true_up),
            DiagramPlane::Primary => primary_plane(root, camera.up),
        };
        Self { origin, right, up }
    }

    /// Where a point lands in the plane.
    pub fn project(&self, p: DVec3) -> DVec2 {
        let v = p - self.origin;
        DVec2::new(v.dot(self.right), v.dot(self.up))
    }
}

/// The plane of incidence drawn as in a textbook: the surface's normal N
/// up, the surface running left to right, the ray coming in from the left.
/// For a missed primary ray: the ray to the right, the camera's up up.
fn primary_plane(root: &crate::record::Node, camera_up: DVec3) -> (DVec3, DVec3) {
    let d = root.direction.normalize();
    if let Some(hit) = &root.hit {
        let n = hit.normal;
        let along = d - d.dot(n) * n;
        if along.length() > 1e-6 {
            return (along.normalize(), n);
        }
    }
    let up = [camera_up, DVec3::Y, DVec3::X]
        .into_iter()
        .map(|u| u - u.dot(d) * d)
        .find(|u| u.length() > 1e-6)
        .map_or(DVec3::Y, |u| u.normalize());
    (d, up)
}

/// What a drawn ray is, for its colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stroke {
    Primary,
    Reflected,
    Transmitted,
    ShadowLit,
    /// 0 < S < 1: only transparent blockers (MODEL §4's Kt product).
    ShadowPartial,
    ShadowBlocked,
    Normal,
    /// Not yet reached by the step-through.
    Later,
    Current,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Segment {
    pub from: DVec2,
    pub to: DVec2,
    pub stroke: Stroke,
}

/// How far a step-through has come, for the strokes: rays cast by the
/// events up to `reached` (included) get their kind's colour, later ones are
/// `Later`, and the ray of `current` is `Current`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Progress {
    pub reached: usize,
    pub current: Option<CurrentRay>,
}

/// The ray the step-through is at: a node's own ray, or (with `light`) its
/// shadow ray to that light.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CurrentRay {
    pub node: NodeId,
    pub light: Option<usize>,
}

impl Progress {
    /// Every event reached and none current: each ray in its kind's colour.
    pub fn done(tree: &RayTree) -> Progress {
        Progress {
            reached: tree.events.len(),
            current: None,
        }
    }
}

/// What a shadow ray's S makes it: lit at 1, blocked at 0, partly
/// blocked between (transparent blockers only).
pub fn shadow_stroke(s: f64) -> Stroke {
    if s >= 1.0 {
        Stroke::ShadowLit
    } else if s <= 0.0 {
        Stroke::ShadowBlocked
    } else {
        Stroke::ShadowPartial
    }
}

/// A shadow ray's blocker, where it crosses, and its ray's kind (blocked
/// or partly blocked), for the colour of its ×.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BlockerMark {
    pub at: DVec2,
    pub stroke: Stroke,
}

/// The rays of a pixel as projected segments, plus blocker points.
pub fn ray_segments(
    tree: &RayTree,
    scene: &Scene,
    projection: &Projection,
    progress: Progress,
) -> (Vec<Segment>, Vec<BlockerMark>) {
    let current = progress.current;
    let reached = |test: &dyn Fn(&EventKind, NodeId) -> bool| {
        tree.events
            .iter()
            .take(progress.reached.saturating_add(1))
            .any(|e| test(&e.kind, e.node))
    };
    let miss_length = miss_length(tree, scene);
    let mut segments = Vec::new();
    let mut blockers = Vec::new();
    for (id, node) in tree.nodes.iter().enumerate() {
        let end = node.hit.as_ref().map_or(
            node.origin + node.direction.normalize() * miss_length,
            |h| h.point,
        );
        let is_current = current
            == Some(CurrentRay {
                node: id,
                light: None,
            });
        let stroke = if is_current {
            Stroke::Current
        } else if !reached(&|k, n| n == id && matches!(k, EventKind::RayCast { .. })) {
            Stroke::Later
        } else {
            match node.kind {
                crate::trace::RayKind::Primary => Stroke::Primary,
                crate::trace::RayKind::Reflected => Stroke::Reflected,
                crate::trace::RayKind::Transmitted => Stroke::Transmitted,
            }
        };
        segments.push(Segment {
            from: projection.project(node.origin),
            to: projection.project(end),
            stroke,
        });
        let Some(hit) = &node.hit else { continue };
        let normal_end = hit.point + hit.normal * miss_length * 0.08;
        segments.push(Segment {
            from: projection.project(hit.point),
            to: projection.project(normal_end),
            stroke: Stroke::Normal,
        });
        for light in &node.lights {
            let Some(shadow) = &light.shadow else {
                continue;
            };
            let target = scene
                .lights
                .get(light.light_index)
                .map_or(hit.point, |l| l.position);
            let is_current = current
                == Some(CurrentRay {
                    node: id,
                    light: Some(light.light_index),
                });
            let cast = |k: &EventKind, n| {
                n == id
                    && matches!(k, EventKind::ShadowCast { light: l } if *l == light.light_index)
            };
            let stroke = match () {
                _ if is_current => Stroke::Current,
                _ if !reached(&cast) => Stroke::Later,
                _ => shadow_stroke(shadow.s),
            };
            segments.push(Segment {
                from: projection.project(hit.point),
                to: projection.project(target),
                stroke,
            });
            // A blocker of a ray S = 1 lets all through (Kt = 1): its × as
            // a partly blocked one's.
            let kind = match shadow_stroke(shadow.s) {
                Stroke::ShadowBlocked => Stroke::ShadowBlocked,
                _ => Stroke::ShadowPartial,
            };
            blockers.extend(shadow.blockers.iter().map(|b| BlockerMark {
                at: projection.project(shadow.origin + shadow.direction * b.t),
                stroke: kind,
            }));
        }
    }
    (segments, blockers)
}

/// How far a missed ray is drawn: half the size of the pixel's scene.
fn miss_length(tree: &RayTree, scene: &Scene) -> f64 {
    let mut points: Vec<DVec3> = tree
        .nodes
        .iter()
        .filter_map(|n| n.hit.as_ref().map(|h| h.point))
        .collect();
    points.push(tree.root().origin);
    points.extend(scene.lights.iter().map(|l| l.position));
    let min = points.iter().fold(DVec3::INFINITY, |a, &p| a.min(p));
    let max = points.iter().fold(DVec3::NEG_INFINITY, |a, &p| a.max(p));
    ((max - min).length() * 0.5).max(1.0)
}

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
    pub fn points(&self) -> Vec<DVec2> {
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

/// The outline of one shape: spheres as circles, polygons as their edges,
/// cones as their two side lines and end caps, planes as the line where they
/// cut the view plane (none when parallel to it).
pub fn outline(shape: &Shape, projection: &Projection) -> Vec<Outline> {
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
    }
}

fn closed(mut points: Vec<DVec2>) -> Outline {
    if let Some(&first) = points.first() {
        points.push(first);
    }
    Outline::Polyline(points)
}

/// The centre of a view of `centre` magnified `m` times about `focus` (the
/// projection's origin, the first hit): the focus moves toward the middle,
/// its offset divided by m² (shown magnified, by m), so a hit near the edge
/// stays in view. Below 1 the view keeps its centre. The SVG's `--zoom` and
/// the debugger's pane zoom both use it.
pub fn magnified_centre(centre: DVec2, focus: DVec2, m: f64) -> DVec2 {
    let m = m.max(1.0);
    focus + (centre - focus) / (m * m)
}

/// The objects this pixel's rays meet: hit by a ray or blocking a shadow ray.
pub fn involved_objects(tree: &RayTree) -> Vec<usize> {
    let mut objects: Vec<usize> = tree
        .events
        .iter()
        .filter_map(|e| match e.kind {
            EventKind::Hit { object, .. } | EventKind::Blocker { object, .. } => Some(object),
            _ => None,
        })
        .collect();
    objects.sort_unstable();
    objects.dedup();
    objects
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tui::view::fixture::ball;
    use crate::tui::view::stepper::progress;

    fn close(a: DVec2, b: DVec2) -> bool {
        (a - b).length() < 1e-9
    }

    #[test]
    fn each_plane_is_seen_from_where_it_says() {
        // The camera looks down -z with y up: right = (1, 0, 0), forward =
        // (0, 0, -1). Every plane passes through r0's hit point (0, 0, 1), so
        // the eye (0, 0, 10) is 9 behind it and the lamp (5, 0, 10) also 5 right.
        let (scene, tree) = ball();
        let top = Projection::new(DiagramPlane::Top, &scene, &tree);
        assert!(close(top.project(DVec3::new(0.0, 0.0, 1.0)), DVec2::ZERO));
        assert!(close(top.project(scene.camera.eye), DVec2::new(0.0, -9.0)));
        assert!(close(
            top.project(DVec3::new(5.0, 0.0, 10.0)),
            DVec2::new(5.0, -9.0)
        ));
        // From the right: forward to the right, up up.
        let side = Projection::new(DiagramPlane::Side, &scene, &tree);
        assert!(close(side.project(scene.camera.eye), DVec2::new(-9.0, 0.0)));
        assert!(close(
            side.project(DVec3::new(0.0, 2.0, 1.0)),
            DVec2::new(0.0, 2.0)
        ));
        // A head-on hit has no plane of incidence: the ray to the right and
        // the camera's up up, as from the right.
        let primary = Projection::new(DiagramPlane::Primary, &scene, &tree);
        assert_eq!((primary.right, primary.up), (side.right, side.up));
    }

    #[test]
    fn planes_cycle_through_all_three() {
        let p = DiagramPlane::Top;
        assert_eq!(p.next(), DiagramPlane::Side);
        assert_eq!(p.next().next(), DiagramPlane::Primary);
        assert_eq!(p.next().next().next(), p);
    }

    #[test]
    fn segments_follow_the_step_through() {
        let (scene, tree) = ball();
        let top = Projection::new(DiagramPlane::Top, &scene, &tree);
        let strokes = |current| {
            let (segments, blockers) = ray_segments(&tree, &scene, &top, progress(&tree, current));
            assert!(blockers.is_empty(), "nothing blocks the lamp");
            segments.iter().map(|s| s.stroke).collect::<Vec<_>>()
        };
        // r0, its normal, its shadow ray to the lamp, then r1 (no hit: no normal).
        use Stroke::*;
        assert_eq!(strokes(0), [Current, Normal, Later, Later], "at r0's cast");
        assert_eq!(
            strokes(3),
            [Primary, Normal, Current, Later],
            "its shadow ray"
        );
        assert_eq!(
            strokes(9),
            [Current, Normal, ShadowLit, Reflected],
            "r0 done"
        );
        // r1 misses: drawn half the scene's size long. The hit (0, 0, 1), the
        // eye (0, 0, 10) and the lamp (5, 0, 10) span (5, 0, 9): half of
        // √106 from (0, 0, 1) along +z, which the top view shows downward.
        let (segments, _) = ray_segments(&tree, &scene, &top, progress(&tree, 9));
        let r1 = &segments[3];
        assert!(close(r1.from, DVec2::ZERO));
        assert!(close(r1.to, DVec2::new(0.0, -(106f64.sqrt() / 2.0))));
    }

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
        assert_eq!(involved_objects(&tree), [0]);
        // The floor y = -1 (y + 1 = 0) lies flat in the top view: no line;
        // from the right it is the line y + 1 = 0 (c = N·origin + d = 0 + 1).
        let floor = Shape::Plane(crate::shapes::Plane {
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
}
