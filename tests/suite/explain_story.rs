//! `explain` and `inspect` tell the whole story (issue 16 §1): each term
//! with its factors, and the events deep in the tree that shaped the pixel,
//! ranked by how much each moved it. Values derived by hand in comments.

use std::path::Path;

use raystep_engine::record::{Children, explain, node_lines, record_pixel, shaping_events};
use raystep_engine::scene::{Scene, load};
use raystep_model::mistakes::{Mistake, Mistakes};

use crate::support::{record, scene};

/// A plane z = -1 facing the camera at the origin; one white light at
/// (0.6, 0, -0.2), so from the hit (0, 0, -1) L = (0.6, 0, 0.8), d_L = 1.
fn lit_plane() -> Scene {
    scene(
        "[camera]
        eye = [0, 0, 0]
        look_at = [0, 0, -1]
        [settings]
        ambient = [0.2, 0.2, 0.2]
        [materials.paint]
        color = [1, 0.5, 0]
        ka = 0.5
        kd = 0.5
        ks = 0.5
        n = 2
        [[light]]
        position = [0.6, 0, -0.2]
        [[object]]
        material = \"paint\"
        plane = { normal = [0, 0, 1], point = [0, 0, -1] }",
    )
}

#[test]
fn each_term_is_printed_with_its_factors() {
    let tree = record(&lit_plane(), [0.0; 3], [0.0, 0.0, -1.0]);
    // The lines unwrapped, as the details pane gets them.
    let lines: Vec<String> = node_lines(&tree, 0, Children::Listed)
        .iter()
        .map(|l| l.to_string())
        .collect();
    let text = lines.join("\n");
    // diffuse = S f_att I_p k_d O_d (N·L) = 1 · 1 · 1 · 0.5 · (1, 0.5, 0) · 0.8
    //         = (0.4, 0.2, 0).
    assert!(
        text.contains("diffuse = S · f_att · I_p · k_d · O_d · (N·L)"),
        "{text}"
    );
    assert!(
        text.contains(
            "    = 1 · 1 · (1.000, 1.000, 1.000) · 0.5 · (1.000, 0.500, 0.000) · 0.8 = \
             (0.400, 0.200, 0.000)"
        ),
        "{text}"
    );
    // V = (0, 0, 1): L + V = (0.6, 0, 1.8), N·H = 1.8 / sqrt(3.6) = 0.9487,
    // (N·H)^2 = 3.24 / 3.6 = 0.9; specular = 0.5 · 0.9 = 0.45 per channel.
    assert!(
        text.contains("specular = S · f_att · I_p · k_s · (N·H)^n"),
        "{text}"
    );
    assert!(
        text.contains("· 0.5 · 0.9487^2 = (0.450, 0.450, 0.450)"),
        "{text}"
    );
    // ambient = I_a k_a O_d = 0.2 · 0.5 · (1, 0.5, 0) = (0.1, 0.05, 0).
    assert!(
        text.contains(
            "ambient = I_a · k_a · O_d = (0.200, 0.200, 0.200) · 0.5 · (1.000, 0.500, 0.000) \
             = (0.100, 0.050, 0.000)"
        ),
        "{text}"
    );
    // An unnamed light is "light 0", once.
    assert!(text.contains("light 0: N·L = 0.8, S = 1"), "{text}");
    assert!(!text.contains("light light"), "{text}");
}

#[test]
fn the_json_holds_every_factor() {
    let tree = record(&lit_plane(), [0.0; 3], [0.0, 0.0, -1.0]);
    let root = &tree.to_json()["tree"];
    let f = &root["hit"]["factors"];
    assert_eq!(f["o_d"], serde_json::json!([1.0, 0.5, 0.0]));
    assert_eq!((f["ka"].as_f64(), f["kd"].as_f64()), (Some(0.5), Some(0.5)));
    assert_eq!((f["ks"].as_f64(), f["n"].as_f64()), (Some(0.5), Some(2.0)));
    assert_eq!(
        (f["kt"].as_f64(), f["ior"].as_f64()),
        (Some(0.0), Some(1.0))
    );
    assert_eq!(root["hit"]["i_a"], serde_json::json!([0.2, 0.2, 0.2]));
    assert_eq!(root["lights"][0]["i_p"], serde_json::json!([1.0, 1.0, 1.0]));
}

