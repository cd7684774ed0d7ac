//! Every number a TOML scene holds is finite and within its range
//! (`raystep_engine::scene::limits`, docs/SCENES.md), or the scene is refused
//! with the key, the value and its line and column. Issue 13, section 2:
//! each case below was accepted before and gave NaN or infinity.

use std::path::Path;

use raystep_engine::scene::{self, SceneError};

/// A valid scene; every case below changes one line of it.
const GOOD: &str = r#"[camera]
eye = [0, 1, 6]
look_at = [0, 1, 0]

[settings]
ambient = [0.1, 0.1, 0.1]

[materials.glass]
color = [1, 1, 1]
kt = 0.8
ior = 1.5

[[light]]
position = [5, 8, 5]

[[object]]
material = "glass"
sphere = { center = [0, 1, 0], radius = 1 }
"#;

/// The (line, column) and message of the error of GOOD with `from` replaced by `to`.
fn error_of(from: &str, to: &str) -> (usize, usize, String) {
    assert!(GOOD.contains(from), "{from}");
    let text = GOOD.replace(from, to);
    let error: SceneError = scene::parse(Path::new("t.toml"), &text)
        .map(|_| ())
        .expect_err("the scene should be refused");
    let at = error.location.expect("every range error has a location");
    (at.line, at.column, error.message)
}

#[test]
fn good_scene_loads() {
    let scene = scene::parse(Path::new("t.toml"), GOOD).unwrap();
    assert_eq!(scene.materials[0].ior, 1.5);
}

#[test]
fn ior_outside_a_tenth_to_ten_is_refused() {
    // ior = 1e-300 gave eta = 1e300 and k = 1 - inf * 0 = NaN on entering.
    let (line, column, message) = error_of("ior = 1.5", "ior = 1e-300");
    assert_eq!((line, column), (11, 7));
    assert_eq!(
        message,
        "`materials.glass.ior` must be between 0.1 and 10, got 1e-300"
    );
    let (_, _, message) = error_of("ior = 1.5", "ior = 1e300");
    assert_eq!(
        message,
        "`materials.glass.ior` must be between 0.1 and 10, got 1e300"
    );
    // The ends of the range are in it.
    for ior in ["0.1", "10"] {
        let text = GOOD.replace("ior = 1.5", &format!("ior = {ior}"));
        assert!(scene::parse(Path::new("t.toml"), &text).is_ok(), "{ior}");
    }
}

#[test]
fn huge_finite_numbers_are_refused_at_their_place() {
    let cases = [
        // (line to change, its replacement, line, column, message)
        (
            "color = [1, 1, 1]",
            "color = [1, 1e308, 1]",
            9,
            13,
            "`materials.glass.color[1]` must be between 0 and 1e6, got 1e308",
        ),
        (
            "position = [5, 8, 5]",
            "position = [5, 8, 1e200]\ncolor = [1, 1, 1]",
            14,
            19,
            "`light[0].position[2]` must be between -10000 and 10000, got 1e200",
        ),
        (
            "position = [5, 8, 5]",
            "position = [5, 8, 5]\ncolor = [1e308, 1, 1]",
            15,
            10,
            "`light[0].color[0]` must be between 0 and 1e6, got 1e308",
        ),
        (
            "radius = 1 }",
            "radius = 1e300 }",
            18,
            41,
            "`object[0].sphere.radius` must be between 0.001 and 10000, got 1e300",
        ),
        (
            "ior = 1.5",
            "ior = 1.5\nn = 1e300",
            12,
            5,
            "`materials.glass.n` must be between 0 and 1e6, got 1e300",
        ),
        (
            "ior = 1.5",
            "ior = 1.5\nks = 1e300",
            12,
            6,
            "`materials.glass.ks` must be between 0 and 100, got 1e300",
        ),
        (
            "ambient = [0.1, 0.1, 0.1]",
            "ambient = [0.1, 0.1, 0.1]\nlight_attenuation = [1, 1e300, 0]",
            7,
            25,
            "`settings.light_attenuation[1]` must be between 0 and 1e6, got 1e300",
        ),
        (
            "eye = [0, 1, 6]",
            "eye = [0, 1, 1e7]",
            2,
            14,
            "`camera.eye[2]` must be between -10000 and 10000, got 1e7",
        ),
    ];
    for (from, to, line, column, message) in cases {
        assert_eq!(
            error_of(from, to),
            (line, column, message.to_string()),
            "{to}"
        );
    }
}

