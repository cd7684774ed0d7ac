//! A mesh file given alone (`raystep render box.obj`): the mesh with a
//! default camera and one light (MODEL §2, docs/SCENES.md "Meshes"), so a
//! course mesh can be looked at before a scene is written around it. An
//! object is framed from outside, a room (faces wound inward, like the
//! Cornell box's) from inside, through its open side: either way the camera
//! sees the lit side of what it looks at.

use std::path::Path;

use glam::DVec3;

use super::{Placement, Request, load};
use crate::scene::{Light, Scene, SceneError, Settings};
use raystep_model::camera::Camera;
use raystep_model::math::Color;
use raystep_model::object::Object;
use raystep_model::shapes::{Aabb, Shape};

/// The camera stands this many times the box's half diagonal from the box's
/// centre: at 45° a sphere around the box then fills about 80% of the
/// image's height.
pub(crate) const DISTANCE: f64 = 3.0;
/// Where from: the +z side, a little to the right and above (x, y, z before
/// normalising), so that a box shows three faces and no edge lines up
/// with the image's centre.
/// The vertical field of view and image size: TOML's defaults.
const FOV: f64 = 45.0;
const SIZE: (u32, u32) = (320, 240);
pub(crate) const VIEW_FROM: DVec3 = DVec3::new(0.4, 0.3, 1.0);

pub(crate) fn scene(path: &Path) -> Result<Scene, SceneError> {
    let request = Request {
        path,
        name: None,
        placement: Placement::default(),
        material: None,
        first_material: 0,
    };
    // Never empty: `load` refuses a mesh with no triangle to show.
    let placed = load(&request)?;
    let bounds = placed
        .objects
        .iter()
        .filter_map(|o| o.shape.bounds())
        .fold(Aabb::EMPTY, |a, b| a.union(&b));
    let (camera, light) = if is_room(&placed.objects, &bounds) {
        room_view(&bounds, open_side(&placed.objects, &bounds))
    } else {
        object_view(&bounds)
    };
    // The light: unless the mesh has emitters of its own (an MTL's Ke),
    // which then light it alone.
    let mut lights = placed.lights;
    if lights.is_empty() {
        lights.push(Light::point("default light", light, Color::ONE));
    }
    let settings = Settings {
        ambient: Color::splat(0.1),
        ..Settings::default()
    };
    let mut scene = Scene::new(
        camera,
        SIZE,
        settings,
        placed.materials,
        lights,
        placed.objects,
    );
    scene.warnings = placed.warnings;
    scene.files = placed.files;
    Ok(scene)
}

/// An object seen from outside: the camera at `DISTANCE` half diagonals
/// from the box's centre, from `VIEW_FROM`; the light above and to the
/// right of the camera.
fn object_view(bounds: &Aabb) -> (Camera, DVec3) {
    let centre = bounds.centroid();
    let radius = (bounds.diagonal() / 2.0).max(1e-3);
    let eye = centre + VIEW_FROM.normalize() * (DISTANCE * radius);
    let camera = Camera {
        eye,
        look_at: centre,
        up: DVec3::Y,
        fov: FOV,
    };
    (camera, eye + DVec3::new(radius, radius, 0.0))
}

/// A room's triangles face inward by their winding (counter-clockwise
/// seen from the front, the plane's normal (v1 - v0) x (v2 - v0)): summed
/// as tetrahedra from the box's centre, (a - c)·((b - c) x (d - c)) / 6
/// each, they enclose a negative volume, where an object's enclose a
/// positive one (the divergence theorem). A closed surface encloses its
/// whole volume: a box's is its bounding box's, a ball's π/6 of it; a room
/// with one side open, like the Cornell box, loses that side's pyramid to
/// the centre (a sixth of a cube's); a mesh of mixed winding, or flat,
/// encloses about nothing. A room encloses minus a quarter of its bounding
/// box's volume or less.
fn is_room(objects: &[Object], bounds: &Aabb) -> bool {
    let c = bounds.centroid();
    let volume: f64 = triangles(objects)
        .map(|[a, b, d]| (a - c).dot((b - c).cross(d - c)) / 6.0)
        .sum();
    let size = bounds.max - bounds.min;
    let box_volume = size.x * size.y * size.z;
    box_volume > 0.0 && volume <= -box_volume / 4.0
}