/// A mirror z = -1 (k_s = 0.5) in front of the camera and a white matte
/// plane z = 1 behind it; the light at (0.6, 0, 0.2) lights the matte plane
/// at (0, 0, 1) with N·L = 0.8, but an opaque ball of radius 0.1 at
/// (0.3, 0, 0.6), halfway along the shadow segment, blocks it.
fn mirror_and_shadow(settings: &str) -> Scene {
    scene(&format!(
        "[camera]
        eye = [0, 0, 0]
        look_at = [0, 0, -1]
        [settings]
        {settings}
        [materials.mirror]
        kd = 0
        ks = 0.5
        n = 10
        [materials.matte]
        kd = 1
        [[light]]
        position = [0.6, 0, 0.2]
        [[object]]
        material = \"mirror\"
        plane = {{ normal = [0, 0, 1], point = [0, 0, -1] }}
        [[object]]
        material = \"matte\"
        plane = {{ normal = [0, 0, -1], point = [0, 0, 1] }}
        [[object]]
        name = \"ball\"
        material = \"matte\"
        sphere = {{ center = [0.3, 0, 0.6], radius = 0.1 }}"
    ))
}

#[test]
fn a_shadow_below_the_first_hit_is_told_with_what_it_cost() {
    let tree = record(&mirror_and_shadow(""), [0.0; 3], [0.0, 0.0, -1.0]);
    // Unblocked, the matte plane's diffuse would be 1 · 1 · 1 · 1 · 0.8 =
    // 0.8 per channel; the reflected ray reaches the pixel with weight 0.5
    // (attenuation 1), so the shadow takes 0.4 from each channel. The
    // shadow ray (0.6, 0, -0.8) meets the ball at t = 0.5 -+ 0.1.
    let events = shaping_events(&tree);
    assert_eq!(events.len(), 1, "{events:?}");
    assert!((events[0].matters - 0.4).abs() < 1e-12);
    assert_eq!(events[0].node, 1);
    let story = explain(&tree);
    assert!(
        flat(&story).contains(
            "0.400 light 0 is blocked at r1 (primary → reflected, depth 2) by ball \
             (t = 0.4, root t0, k_t = 0), ball (t = 0.6, root t1, k_t = 0): S = 0; unblocked it \
             would add (0.400, 0.400, 0.400) more to the pixel"
        ),
        "{story}"
    );
    // Each blocker's working: o - c = (-0.3, 0, 0.4), d = (0.6, 0, -0.8):
    // A = 1, B = 2 d·(o - c) = -1, C = 0.25 - 0.01 = 0.24, B^2 - 4AC = 0.04,
    // roots (1 -+ 0.2) / 2 = 0.4 and 0.6.
    let lines: Vec<String> = node_lines(&tree, 1, Children::Listed)
        .iter()
        .map(|l| l.to_string())
        .collect();
    let working = [
        "  ball crossed at t = 0.4 (root t0) and t = 0.6 (root t1):",
        "    sphere: A = 1, B = -1, C = 0.24, discriminant B^2 - 4AC = 0.04",
        "    roots t0 = 0.4, t1 = 0.6",
        "  f_att = 1, N·H = ",
    ];
    let at = lines
        .iter()
        .position(|l| l == working[0])
        .expect("blocker lines");
    for (line, start) in lines[at..at + 4].iter().zip(working) {
        assert!(line.starts_with(start), "{lines:#?}");
    }
}

