//! The scene both ray log targets read logs against (`raylog_reader`,
//! `raylog_compare`): 3 lights, a glass ball and a glass floor, 8x6, so
//! every ray kind is cast. `seed.sh` reads SCENE out of this file.

use std::path::Path;
use std::sync::OnceLock;

use raystep_engine::scene::Scene;

const SCENE: &str = r#"
[camera]
eye = [0, 0, 5]
look_at = [0, 0, 0]
[image]
width = 8
height = 6
[materials.glass]
ks = 0.3
kt = 0.5
ior = 1.5
[[light]]
position = [0, 4, 4]
[[light]]
position = [4, 4, 4]
[[light]]
position = [-4, 4, 4]
[[object]]
name = "ball"
material = "glass"
sphere = { center = [0, 0, 0], radius = 1 }
[[object]]
name = "floor"
material = "glass"
plane = { normal = [0, 1, 0], point = [0, -1, 0] }
"#;

pub fn scene() -> &'static Scene {
    static SCENE_ONCE: OnceLock<Scene> = OnceLock::new();
    SCENE_ONCE.get_or_init(|| raystep_engine::scene::parse(Path::new("fuzz.toml"), SCENE).unwrap())
}