/// The sides of the box, in the order a tie between them is settled: the
/// axis (0 x, 1 y, 2 z) and which end (+1 the max, -1 the min).
const SIDES: [(usize, f64); 6] = [
    (2, 1.0),
    (2, -1.0),
    (0, 1.0),
    (0, -1.0),
    (1, 1.0),
    (1, -1.0),
];

/// The side a room is open on, or the one with the least wall: for each
/// side of the box, the area of the triangles whose centroid lies within a
/// tenth of the box's size of that side, projected on it; the first least
/// in `SIDES`' order.
fn open_side(objects: &[Object], bounds: &Aabb) -> (usize, f64) {
    let size = bounds.max - bounds.min;
    let wall = |(axis, end): (usize, f64)| -> f64 {
        let near_side = |centroid: DVec3| {
            let inward = if end > 0.0 {
                bounds.max[axis] - centroid[axis]
            } else {
                centroid[axis] - bounds.min[axis]
            };
            inward <= size[axis] / 10.0
        };
        triangles(objects)
            .filter(|[a, b, d]| near_side((a + b + d) / 3.0))
            .map(|[a, b, d]| (b - a).cross(d - a)[axis].abs() / 2.0)
            .sum()
    };
    let mut best = (SIDES[0], wall(SIDES[0]));
    for side in &SIDES[1..] {
        let area = wall(*side);
        if area < best.1 {
            best = (*side, area);
        }
    }
    best.0
}

/// The mesh's triangles (a polygon's fan, should one have more corners).
fn triangles(objects: &[Object]) -> impl Iterator<Item = [DVec3; 3]> + '_ {
    objects.iter().flat_map(|o| {
        let corners: &[DVec3] = match &o.shape {
            Shape::Polygon(p) => &p.vertices,
            Shape::Patch(p) => &p.polygon.vertices,
            _ => &[],
        };
        (2..corners.len()).map(move |i| [corners[0], corners[i - 1], corners[i]])
    })
}

/// A room seen from inside: the camera on the line through the box's
/// centre across the open side, a tenth of the room's depth in from that
/// side, looking at the opposite side; up +y (+z when it looks along y);
/// the field of view is the one in which the opposite side, a quarter
/// larger, just fills the image, so the walls round it show, at most 100°.
/// The light: a quarter of the room's height above the camera.
fn room_view(bounds: &Aabb, (axis, end): (usize, f64)) -> (Camera, DVec3) {
    let size = bounds.max - bounds.min;
    let centre = bounds.centroid();
    let (near, far) = if end > 0.0 {
        (bounds.max[axis], bounds.min[axis])
    } else {
        (bounds.min[axis], bounds.max[axis])
    };
    let mut eye = centre;
    eye[axis] = near + (far - near) / 100.0;
    let mut look_at = centre;
    look_at[axis] = far;
    let (up, across) = match axis {
        1 => (2, 0),
        0 => (1, 2),
        _ => (1, 0),
    };
    let aspect = f64::from(SIZE.0) / f64::from(SIZE.1);
    let depth = (far - eye[axis]).abs().max(1e-3);
    let half = (size[up] / 2.0).max(size[across] / 2.0 / aspect);
    let fov = (2.0 * (1.5 * half / depth).atan().to_degrees()).min(100.0);
    let mut up_direction = DVec3::ZERO;
    up_direction[up] = 1.0;
    let camera = Camera {
        eye,
        look_at,
        up: up_direction,
        fov,
    };
    (camera, eye + up_direction * (size[up] / 4.0))
}