#[test]
fn a_ray_cut_by_the_depth_limit_is_told_with_its_weight() {
    // max_depth 1: the mirror's reflected ray (weight k_s = 0.5) is never
    // spawned; it could have added up to 0.5 per channel.
    let tree = record(
        &mirror_and_shadow("max_depth = 1"),
        [0.0; 3],
        [0.0, 0.0, -1.0],
    );
    let events = shaping_events(&tree);
    assert_eq!(events.len(), 1, "{events:?}");
    assert_eq!(events[0].matters, 0.5);
    assert!(
        events[0]
            .text
            .contains("the depth limit (max_depth 1) stops its reflected ray (weight 0.5)"),
        "{}",
        events[0].text
    );
}

#[test]
fn a_clamped_channel_is_ranked_by_what_clamping_took() {
    // Ambient 1.6 on a white matte plane: the pixel is (1.6, 1.6, 1.6) and
    // each channel loses 0.6 to clamping, 0.6 / 3 = 0.2 of a channel on average.
    let plane = scene(
        "[camera]
        eye = [0, 0, 0]
        look_at = [0, 0, -1]
        [settings]
        ambient = [1.6, 1.6, 1.6]
        [materials.white]
        kd = 0
        [[object]]
        material = \"white\"
        plane = { normal = [0, 0, 1], point = [0, 0, -1] }",
    );
    let tree = record(&plane, [0.0; 3], [0.0, 0.0, -1.0]);
    let events = shaping_events(&tree);
    assert_eq!(events.len(), 3, "{events:?}");
    assert!(events.iter().all(|e| (e.matters - 0.2).abs() < 1e-12));
    assert!(explain(&tree).contains("the red channel is 1.6 before clamping: it is stored as 255"));
}

#[test]
fn the_glass_scenes_tir_example_is_told_below_the_first_hit() {
    // scenes/glass.toml names pixel (132, 88): into the block's front face,
    // then TIR at its bottom (k = -1.02), on the transmitted ray r2.
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/glass.toml");
    let scene = load(&path).unwrap();
    let tree = record_pixel(&scene, &scene.settings, 132, 88);
    let story = flat(&explain(&tree));
    assert!(
        story.contains(
            "total internal reflection at r2 (primary → transmitted, depth 2) on glass block \
             bottom: k = -1.0217 < 0"
        ),
        "{story}"
    );
    // The TIR is the event that matters most for this pixel.
    assert!(
        shaping_events(&tree)[0]
            .text
            .starts_with("total internal reflection at r2")
    );
}

#[test]
fn tir_at_the_depth_limit_casts_one_reflected_ray_of_weight_ks_plus_kt() {
    // scenes/glass.toml's pixel (135, 58): into the block's top face, then
    // TIR at r2 (depth 2). With max_depth 2 the limit stops r2's children.
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/glass.toml");
    let scene = load(&path).unwrap();
    let mut settings = scene.settings;
    settings.max_depth = 2;
    let tree = record_pixel(&scene, &settings, 135, 58);
    let r2 = tree.root().transmitted.unwrap();
    let node = &tree.nodes[r2];
    let hit = node.hit.as_ref().unwrap();
    // Leaving the glass: eta = ior / 1 = 1.5, cos_i = -d·N from the recorded
    // ray and normal, k = 1 - eta^2 (1 - cos_i^2); at (135, 58) cos_i is
    // about 0.4644, so k = 1 - 2.25 · 0.7843 = -0.7648 < 0: TIR.
    assert!(!hit.entering);
    let cos_i = -node.direction.dot(hit.normal);
    let k = 1.0 - 1.5 * 1.5 * (1.0 - cos_i * cos_i);
    assert!((k - -0.7648).abs() < 1e-4, "k = {k}");
    let refraction = node.refraction.expect("TIR is decided at the limit too");
    assert!(refraction.tir);
    assert!((refraction.k - k).abs() < 1e-12);
    // No ray is cast, so the colour is that of the default-depth tree's r2
    // without its children: the same as before the TIR was recorded.
    assert!(node.reflected.is_none() && node.transmitted.is_none());
    // The one ray not cast is reflected, weight k_s + k_t = 0.1 + 0.9 = 1.
    let story = flat(&explain(&tree));
    assert!(
        story.contains(
            "the depth limit (max_depth 2) stops its reflected ray (weight 1), the one ray of a \
             total internal reflection on glass block right"
        ),
        "{story}"
    );
    assert!(!story.contains("stops its transmitted ray"), "{story}");
}

