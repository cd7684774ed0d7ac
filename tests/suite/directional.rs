//! Directional lights (MODEL §4): L is the light's direction at every
//! point, there is no d_L, the shadow ray runs over (EPS, inf) and f_att is
//! 1. Each value below is worked by hand.

use std::path::Path;

use glam::DVec3;
use raystep_engine::record::record_pixel;
use raystep_engine::render::render;
use raystep_engine::scene::{Scene, Settings, parse};
use raystep_engine::trace::NoRecorder;
use raystep_model::mistakes::Mistake;
use serde_json::Value;

use crate::support::{raystep, record, scene, stdout};

fn close(a: DVec3, b: [f64; 3]) -> bool {
    (a - DVec3::from_array(b)).abs().max_element() < 1e-12
}

/// A unit ball at the origin seen head-on down -z by a 1 x 1 image, lit by
/// one directional light towards (0, 3, 4), under `settings`.
fn ball_under_the_sun(settings: &str) -> Scene {
    scene(&format!(
        "[camera]
        eye = [0, 0, 5]
        look_at = [0, 0, 0]
        [image]
        width = 1
        height = 1
        [settings]
        {settings}
        [materials.m]
        color = [1, 0.5, 0.25]
        kd = 0.8
        ks = 0.5
        n = 2
        reflect = false
        [[light]]
        name = \"sun\"
        direction = [0, 3, 4]
        [[object]]
        material = \"m\"
        sphere = {{ center = [0, 0, 0], radius = 1 }}"
    ))
}

fn the_byte(scene: &Scene, settings: &Settings) -> [u8; 3] {
    let (image, _) = render::<NoRecorder>(scene, settings, &|| {});
    image.get_pixel(0, 0).0
}

#[test]
fn a_ball_lit_by_a_directional_light_to_the_byte() {
    let s = ball_under_the_sun("");
    // The only ray goes down -z from (0, 0, 5) and hits (0, 0, 1): N = V = (0, 0, 1).
    // L = (0, 3, 4) / 5 = (0, 0.6, 0.8), the same at every point: N·L = 0.8.
    // H = normalize(L + V) = (0, 0.6, 1.8) / sqrt(0.36 + 3.24) = (0, 0.6, 1.8) / sqrt(3.6):
    //   N·H = 1.8 / sqrt(3.6) = 0.9487, (N·H)^2 = 3.24 / 3.6 = 0.9.
    // S = 1 (nothing above the ball), f_att = 1, ambient black:
    // diffuse  = I_p k_d O_d N·L = 0.8 * 0.8 * (1, 0.5, 0.25) = (0.64, 0.32, 0.16)
    // specular = I_p k_s (N·H)^2 = 0.5 * 0.9 = 0.45 each channel
    // sum = (1.09, 0.77, 0.61)
    // bytes floor(255 c + 0.5), clamped: 255, 196.85 -> 196, 156.05 -> 156.
    let tree = record_pixel(&s, &s.settings, 0, 0);
    let light = &tree.root().lights[0];
    assert!(light.directional);
    assert!(close(light.to_light, [0.0, 0.6, 0.8]));
    assert!((light.n_dot_l - 0.8).abs() < 1e-15);
    assert!((light.specular_cosine - 1.8 / 3.6f64.sqrt()).abs() < 1e-15);
    assert_eq!(light.f_att, 1.0);
    assert_eq!(light.distance, None);
    assert!(close(light.diffuse, [0.64, 0.32, 0.16]));
    let highlight = 0.5 * 3.24 / 3.6;
    assert!(close(light.specular, [highlight; 3]));
    assert_eq!(the_byte(&s, &s.settings), [255, 196, 156]);
}

#[test]
fn a_directional_light_is_never_attenuated() {
    // light_attenuation (1, 0.5, 0.25) would give a point light 2 away
    // f_att = 1 / (1 + 1 + 1) = 1/3; a directional light has no distance
    // and keeps f_att = 1, so the byte is the one of the test above.
    let s = ball_under_the_sun("light_attenuation = [1, 0.5, 0.25]");
    let light = &record_pixel(&s, &s.settings, 0, 0).root().lights[0].clone();
    assert_eq!(light.f_att, 1.0);
    assert!(close(light.diffuse, [0.64, 0.32, 0.16]));
    assert_eq!(the_byte(&s, &s.settings), [255, 196, 156]);
    // Nor do the mistakes whose rule is about a point light's d_L or P_L
    // touch it (MODEL §8): under inverse-square a point light would get
    // min(1, 1 / d_L^2), under light-not-normalised L = P_L - p, under
    // shadows-past-light a segment past d_L.
    for mistake in [
        Mistake::InverseSquare,
        Mistake::NoLightAttenuation,
        Mistake::LightNotNormalised,
        Mistake::ShadowsPastLight,
    ] {
        let settings = Settings {
            mistakes: s.settings.mistakes.with(mistake),
            ..s.settings
        };
        let light = &record_pixel(&s, &settings, 0, 0).root().lights[0].clone();
        assert_eq!(light.f_att, 1.0, "{}", mistake.name());
        assert_eq!(
            the_byte(&s, &settings),
            [255, 196, 156],
            "{}",
            mistake.name()
        );
    }
}

