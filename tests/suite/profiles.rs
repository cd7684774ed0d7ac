//! The cse167 profile (MODEL §11) against values worked by hand: each test
//! traces one pixel head-on and checks the terms and bytes that CSE 167's
//! equation gives, and where the lecture's differs, that it still does.

use raystep_engine::record::{explain, record_pixel, text};
use raystep_engine::scene::{Profile, Scene};
use raystep_model::math::to_rgb8;

use crate::support::{path, raystep, scene, stderr, stdout};

/// A 3x3 image whose centre pixel (1, 1) looks straight down -z from z = 5.
const CAMERA: &str =
    "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\n[image]\nwidth = 3\nheight = 3\n";

fn centre(scene: &Scene) -> raystep_engine::record::RayTree {
    record_pixel(scene, &scene.settings, 1, 1)
}

fn with_profile(profile: Profile, body: &str) -> Scene {
    scene(&format!(
        "{CAMERA}[settings]\nprofile = \"{}\"\n{body}",
        profile.name()
    ))
}

#[test]
fn ambient_and_emission_colours_are_added_as_they_are() {
    // No light: I = A + E. A = (0.2, 0.1, 0.05), E = (0.2, 0.3, 0)
    // -> (0.4, 0.4, 0.05) -> bytes floor(255 c + 0.5): (102, 102, 13).
    // The scene's I_a (0.5 grey) and k_a play no part for a material with
    // its own ambient colour, under either profile.
    let body = "ambient = [0.5, 0.5, 0.5]
        [materials.m]
        color = [1, 1, 1]
        ambient = [0.2, 0.1, 0.05]
        emission = [0.2, 0.3, 0]
        [[object]]
        material = \"m\"
        sphere = { center = [0, 0, 0], radius = 1 }";
    for profile in Profile::ALL {
        let tree = centre(&with_profile(profile, body));
        let root = tree.root();
        assert_eq!(root.ambient.to_array(), [0.2, 0.1, 0.05]);
        assert_eq!(root.emission.to_array(), [0.2, 0.3, 0.0]);
        assert_eq!(to_rgb8(root.color), [102, 102, 13], "{profile:?}");
        let words = text(&tree);
        assert!(
            words.contains("ambient = the material's own ambient colour, added as it is"),
            "{words}"
        );
        assert!(
            words.contains("emission E = (0.200, 0.300, 0.000), added as it is"),
            "{words}"
        );
    }
}

/// A ball of radius 1 lit head-on from (0, 0, 1.5), 0.5 from its front
/// point, through attenuation (0, 0, 1): 1 / d² = 4.
const CLOSE_LIGHT: &str = "[materials.m]
        color = [0.1, 0.2, 0.12]
        ambient = [0, 0, 0]
        [[light]]
        position = [0, 0, 1.5]
        color = [0.6, 0.6, 0.6]
        attenuation = [0, 0, 1]
        [[object]]
        material = \"m\"
        sphere = { center = [0, 0, 0], radius = 1 }";

#[test]
fn a_close_light_passes_the_clamp_under_cse167_only() {
    // Hit (0, 0, 1), N = L = (0, 0, 1), N·L = 1, d = 0.5, S = 1.
    // cse167: f_att = 1 / (0 + 0 + 0.25) = 4; diffuse = 4 * 0.6 * D
    //   = 2.4 * (0.1, 0.2, 0.12) = (0.24, 0.48, 0.288)
    //   -> (61.2, 122.4, 73.44) + 0.5 floored: (61, 122, 73).
    // lecture: f_att = min(1, 4) = 1; diffuse = 0.6 * D = (0.06, 0.12, 0.072)
    //   -> (15.3, 30.6, 18.36) + 0.5 floored: (15, 31, 18).
    let tree = centre(&with_profile(Profile::Cse167, CLOSE_LIGHT));
    let light = &tree.root().lights[0];
    assert_eq!((light.distance, light.f_att), (Some(0.5), 4.0));
    assert_eq!(to_rgb8(tree.root().color), [61, 122, 73]);
    let words = text(&tree);
    assert!(
        words.contains("f_att = 1 / (0 + 0 d + 1 d²) = 4, d = 0.5, no clamp"),
        "{words}"
    );
    assert!(words.starts_with("pixel (1, 1)") && words.contains("profile: cse167 (MODEL §11)"));
    let story = explain(&tree);
    assert!(
        story.contains("It is traced with the cse167 profile"),
        "{story}"
    );
    assert!(story.contains("no clamp (the cse167 profile)"), "{story}");

    let tree = centre(&with_profile(Profile::Lecture, CLOSE_LIGHT));
    assert_eq!(tree.root().lights[0].f_att, 1.0);
    assert_eq!(to_rgb8(tree.root().color), [15, 31, 18]);
    assert!(!text(&tree).contains("profile:"));
}

