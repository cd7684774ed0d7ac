//! Scenes whose centre pixel's recording can be worked out by hand, for the
//! unit tests of the views and the diagram.

use std::path::Path;

use crate::record::{RayTree, record_pixel};
use crate::scene::Scene;

/// A mirror ball (kd = ks = 0.5) at the origin, seen from (0, 0, 10),
/// the lamp at (5, 0, 10). The centre pixel (5, 5) hits the ball head on
/// at (0, 0, 1); its reflected ray r1 goes straight back and misses. Its
/// ten events, in order:
///
/// | 0 r0 cast | 1 r0 hit | 2 r0 ambient | 3 r0 shadow ray to the lamp |
/// 4 r0 lamp's terms | 5 r1 cast | 6 r1 miss | 7 r1 done |
/// 8 r0: r1 returns | 9 r0 done |
pub const BALL: &str = r#"
[camera]
eye = [0, 0, 10]
look_at = [0, 0, 0]
up = [0, 1, 0]
fov = 40

[image]
width = 11
height = 11

[settings]
background = [0.1, 0.2, 0.3]
ambient = [0.1, 0.1, 0.1]

[materials.mirror]
color = [1, 1, 1]
kd = 0.5
ks = 0.5
n = 20

[[light]]
name = "lamp"
position = [5, 0, 10]

[[object]]
name = "ball"
material = "mirror"
sphere = { center = [0, 0, 0], radius = 1 }
"#;

/// A matte ball (no reflected ray) at the origin seen from (0, 0, 10),
/// the lamp at (5, 0, 10) and a second light, "back", behind the ball
/// at (0, 0, -10); a pebble of radius 1 at (0.9, 0.9, 4) beside the
/// primary ray's way. The centre pixel's ray runs down the z axis and
/// hits the ball at (0, 0, 1), N = (0, 0, 1).
pub const PEBBLE: &str = r#"
[camera]
eye = [0, 0, 10]
look_at = [0, 0, 0]
up = [0, 1, 0]
fov = 40

[image]
width = 11
height = 11

[materials.matte]
color = [1, 1, 1]
kd = 1

[[light]]
name = "lamp"
position = [5, 0, 10]

[[light]]
name = "back"
position = [0, 0, -10]

[[object]]
name = "ball"
material = "matte"
sphere = { center = [0, 0, 0], radius = 1 }

[[object]]
name = "pebble"
material = "matte"
sphere = { center = [0.9, 0.9, 4], radius = 1 }
"#;

/// The ball scene and its centre pixel's recording.
pub fn ball() -> (Scene, RayTree) {
    centre_pixel("ball.toml", BALL)
}

/// The pebble scene and its centre pixel's recording.
pub fn pebble() -> (Scene, RayTree) {
    centre_pixel("pebble.toml", PEBBLE)
}

/// The scene of `text` (11x11) and its centre pixel (5, 5)'s recording.
pub fn centre_pixel(name: &str, text: &str) -> (Scene, RayTree) {
    let scene = crate::scene::parse(Path::new(name), text).unwrap();
    let tree = record_pixel(&scene, &scene.settings, 5, 5);
    (scene, tree)
}