/// A floor at y = 0, a sun straight above it, and an opaque ball of radius
/// 10 at height 9000: farther than any point light could stand from the
/// floor and still light it past the ball.
fn floor_under_a_far_ball() -> Scene {
    scene(
        "[camera]
        eye = [0, 5, 5]
        look_at = [0, 0, 0]
        [settings]
        ambient = [0.2, 0.2, 0.2]
        [materials.floor]
        [materials.ball]
        [[light]]
        name = \"sun\"
        direction = [0, 7, 0]
        [[object]]
        name = \"floor\"
        material = \"floor\"
        plane = { normal = [0, 1, 0], point = [0, 0, 0] }
        [[object]]
        name = \"far ball\"
        material = \"ball\"
        sphere = { center = [0, 9000, 0], radius = 10 }",
    )
}

#[test]
fn a_far_occluder_shadows_a_directional_light() {
    // The ray from (0, 1, 0) straight down hits the floor at the origin (t = 1).
    // L = (0, 1, 0), N·L = 1. The shadow ray up, over (EPS, inf), crosses the
    // ball at t = 9000 - 10 = 8990 and 9000 + 10 = 9010: S = 0, and the
    // floor keeps its ambient alone, 0.2 * 1 = 0.2.
    let tree = record(&floor_under_a_far_ball(), [0.0, 1.0, 0.0], [0.0, -1.0, 0.0]);
    let light = &tree.root().lights[0];
    let shadow = light.shadow.as_ref().unwrap();
    let blockers: Vec<(&str, f64)> = (shadow.blockers.iter())
        .map(|b| (b.object.as_str(), b.t))
        .collect();
    assert_eq!(blockers, [("far ball", 8990.0), ("far ball", 9010.0)]);
    assert_eq!(shadow.s, 0.0);
    assert_eq!(light.diffuse, DVec3::ZERO);
    assert!(close(tree.color(), [0.2, 0.2, 0.2]));
    // Without the ball the floor is lit: 0.2 + k_d O_d N·L = 0.2 + 1 = 1.2.
    let open = scene(
        "[camera]
        eye = [0, 5, 5]
        look_at = [0, 0, 0]
        [settings]
        ambient = [0.2, 0.2, 0.2]
        [materials.floor]
        [[light]]
        direction = [0, 7, 0]
        [[object]]
        material = \"floor\"
        plane = { normal = [0, 1, 0], point = [0, 0, 0] }",
    );
    let tree = record(&open, [0.0, 1.0, 0.0], [0.0, -1.0, 0.0]);
    assert!(close(tree.color(), [1.2, 1.2, 1.2]));
}

/// The error of `light`'s table in an otherwise good scene: (line, column, message).
fn light_error(light: &str) -> (usize, usize, String) {
    let text = format!(
        "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\n[materials.m]\n{light}\
         [[object]]\nmaterial = \"m\"\nsphere = {{ center = [0, 0, 0], radius = 1 }}\n"
    );
    let error = parse(Path::new("t.toml"), &text).unwrap_err();
    let at = error.location.as_ref().unwrap();
    (at.line, at.column, error.message)
}

#[test]
fn a_light_takes_exactly_one_of_position_and_direction() {
    // Both and neither are told at the light's `[[light]]`, line 5, column 1.
    let both = light_error("[[light]]\nposition = [0, 5, 0]\ndirection = [0, 1, 0]\n");
    assert_eq!((both.0, both.1), (5, 1), "{both:?}");
    assert!(both.2.contains("not both"), "{both:?}");
    let neither = light_error("[[light]]\ncolor = [1, 1, 1]\n");
    assert_eq!((neither.0, neither.1), (5, 1), "{neither:?}");
    assert!(
        neither.2.contains("needs `position`") && neither.2.contains("`direction`"),
        "{neither:?}"
    );
    // A zero direction is refused at the array: line 6, column 13.
    assert_eq!(
        light_error("[[light]]\ndirection = [0, 0, 0]\n"),
        (
            6,
            13,
            "a directional light's `direction` must not be zero, got [0, 0, 0]".to_string()
        )
    );
    // Its numbers keep the coordinates' range, at their own place.
    assert_eq!(
        light_error("[[light]]\ndirection = [0, 1e300, 0]\n"),
        (
            6,
            17,
            "`light[0].direction[1]` must be between -10000 and 10000, got 1e300".to_string()
        )
    );
}