#[test]
fn under_depth_off_by_one_the_limit_is_one_level_higher_everywhere() {
    // scenes/mirrors.toml's pixel (97, 50): the primary ray hits the right
    // mirror (k_s = 0.85), whose reflection shows the ball. With max_depth 2
    // and depth-off-by-one, rays of depth 2 - 1 = 1 spawn nothing (MODEL
    // §8): the primary ray is at the limit, so it casts no reflected ray.
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/mirrors.toml");
    let scene = load(&path).unwrap();
    let mut settings = scene.settings;
    settings.max_depth = 2;
    settings.mistakes = Mistakes::NONE.with(Mistake::DepthOffByOne);
    let tree = record_pixel(&scene, &settings, 97, 50);
    assert_eq!(tree.nodes.len(), 1, "no secondary ray is cast");
    let story = flat(&explain(&tree));
    assert!(
        story.contains(
            "No secondary rays: max_depth is 2, and under depth-off-by-one the primary ray \
             spawns none."
        ),
        "{story}"
    );
    // The ray not cast is the mirror's reflected ray, of weight k_s = 0.85.
    assert!(
        story.contains("the depth limit (max_depth 2) stops its reflected ray (weight 0.85)"),
        "{story}"
    );
    // inspect's lines agree: depth 1 is the limit, not max_depth.
    let lines: Vec<String> = node_lines(&tree, 0, Children::Omitted)
        .iter()
        .map(|l| l.to_string())
        .collect();
    assert!(
        lines.contains(
            &"no secondary rays: depth 1 is max_depth - 1, the limit under depth-off-by-one"
                .to_string()
        ),
        "{lines:#?}"
    );
}

#[test]
fn a_ray_switched_off_is_not_told_as_cut_by_the_depth_limit() {
    // max_depth 1 on the mirror (k_s = 0.5) with reflection switched off:
    // the mirror would cast no reflected ray at any depth, so the depth
    // limit cuts nothing and nothing shaped the pixel but its terms.
    let mut scene = mirror_and_shadow("max_depth = 1");
    scene.settings.switches.reflection = false;
    let tree = record(&scene, [0.0; 3], [0.0, 0.0, -1.0]);
    assert_eq!(tree.nodes.len(), 1);
    let story = flat(&explain(&tree));
    assert!(!story.contains("the depth limit"), "{story}");
}

#[test]
fn a_tir_at_the_depth_limit_is_named_with_its_object() {
    // scenes/glass.toml's pixel (122, 72): r5 (depth 5, max_depth 5) is
    // inside the block and meets its bottom face at too shallow an angle:
    // TIR, and the limit stops the one reflected ray, of weight k_s + k_t
    // = 0.1 + 0.9 = 1. The sentence says where: on glass block bottom.
    let story = flat(&explain_file("scenes/glass.toml", 122, 72));
    assert!(
        story.contains(
            "at r5 (primary → transmitted → reflected → reflected → reflected, depth 5) the \
             depth limit (max_depth 5) stops its reflected ray (weight 1), the one ray of a \
             total internal reflection on glass block bottom:"
        ),
        "{story}"
    );
    // Every TIR sentence names its object.
    for sentence in story.split_inclusive(". ") {
        if sentence.contains("total internal reflection") {
            assert!(sentence.contains(" on glass block "), "{sentence}");
        }
    }
}