/// A square in the plane z = 0 facing the camera, lit from (10, 0, -1):
/// just behind its plane, yet close to the mirror direction of the view.
const BEHIND: &str = "[materials.m]
        color = [0.3, 0.3, 0.3]
        ambient = [0, 0, 0]
        ks = 1
        n = 1
        specular_color = [0.5, 0.5, 0.5]
        [[light]]
        position = [10, 0, -1]
        [[object]]
        material = \"m\"
        polygon = { vertices = [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]] }";

#[test]
fn a_light_behind_the_surface_still_adds_its_highlight_under_cse167() {
    // Hit (0, 0, 0) at t = 5, N = V = (0, 0, 1). L = (10, 0, -1) / √101
    // = (0.995037, 0, -0.0995037): N·L = -0.0995 <= 0.
    // lecture: the light is behind the surface: no shadow ray, adds
    //   nothing; the mirror ray goes back to the camera side and misses
    //   (black background): pixel (0, 0, 0).
    // cse167: the shadow ray is cast (nothing in the way: S = 1), diffuse
    //   uses (N·L)₊ = 0, and H = normalize(L + V) = normalize(0.995037, 0,
    //   0.900496), |L + V| = √(0.990099 + 0.810893) = 1.342011, so
    //   N·H = 0.900496 / 1.342011 = 0.671005; specular = S f_att I_p k_s O_s
    //   (N·H)^1 = 0.5 * 0.671005 = 0.335502 -> 85.55 + 0.5 floored: 86.
    let tree = centre(&with_profile(Profile::Lecture, BEHIND));
    let light = &tree.root().lights[0];
    assert!(light.faces_away && light.shadow.is_none());
    assert_eq!(to_rgb8(tree.root().color), [0, 0, 0]);

    let tree = centre(&with_profile(Profile::Cse167, BEHIND));
    let light = &tree.root().lights[0];
    assert!(light.faces_away && light.lit_from_behind);
    assert_eq!(light.shadow.as_ref().map(|s| s.s), Some(1.0));
    assert_eq!(light.diffuse.to_array(), [0.0; 3]);
    assert!((light.specular_cosine - 0.671005).abs() < 1e-6);
    assert!((light.specular.x - 0.335502).abs() < 1e-6);
    assert_eq!(to_rgb8(tree.root().color), [86, 86, 86]);
    let words = text(&tree);
    assert!(
        words.contains("diffuse = S · f_att · I_p · k_d · O_d · (N·L)₊"),
        "{words}"
    );
    assert!(
        words.contains("specular = S · f_att · I_p · k_s · O_s · (N·H)^n"),
        "{words}"
    );
    let story = explain(&tree);
    assert!(story.contains("its highlight still counts"), "{story}");
}

#[test]
fn the_mirror_ray_is_weighted_by_the_specular_colour_under_cse167() {
    // A black mirror square seen head-on, white background: the mirror
    // ray goes back along +z and misses, bringing I_R = (1, 1, 1).
    // lecture: adds k_s I_R = 0.5 * (1, 1, 1) -> 127.5 + 0.5 floored: 128.
    // cse167: adds k_s O_s ∘ I_R = 0.5 * (0.2, 0.4, 0.6) = (0.1, 0.2, 0.3)
    //   -> (25.5, 51, 76.5) + 0.5 floored: (26, 51, 77).
    let body = "background = [1, 1, 1]
        [materials.m]
        color = [0, 0, 0]
        ambient = [0, 0, 0]
        ks = 0.5
        specular_color = [0.2, 0.4, 0.6]
        [[object]]
        material = \"m\"
        polygon = { vertices = [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]] }";
    let tree = centre(&with_profile(Profile::Lecture, body));
    assert_eq!(to_rgb8(tree.root().color), [128, 128, 128]);
    let tree = centre(&with_profile(Profile::Cse167, body));
    assert_eq!(to_rgb8(tree.root().color), [26, 51, 77]);
    let mirror = &tree.nodes[tree.root().reflected.unwrap()];
    assert_eq!(mirror.tint.map(|t| t.to_array()), Some([0.2, 0.4, 0.6]));
    let words = text(&tree);
    assert!(
        words.contains("reflected ray, depth 2, weight 0.5 × O_s (0.200, 0.400, 0.600)"),
        "{words}"
    );
    // explain's parts, channel by channel: the background through 0.5 O_s.
    let story = explain(&tree);
    assert!(
        story.contains("0.200  r1 (primary → reflected, depth 2) misses everything")
            && story.contains("adds (0.100, 0.200, 0.300) to the pixel."),
        "{story}"
    );
}

