//! One line of a ray log: a ray of one pixel, named by its path, with the
//! numbers its tracer printed for it. Every field but the pixel and the
//! path is optional: a student's tracer prints what it has.

use glam::DVec3;

use super::path::RayPath;

/// What a ray hit: an object, by its index in the scene's file order, or
/// nothing (`null` in the log).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Hit {
    Object(usize),
    Miss,
}

/// One ray of a log, with the keys of docs/RAYLOG.md.
#[derive(Clone, Debug, PartialEq)]
pub struct LoggedRay {
    pub pixel: (u32, u32),
    pub path: RayPath,
    pub origin: Option<DVec3>,
    pub dir: Option<DVec3>,
    pub hit: Option<Hit>,
    pub t: Option<f64>,
    pub point: Option<DVec3>,
    /// N, facing the ray.
    pub normal: Option<DVec3>,
    /// What the ray brings back, before its parent weights it.
    pub color: Option<DVec3>,
    pub ambient: Option<DVec3>,
    /// One per light, in the scene's order of lights.
    pub diffuse: Option<Vec<DVec3>>,
    pub specular: Option<Vec<DVec3>>,
    /// A shadow ray's factor.
    pub s: Option<f64>,
    /// The ray's accumulated weight: the product of the weights from the
    /// primary ray (1) down to it, per channel: the same on every channel
    /// but where a profile weighs the mirror ray by a colour (cse167's
    /// k_s O_s, MODEL §11).
    pub weight: Option<DVec3>,
    /// `t` was logged as `null`: what a tracer prints for a miss's t when
    /// its JSON printer writes infinity so (read as a miss, docs/RAYLOG.md).
    pub t_null: bool,
}

impl LoggedRay {
    /// A ray with only its pixel and path.
    pub fn new(pixel: (u32, u32), path: RayPath) -> Self {
        Self {
            pixel,
            path,
            origin: None,
            dir: None,
            hit: None,
            t: None,
            point: None,
            normal: None,
            color: None,
            ambient: None,
            diffuse: None,
            specular: None,
            s: None,
            weight: None,
            t_null: false,
        }
    }
}

/// The one value of a weight that is the same on every channel: a weight
/// is written and compared as a number then, as a colour only where a
/// profile made its channels differ.
pub fn uniform(weight: DVec3) -> Option<f64> {
    (weight.x == weight.y && weight.y == weight.z).then_some(weight.x)
}