#[test]
fn a_ray_leaving_a_sphere_says_t0_is_where_it_leaves() {
    // A glass ball of radius 1 at (0, 0, -3), met head on: the primary ray
    // enters at (0, 0, -2), straight through (cos_i = 1, so the transmitted
    // direction is (0, 0, -1)). The transmitted ray r1 starts on the
    // sphere: o - c = (0, 0, 1), A = 1, B = 2 d·(o - c) = -2, C = 1 - 1 = 0,
    // roots (2 -+ 2) / 2 = 0 and 2: t0 is the point it leaves, t1 the back.
    let ball = scene(
        "[camera]
        eye = [0, 0, 0]
        look_at = [0, 0, -1]
        [settings]
        max_depth = 2
        [materials.glass]
        kd = 0.1
        ks = 0
        kt = 0.9
        ior = 1.5
        [[object]]
        name = \"ball\"
        material = \"glass\"
        sphere = { center = [0, 0, -3], radius = 1 }",
    );
    let tree = record(&ball, [0.0; 3], [0.0, 0.0, -1.0]);
    let r1 = tree.root().transmitted.expect("the ball transmits");
    let lines: Vec<String> = node_lines(&tree, r1, Children::Listed)
        .iter()
        .map(|l| l.to_string())
        .collect();
    assert!(
        lines
            .iter()
            .any(|l| l.starts_with("  roots t0 ≈ 0 (the point the ray leaves), t1 = 2: took t1")),
        "{lines:#?}"
    );
}

fn explain_file(file: &str, x: u32, y: u32) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(file);
    let scene = load(&path).unwrap();
    explain(&record_pixel(&scene, &scene.settings, x, y))
}

#[test]
fn an_nff_sphere_near_miss_is_named_once() {
    // NFF objects are named by kind and number already ("sphere 3").
    let story = flat(&explain_file("scenes/spd/balls-small.nff", 200, 300));
    assert!(
        story.contains("the bounding box of sphere 3 but passes it by"),
        "{story}"
    );
    assert!(!story.contains("sphere sphere"), "{story}");
}

#[test]
fn rays_that_add_nothing_visible_get_no_share_line() {
    // attenuation.toml (135, 58): r0's surface is 100.0% of the colour; its
    // two other rays add under 0.0005 per channel, so no "other rays" line.
    let story = explain_file("scenes/attenuation.toml", 135, 58);
    assert!(
        story.contains("100.0%  right pillar 1, hit by r0"),
        "{story}"
    );
    assert!(!story.contains("other rays add"), "{story}");
}

#[test]
fn a_passed_by_polygon_is_tested_at_its_plane_point() {
    // polygons.toml (40, 54): between the star's lower legs the ray meets
    // the star's plane outside the outline (2 crossings) and hits the wall.
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/polygons.toml");
    let scene = load(&path).unwrap();
    let tree = record_pixel(&scene, &scene.settings, 40, 54);
    let lines: Vec<String> = node_lines(&tree, 0, Children::Listed)
        .iter()
        .map(|l| l.to_string())
        .collect();
    let text = lines.join("\n");
    assert!(text.contains("drop Z: plane point at (U, V)"), "{text}");
    assert!(text.contains("vertices from the plane point"), "{text}");
}

/// A grey mirror (k_s = 0.8, no diffuse) at z = -1 facing the eye at the
/// origin, and behind the eye, at z = 2, `behind`; ambient 0.2, no lights,
/// so every surface's own colour is its ambient term I_a · k_a · O_d.
fn mirror_before(behind: &str) -> Scene {
    scene(&format!(
        "[camera]
        eye = [0, 0, 0]
        look_at = [0, 0, -1]
        [settings]
        ambient = [0.2, 0.2, 0.2]
        background = [0, 0, 0.5]
        [materials.mirror]
        color = [0.5, 0.5, 0.5]
        kd = 0
        ks = 0.8
        [materials.green]
        color = [0, 1, 0]
        kd = 0
        [[object]]
        name = \"mirror\"
        material = \"mirror\"
        plane = {{ normal = [0, 0, 1], point = [0, 0, -1] }}
        {behind}"
    ))
}