#[test]
fn inspect_and_explain_say_what_a_directional_light_is() {
    let scene = "scenes/directional.toml";
    // (20, 100): far floor, lit by the sun at full strength and the lamp dimmed.
    let inspect = stdout(&raystep(&["inspect", scene, "--pixel", "20,100"]));
    snapshot!("inspect_directional_20_100", inspect);
    // L = (-1, 2, 1) / sqrt(6) = (-0.4082, 0.8165, 0.4082), f_att = 1.
    assert!(
        inspect.contains(
            "    directional light, L = (-0.4082, 0.8165, 0.4082), not attenuated: f_att = 1,\n"
        ),
        "{inspect}"
    );
    // The lamp, a point light, is told as before.
    assert!(
        inspect.contains("    f_att = 0.4112, N·H = 0.5525\n"),
        "{inspect}"
    );
    let explain = stdout(&raystep(&["explain", scene, "--pixel", "20,100"]));
    assert!(
        explain.contains("A directional light, L = (-0.4082, 0.8165, 0.4082),")
            && explain.contains("not attenuated: its shadow ray has no end."),
        "{explain}"
    );
    // No d_L for the sun: "distance" is said of the lamp alone.
    let sun_line = explain.lines().find(|l| l.starts_with("  sun:")).unwrap();
    assert!(!sun_line.contains("distance"), "{sun_line}");
    // (100, 68): the big ball's sun shadow, told without a distance to the light.
    let explain = stdout(&raystep(&["explain", scene, "--pixel", "100,68"]));
    assert!(
        explain.contains("towards a") && explain.contains("directional light, which is"),
        "{explain}"
    );
}

/// Every number of a JSON value, with its path.
fn numbers(value: &Value, path: String, out: &mut Vec<(String, f64)>) {
    match value {
        Value::Number(n) => out.push((path, n.as_f64().unwrap())),
        Value::Array(items) => {
            for (i, item) in items.iter().enumerate() {
                numbers(item, format!("{path}[{i}]"), out);
            }
        }
        Value::Object(map) => {
            for (k, v) in map {
                numbers(v, format!("{path}.{k}"), out);
            }
        }
        _ => {}
    }
}

#[test]
fn the_recorded_tree_of_a_directional_light_is_finite_json() {
    // (100, 68): the sun's shadow ray is blocked by the big ball; the lamp
    // lights the floor. JSON writes an infinity or NaN as null, so a
    // segment "to infinity" must not be written as a number at all.
    let out = raystep(&[
        "inspect",
        "scenes/directional.toml",
        "--pixel",
        "100,68",
        "--format",
        "json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = stdout(&out);
    let json: Value = serde_json::from_str(&text).unwrap();
    let mut all = Vec::new();
    numbers(&json, String::new(), &mut all);
    assert!(all.iter().all(|(_, x)| x.is_finite()));
    let lights = json["tree"]["lights"].as_array().unwrap();
    let (sun, lamp) = (&lights[0], &lights[1]);
    assert_eq!(sun["light"], "sun");
    assert_eq!(sun["directional"], true);
    assert!(sun.get("distance").is_none(), "{sun}");
    assert!(sun["shadow"].get("distance").is_none(), "{sun}");
    assert_eq!(sun["f_att"], 1.0);
    // The point lamp keeps every key it had, and no `directional`.
    assert!(lamp["distance"].is_number() && lamp["shadow"]["distance"].is_number());
    assert!(lamp.get("directional").is_none(), "{lamp}");
    // Nowhere a null where a number belongs (serde_json's infinity).
    let nulls: Vec<&str> = ["distance", "t", "f_att", "s", "n_dot_l"]
        .into_iter()
        .filter(|key| text.contains(&format!("\"{key}\": null")))
        .collect();
    assert!(nulls.is_empty(), "{nulls:?}");
}

#[test]
fn the_diagram_draws_a_directional_light_along_its_l_from_every_hit() {
    use raystep_tools::diagram::{Diagram, DiagramPlane, Progress};
    // A directional light has no place: it is drawn along L from the
    // primary ray's hit. The figure is centred on that hit and drawn in the
    // camera's frame, so L, the same everywhere, points the same way in
    // the figures of two pixels whose rays hit the floor far apart (its
    // shadow rays are parallel); the point lamp, a place, lies in
    // different directions from the two hits.
    let scene = raystep_engine::scene::load(Path::new("scenes/directional.toml")).unwrap();
    let seen = |x, y| {
        let tree = record_pixel(&scene, &scene.settings, x, y);
        let point = tree.root().hit.as_ref().unwrap().point;
        let diagram = Diagram::new(&scene, &tree, DiagramPlane::Side, Progress::done(&tree));
        // segments[0] is the primary ray, from the eye to its hit.
        let hit = diagram.segments[0].to;
        let svg = raystep_tools::diagram::svg::figure(&diagram, 1.0);
        assert!(svg.contains("light sun (directional)"), "{svg}");
        assert!(!svg.contains("light lamp (directional)"));
        let (sun, lamp) = (diagram.lights[0].at, diagram.lights[1].at);
        ((sun - hit).normalize(), (lamp - hit).normalize(), point)
    };
    let (sun_a, lamp_a, hit_a) = seen(100, 68);
    let (sun_b, lamp_b, hit_b) = seen(20, 100);
    assert!((hit_a - hit_b).length() > 1.0, "{hit_a} {hit_b}");
    assert!((sun_a - sun_b).length() < 1e-9, "{sun_a} {sun_b}");
    assert!((lamp_a - lamp_b).length() > 0.01, "{lamp_a} {lamp_b}");
}
