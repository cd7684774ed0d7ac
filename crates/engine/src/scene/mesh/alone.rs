//! A mesh file given alone (`raystep render box.obj`): the mesh with a
//! default camera that frames its bounding box and one light (MODEL §2,
//! docs/SCENES.md "Meshes"), so a course mesh can be looked at before a scene is
//! written around it.

use std::path::Path;

use glam::DVec3;

use super::{Placement, Request, load};
use crate::scene::{Light, Scene, SceneError, Settings};
use raystep_model::camera::Camera;
use raystep_model::math::Color;
use raystep_model::shapes::Aabb;

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
    let centre = bounds.centroid();
    let radius = (bounds.diagonal() / 2.0).max(1e-3);
    let eye = centre + VIEW_FROM.normalize() * (DISTANCE * radius);
    let camera = Camera {
        eye,
        look_at: centre,
        up: DVec3::Y,
        fov: FOV,
    };
    // The light: above and to the right of the camera, white, unless the
    // mesh has emitters of its own (an MTL's Ke), which then light it alone.
    let mut lights = placed.lights;
    if lights.is_empty() {
        lights.push(Light {
            name: "default light".into(),
            position: eye + DVec3::new(radius, radius, 0.0),
            color: Color::ONE,
        });
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