#[test]
fn the_colour_is_traced_to_the_surfaces_it_comes_from() {
    let wall = "[[object]]
        name = \"wall\"
        material = \"green\"
        plane = { normal = [0, 0, -1], point = [0, 0, 2] }";
    let tree = record(&mirror_before(wall), [0.0; 3], [0.0, 0.0, -1.0]);
    // The mirror's own term: 0.2 · 1 · 0.5 = (0.1, 0.1, 0.1). Its reflected
    // ray (weight 0.8, attenuation 1) meets the wall at t = 3, whose own
    // term is 0.2 · (0, 1, 0), reaching the pixel as 0.8 · (0, 0.2, 0) =
    // (0, 0.16, 0). Pixel (0.1, 0.26, 0.1), brightness 0.46: the mirror
    // 0.3 / 0.46 = 65.2%, the wall 0.16 / 0.46 = 34.8%, summing to all of it.
    let story = explain(&tree);
    let expected = "Where the colour comes from: each surface's own ambient + diffuse + \
        specular, times the weights and attenuations of the rays leading to it, as a share \
        of the brightness:\n   65.2%  mirror, hit by r0 (primary, depth 1): adds \
        (0.100, 0.100, 0.100)\n   34.8%  wall, hit by r1 (primary → reflected, depth 2): adds \
        (0.000, 0.160, 0.000)\n";
    assert!(flat(&story).contains(&flat(expected)), "{story}");
}

#[test]
fn a_miss_to_the_background_is_a_source_too() {
    // No wall: the reflected ray misses and brings the background
    // (0, 0, 0.5) unattenuated, 0.8 · 0.5 = 0.4 of blue. Pixel (0.1, 0.1,
    // 0.5), brightness 0.7: background 0.4 / 0.7 = 57.1%, mirror 42.9%.
    let tree = record(&mirror_before(""), [0.0; 3], [0.0, 0.0, -1.0]);
    let story = explain(&tree);
    let expected = "   57.1%  the background, seen by r1 (primary → reflected, depth 2): \
        adds (0.000, 0.000, 0.400)\n   42.9%  mirror, hit by r0 (primary, depth 1): adds \
        (0.100, 0.100, 0.100)\nWhat shaped";
    assert!(flat(&story).contains(&flat(expected)), "{story}");
}

#[test]
fn the_prism_is_green_because_of_the_wall() {
    // scenes/prism.toml's header: the green comes from the wall behind the
    // camera, seen after two total internal reflections.
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/prism.toml");
    let scene = load(&path).unwrap();
    let tree = record_pixel(&scene, &scene.settings, 90, 60);
    let story = flat(&explain(&tree));
    let sources = story.split("Where the colour comes from").nth(1).unwrap();
    let first = sources.split('%').nth(1).unwrap();
    assert!(first.starts_with(" green wall, hit by r4 (primary → transmitted → reflected → reflected → transmitted, depth 5)"), "{story}");
}

#[test]
fn explain_wraps_at_100_columns_and_hides_invisible_events() {
    // glass.toml 135,58 had lines of 317 characters and an event that
    // moved the pixel by 0.000.
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/glass.toml");
    let scene = load(&path).unwrap();
    let tree = record_pixel(&scene, &scene.settings, 135, 58);
    let story = explain(&tree);
    assert!(story.lines().all(|l| l.chars().count() <= 100), "{story}");
    assert!(!story.contains("0.000  "), "{story}");
    assert!(
        story.contains("  1 more event changed nothing visible"),
        "{story}"
    );
    // Continuations of a ranked event hang under its text, past "  0.516  ".
    let at = story
        .lines()
        .position(|l| l.starts_with("  0.516  "))
        .unwrap();
    let next = story.lines().nth(at + 1).unwrap();
    assert!(next.starts_with("         -0.7648"), "{story}");
}

/// The story with its wrapping undone: every run of whitespace one space.
fn flat(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}
