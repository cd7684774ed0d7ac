//! Term images carry their scale: `--stats` gives the range of the two
//! false-colour counts, and `shadow.png` tells S = 0 (black), a point no
//! light faces (purple) and the background (dark blue) apart. A scene with
//! emission gets `emission.png` too; one without writes what it always did.

use crate::support::renders::TERM_FILES;
use crate::support::{raystep, stderr};
use raystep_engine::record::record_pixel;
use raystep_engine::terms::{NO_LIGHT_FACES, SHADOW_BACKGROUND};

#[test]
fn stats_give_the_count_images_scales_and_shadow_png_its_three_colours() {
    // shadows.toml has points no light faces and full shadows; glass.toml
    // has sky too.
    let mut seen = (0, 0, 0);
    for file in ["scenes/shadows.toml", "scenes/glass.toml"] {
        let (misses, facing_none, black) = check(file);
        seen = (seen.0 + misses, seen.1 + facing_none, seen.2 + black);
    }
    assert!(seen.0 > 0 && seen.1 > 0 && seen.2 > 0, "{seen:?}");
}

/// Renders `file` at 32x24 with --terms and --stats, checks shadow.png and
/// the rays' range pixel by pixel against the recordings, and returns how
/// many pixels missed, faced no light and were black.
fn check(file: &str) -> (usize, usize, usize) {
    let dir = tempfile::tempdir().unwrap();
    let terms = dir.path().join("terms");
    let out = dir.path().join("out.png");
    let output = raystep(&[
        "render",
        file,
        "--size",
        "32x24",
        "-o",
        out.to_str().unwrap(),
        "--terms",
        terms.to_str().unwrap(),
        "--stats",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let stats: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();

    // Independently: each pixel's rays are its tree's rays plus one shadow
    // ray per light that got one.
    let scene = raystep_engine::scene::load(std::path::Path::new(file))
        .unwrap()
        .with_size(32, 24)
        .unwrap();
    let shadow = image::open(terms.join("shadow.png")).unwrap().into_rgb8();
    let mut rays = Vec::new();
    let (mut misses, mut facing_none, mut black) = (0, 0, 0);
    for y in 0..24 {
        for x in 0..32 {
            let tree = record_pixel(&scene, &scene.settings, x, y);
            let shadow_rays = tree
                .nodes
                .iter()
                .flat_map(|n| &n.lights)
                .filter(|l| l.shadow.is_some())
                .count();
            rays.push(tree.nodes.len() + shadow_rays);
            let root = tree.root();
            let shown = shadow.get_pixel(x, y).0;
            if root.hit.is_none() {
                assert_eq!(shown, SHADOW_BACKGROUND, "({x}, {y}) misses");
                misses += 1;
            } else if root.lights.iter().all(|l| l.faces_away) {
                assert_eq!(shown, NO_LIGHT_FACES, "({x}, {y}) faces no light");
                facing_none += 1;
            } else if shown == [0, 0, 0] {
                // Black is S = 0 and nothing else.
                assert!(
                    root.lights
                        .iter()
                        .filter(|l| !l.faces_away)
                        .all(|l| l.shadow.as_ref().is_some_and(|s| s.s == 0.0))
                );
                black += 1;
            }
        }
    }
    let range = &stats["rays_per_pixel"];
    assert_eq!(range["min"], *rays.iter().min().unwrap());
    assert_eq!(range["max"], *rays.iter().max().unwrap());
    assert!(stats["cost_per_pixel"]["max"].as_u64().unwrap() > 0);
    (misses, facing_none, black)
}

/// `render FILE -o image.png --terms terms` in a fresh folder, returned
/// with the sorted names of the files written in `terms`.
fn terms_of(file: &str) -> (tempfile::TempDir, Vec<String>) {
    let dir = tempfile::tempdir().unwrap();
    let terms = dir.path().join("terms");
    let out = dir.path().join("image.png");
    let output = raystep(&[
        "render",
        file,
        "-o",
        out.to_str().unwrap(),
        "--terms",
        terms.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let mut names: Vec<String> = std::fs::read_dir(&terms)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    (dir, names)
}

/// One pixel of `file` in the folder.
fn pixel(dir: &tempfile::TempDir, file: &str, x: u32, y: u32) -> [u8; 3] {
    image::open(dir.path().join(file))
        .unwrap()
        .into_rgb8()
        .get_pixel(x, y)
        .0
}

#[test]
fn an_emitting_scene_gets_emission_png_and_its_ambient_png_the_materials_own() {
    // ambient-emission.test (160x120, eye (0, 0, 6), fovy 40, no lights):
    // balls of radius 0.6 at x = -1.4, 0, 1.4. Row 60's centre is 0.5 px
    // below the axis; a pixel x meets the plane z = 0 at
    // ((x + 0.5) / 80 - 1) (4/3) tan 20° 6: x = 41 at -1.40, x = 80 at
    // 0.02, x = 118 at 1.40, each well inside its ball.
    let (dir, names) = terms_of("scenes/cse167/ambient-emission.test");
    let mut expected = TERM_FILES.to_vec();
    expected.insert(3, "emission.png");
    assert_eq!(names, expected);
    // The bytes, floor(255 c + 0.5) (MODEL §6): E = (0.9, 0.5, 0.1) is
    // (229.5, 127.5, 25.5) + 0.5 = (230, 128, 26); the left ball's own
    // ambient (0.1, 0.3, 0.8) is (26, 77, 204) (76.5 + 0.5 = 77), the
    // middle one's 0.2 grey 51, the right one's ambient (0, 0, 0) black.
    let (left, middle, right) = ((41, 60), (80, 60), (118, 60));
    assert_eq!(
        pixel(&dir, "terms/emission.png", right.0, right.1),
        [230, 128, 26]
    );
    for (x, y) in [left, middle, (0, 0)] {
        assert_eq!(
            pixel(&dir, "terms/emission.png", x, y),
            [0, 0, 0],
            "({x}, {y})"
        );
    }
    assert_eq!(
        pixel(&dir, "terms/ambient.png", left.0, left.1),
        [26, 77, 204]
    );
    assert_eq!(
        pixel(&dir, "terms/ambient.png", middle.0, middle.1),
        [51, 51, 51]
    );
    assert_eq!(
        pixel(&dir, "terms/ambient.png", right.0, right.1),
        [0, 0, 0]
    );
    // No lights: the picture is A + E, so the right ball is E's bytes.
    assert_eq!(pixel(&dir, "image.png", right.0, right.1), [230, 128, 26]);
}

#[test]
fn a_scene_without_emission_writes_only_the_eight_term_images() {
    for file in ["scenes/glass.toml", "scenes/cse167/mirrors.test"] {
        let (_dir, names) = terms_of(file);
        assert_eq!(names, TERM_FILES, "{file}");
    }
}
