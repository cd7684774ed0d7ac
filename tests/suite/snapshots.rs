//! Pinned pictures and recordings of the example scenes. Every snapshot was
//! read against MODEL.md before it was accepted; floats are rounded so the
//! files are the same on every platform.

use std::path::Path;

use crate::support::scene_at;
use raystep_engine::record::{explain, record_pixel};
use raystep_engine::render::render;
use raystep_engine::trace::NoRecorder;
use serde_json::Value;

fn scene_path(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(name)
}

/// Rounds every float to 6 decimals (and -0 to 0) so snapshots are stable.
fn rounded(value: Value) -> Value {
    match value {
        Value::Number(n) if n.is_f64() => {
            let x = (n.as_f64().unwrap() * 1e6).round() / 1e6;
            serde_json::json!(if x == 0.0 { 0.0 } else { x })
        }
        Value::Array(items) => Value::Array(items.into_iter().map(rounded).collect()),
        Value::Object(map) => {
            Value::Object(map.into_iter().map(|(k, v)| (k, rounded(v))).collect())
        }
        other => other,
    }
}

/// Each scene rendered at 32 x 24, one line of hex colours per pixel row.
#[test]
fn scene_pixels() {
    insta::glob!("../../scenes", "*.toml", |path| {
        let scene = scene_at(path, Some((32, 24)));
        let (image, _) = render::<NoRecorder>(&scene, &scene.settings, &|| {});
        let mut text = String::new();
        for row in image.rows() {
            let line: Vec<String> = row
                .map(|p| format!("{:02x}{:02x}{:02x}", p[0], p[1], p[2]))
                .collect();
            text.push_str(&line.join(" "));
            text.push('\n');
        }
        snapshot!("scene_pixels", text);
    });
}

/// Chosen pixels: the tree as JSON, the explanation and the event list.
const PIXELS: &[(&str, u32, u32, &str)] = &[
    (
        "seven-rays.toml",
        80,
        60,
        "the seven-ray tree: 1 primary, 2 secondary, 4 at max_depth 3",
    ),
    (
        "seven-rays.toml",
        80,
        5,
        "a miss: the background colour, no terms",
    ),
    (
        "shadows.toml",
        14,
        66,
        "floor in the box's shadow: opaque blockers, S = 0",
    ),
    (
        "shadows.toml",
        66,
        68,
        "floor behind the glass ball: two crossings, S = 0.6^2 = 0.36",
    ),
    (
        "mirrors.toml",
        127,
        48,
        "the ball's fourth reflection, at max_depth 5",
    ),
    (
        "glass.toml",
        132,
        88,
        "into the glass block, then total internal reflection",
    ),
    (
        "polygons.toml",
        32,
        52,
        "a concave star's leg: 3 crossings, odd, inside",
    ),
    (
        "polygons.toml",
        30,
        30,
        "through the star's notch: a near miss, 2 crossings, outside",
    ),
    ("highlights.toml", 107, 32, "Phong's R·V beside Blinn's N·H"),
    (
        "attenuation.toml",
        66,
        48,
        "a far pillar: light attenuation f_att = 0.21",
    ),
    (
        "directional.toml",
        100,
        68,
        "the sun's shadow: a directional light, no distance, blocked by the ball",
    ),
    (
        "ellipsoid.toml",
        112,
        50,
        "the squashed ball: a sphere's working in its own space, N_g by M⁻ᵀ",
    ),
];

#[test]
fn chosen_pixels() {
    for &(file, x, y, why) in PIXELS {
        let scene = scene_at(&scene_path(file), None);
        let tree = record_pixel(&scene, &scene.settings, x, y);
        let name = format!("{}_{x}_{y}", file.trim_end_matches(".toml"));
        let mut json = rounded(tree.to_json());
        let events = json.as_object_mut().unwrap().remove("events").unwrap();
        insta::with_settings!({ description => why }, {
            json_snapshot!(&format!("{name}_tree"), json);
            json_snapshot!(&format!("{name}_events"), events);
            snapshot!(&format!("{name}_explain"), explain(&tree));
        });
    }
}

#[test]
fn graphviz_of_a_pixel_with_total_internal_reflection() {
    // glass.toml names (135, 58) for TIR: into the block's top face, then
    // TIR at its right and back faces (red edges, weight k_s + k_t = 1),
    // a light that faces away without a shadow edge, blockers named.
    let scene = scene_at(&scene_path("glass.toml"), None);
    let tree = record_pixel(&scene, &scene.settings, 135, 58);
    let dot = raystep_engine::record::dot(&tree);
    assert_eq!(dot.matches("(TIR)").count(), 2);
    // r5 hits the glass block (k_s 0.1, k_t 0.9) from inside at depth 5 =
    // max_depth with k = -0.7648 (cos_i = 0.4644, eta = 1.5): TIR, so the
    // one ray cut is reflected, weight k_s + k_t = 1, a grey dashed box; no
    // transmitted ray exists to cut. r6's square is opaque and matte
    // (k_s = k_t = 0), so it had nothing to cut.
    assert_eq!(dot.matches("not cast: max_depth").count(), 1);
    assert!(
        dot.contains("label=\"reflected ray\\nnot cast: max_depth\\nweight 1, max_depth = 5\"")
    );
    snapshot!("glass_135_58_dot", dot);
}