#[test]
fn glass_does_not_refract_under_cse167() {
    // k_t = 0.9 and ior 1.5: the lecture casts a transmitted ray at the
    // ball's front; CSE 167's tracer has no refraction, so no such ray,
    // and its shadows are 0 or 1 (the ball is opaque to them).
    let body = "[materials.glass]
        color = [0, 0, 0]
        kt = 0.9
        ior = 1.5
        [[object]]
        material = \"glass\"
        sphere = { center = [0, 0, 0], radius = 1 }";
    let tree = centre(&with_profile(Profile::Lecture, body));
    assert!(tree.root().transmitted.is_some());
    let tree = centre(&with_profile(Profile::Cse167, body));
    assert!(tree.root().transmitted.is_none() && tree.root().refraction.is_none());
}

#[test]
fn unclamped_attenuation_of_zeros_is_refused_at_its_place() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("zero.toml");
    let text = format!(
        "{CAMERA}[settings]\nprofile = \"cse167\"\n[[light]]\nposition = [0, 0, 3]\nattenuation = [0, 0, 0]\n"
    );
    std::fs::write(&file, text).unwrap();
    let error = raystep_engine::scene::load(&file).unwrap_err().to_string();
    // Line 11 of the file: `attenuation = [0, 0, 0]`, its first number at
    // column 16.
    assert!(error.contains("zero.toml:11:16"), "{error}");
    assert!(
        error.contains("attenuation (0, 0, 0) divides by zero"),
        "{error}"
    );
    // The lecture clamps: the same coefficients are f_att = 1 there.
    std::fs::write(&file, text_without_profile()).unwrap();
    assert!(raystep_engine::scene::load(&file).is_ok());
}

#[test]
fn a_mistake_of_refraction_is_refused_under_cse167_before_anything_is_written() {
    // MODEL §11: no transmitted ray is cast, so eta-inverted could change
    // nothing; render, inspect, explain and diagram say so and exit 1.
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("out.png");
    let svg = dir.path().join("out.svg");
    let scene = "scenes/cse167/mirrors.test";
    let pixel = ["--pixel", "1,1"];
    let runs: [Vec<&str>; 4] = [
        vec!["render", scene, "-o", path(&png)],
        [&["inspect", scene][..], &pixel].concat(),
        [&["explain", scene][..], &pixel].concat(),
        [&["diagram", scene, "-o", path(&svg)][..], &pixel].concat(),
    ];
    for args in runs {
        let output = raystep(&[&args[..], &["--mistake", "eta-inverted"]].concat());
        assert_eq!(output.status.code(), Some(1), "{args:?}");
        assert_eq!(
            stderr(&output),
            "error: --mistake eta-inverted has no meaning under the cse167 profile: \
             it has no refraction (MODEL §11)\n",
            "{args:?}"
        );
        assert!(stdout(&output).is_empty(), "{args:?}");
    }
    assert!(!png.exists() && !svg.exists(), "nothing written");
    // An offered mistake is still taken there, and the lecture takes all.
    let output = raystep(&[
        "render",
        scene,
        "-o",
        path(&png),
        "--mistake",
        "opaque-shadows",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let lecture = ["inspect", "scenes/seven-rays.toml", "--pixel", "1,1"];
    let output = raystep(&[&lecture[..], &["--mistake", "eta-inverted"]].concat());
    assert!(output.status.success(), "{}", stderr(&output));
}

fn text_without_profile() -> String {
    format!("{CAMERA}[[light]]\nposition = [0, 0, 3]\nattenuation = [0, 0, 0]\n")
}