#[test]
fn cylinder_ends_far_apart_are_refused() {
    let sphere = "sphere = { center = [0, 1, 0], radius = 1 }";
    // Ends 2e308 apart: each end is out of range before their distance overflows.
    let (line, column, message) = error_of(
        sphere,
        "cylinder = { base = [-1e308, 0, 0], apex = [1e308, 0, 0], radius = 1 }",
    );
    assert_eq!((line, column), (18, 22));
    assert_eq!(
        message,
        "`object[0].cylinder.base[0]` must be between -10000 and 10000, got -1e308"
    );
    // Ends within range but 3e4 * sqrt(2) apart, more than a size may be.
    let (line, column, message) = error_of(
        sphere,
        "cylinder = { base = [-1e4, -1e4, 0], apex = [1e4, 1e4, 0], radius = 1 }",
    );
    assert_eq!((line, column), (18, 12));
    assert!(
        message.starts_with("`object[0].cylinder`: the distance between the ends is 28284.27")
            && message.ends_with("it must be between 0.001 and 10000"),
        "{message}"
    );
    // A cone's pointed end has radius 0; a tiny non-zero one is refused.
    let (line, column, message) = error_of(
        sphere,
        "cone = { base = [0, 0, 0], base_radius = 1, apex = [0, 1, 0], apex_radius = 1e-9 }",
    );
    assert_eq!((line, column), (18, 77));
    assert_eq!(
        message,
        "`object[0].cone.apex_radius` must be between 0.001 and 10000 (or be 0), got 1e-9"
    );
}

#[test]
fn negative_background_ambient_and_attenuation_are_refused() {
    let cases = [
        (
            "ambient = [0.1, 0.1, 0.1]",
            "ambient = [0.1, -0.1, 0.1]",
            (6, 17),
            "`settings.ambient[1]` must be between 0 and 1e6, got -0.1",
        ),
        (
            "ambient = [0.1, 0.1, 0.1]",
            "background = [-1, 0, 0]",
            (6, 15),
            "`settings.background[0]` must be between 0 and 1e6, got -1",
        ),
        (
            "ambient = [0.1, 0.1, 0.1]",
            "ray_attenuation = [1, 0, -0.5]",
            (6, 26),
            "`settings.ray_attenuation[2]` must be between 0 and 1e6, got -0.5",
        ),
        (
            "ior = 1.5",
            "ior = 1.5\nka = -1",
            (12, 6),
            "`materials.glass.ka` must be between 0 and 100, got -1",
        ),
    ];
    for (from, to, (line, column), message) in cases {
        assert_eq!(
            error_of(from, to),
            (line, column, message.to_string()),
            "{to}"
        );
    }
}

#[test]
fn vectors_have_exactly_three_elements() {
    let (line, column, message) = error_of("eye = [0, 1, 6]", r#"eye = [0, 1, 6, "junk"]"#);
    assert_eq!((line, column), (2, 7));
    assert_eq!(
        message,
        "expected an array of three numbers (x, y, z or red, green, blue), got 4"
    );
    let (line, column, message) = error_of("color = [1, 1, 1]", "color = [1, 0, 0, 0.5]");
    assert_eq!((line, column), (9, 9));
    assert!(message.ends_with("got 4"), "{message}");
    let (line, column, message) = error_of("color = [1, 1, 1]", "color = [1, 0]");
    assert_eq!((line, column), (9, 9));
    assert!(message.ends_with("got 2"), "{message}");
    let (_, _, message) = error_of("eye = [0, 1, 6]", "eye = []");
    assert!(message.ends_with("got 0"), "{message}");
}

#[test]
fn fov_error_points_at_the_fov() {
    let (line, column, message) = error_of("look_at = [0, 1, 0]", "look_at = [0, 1, 0]\nfov = 180");
    assert_eq!((line, column), (4, 7));
    assert_eq!(
        message,
        "fov must be between 0 and 180 degrees (exclusive), got 180"
    );
}

#[test]
fn degenerate_camera_is_refused() {
    let (line, _, message) = error_of("eye = [0, 1, 6]", "eye = [0, 1, 0]");
    assert_eq!(line, 1);
    assert!(message.starts_with("camera eye and look_at are the same point"));
    let (_, _, message) = error_of("look_at = [0, 1, 0]", "look_at = [0, 1, 0]\nup = [0, 0, 0]");
    assert!(message.contains("is zero or parallel"), "{message}");
    let (_, _, message) = error_of(
        "look_at = [0, 1, 0]",
        "look_at = [0, 1, 0]\nup = [0, 0, -2]",
    );
    assert!(message.contains("is zero or parallel"), "{message}");
}

#[test]
fn every_scene_in_the_repository_loads() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut count = 0;
    for dir in ["scenes", "scenes/spd"] {
        for entry in std::fs::read_dir(root.join(dir)).unwrap() {
            let path = entry.unwrap().path();
            let ext = path.extension().and_then(|e| e.to_str());
            if matches!(ext, Some("toml" | "nff")) {
                scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
                count += 1;
            }
        }
    }
    // 11 teaching scenes (two-lights and prism for issue 16's five
    // questions, directional for issue 42's lights, ellipsoid for its
    // ellipsoids) and 14 SPD files.
    assert_eq!(count, 25);
}
