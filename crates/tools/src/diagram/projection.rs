//! The plane a pixel's ray diagram is drawn on, in the camera's frame,
//! and the projection onto it; `rays.rs` and `outline.rs` project the rays
//! and the objects with it.

use glam::{DVec2, DVec3};

use raystep_engine::record::RayTree;
use raystep_engine::scene::Scene;

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
pub(crate) struct Projection {
    pub(crate) origin: DVec3,
    pub(crate) right: DVec3,
    pub(crate) up: DVec3,
}

impl Projection {
    pub(crate) fn new(plane: DiagramPlane, scene: &Scene, tree: &RayTree) -> Self {
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
    pub(crate) fn project(&self, p: DVec3) -> DVec2 {
        let v = p - self.origin;
        DVec2::new(v.dot(self.right), v.dot(self.up))
    }
}

/// The plane of incidence drawn as in a textbook: the surface's normal N
/// up, the surface running left to right, the ray coming in from the left.
/// For a missed primary ray: the ray to the right, the camera's up up.
fn primary_plane(root: &raystep_engine::record::Node, camera_up: DVec3) -> (DVec3, DVec3) {
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

/// The centre of a view of `centre` magnified `m` times about `focus` (the
/// projection's origin, the first hit): the focus moves toward the middle,
/// its offset divided by m² (shown magnified, by m), so a hit near the edge
/// stays in view. Below 1 the view keeps its centre. The SVG's `--zoom` and
/// the debugger's pane zoom both use it.
pub fn magnified_centre(centre: DVec2, focus: DVec2, m: f64) -> DVec2 {
    let m = m.max(1.0);
    focus + (centre - focus) / (m * m)
}

#[cfg(test)]
mod tests {
    use super::*;
    use raystep_engine::test_scenes::ball;

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
}
