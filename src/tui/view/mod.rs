//! What the panes show, worked out apart from drawing: the ray tree's rows,
//! the step list, stepping, the diagram's labels and its pan and zoom, where
//! image pixels land in the image pane, the details' lines, the help's
//! lines, and where each pane goes. Pure functions of the recording, the scene and sizes, so
//! each file tests its own; the app (`app/`) and the panes (`pane/`) both
//! read them, and nothing here knows either.

pub(crate) mod cell_labels;
pub mod details;
pub(crate) mod find;
pub(crate) mod help;
pub(crate) mod image_grid;
pub(crate) mod layout;
pub(crate) mod mistakes_menu;
pub(crate) mod pan_zoom;
pub(crate) mod stepper;
pub mod steps;
pub mod tree;

/// A scene whose one pixel's recording can be worked out by hand, for the
/// views' unit tests.
#[cfg(test)]
pub(crate) mod fixture {
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
    pub(crate) const BALL: &str = r#"
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

    /// The ball scene and its centre pixel's recording.
    pub(crate) fn ball() -> (Scene, RayTree) {
        let scene = crate::scene::parse(Path::new("ball.toml"), BALL).unwrap();
        let tree = record_pixel(&scene, &scene.settings, 5, 5);
        (scene, tree)
    }
}
