//! Term images carry their scale: `--stats` gives the range of the two
//! false-colour counts, and `shadow.png` tells S = 0 (black), a point no
//! light faces (purple) and the background (dark blue) apart.

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
