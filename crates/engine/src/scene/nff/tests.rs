use super::*;
use crate::scene::Scene;

fn parse_str(text: &str) -> Result<Scene, SceneError> {
    parse(Path::new("t.nff"), text).map(SceneParts::build)
}

/// The (line, column) and message of the error `text` gives.
fn error_of(text: &str) -> (usize, usize, String) {
    let error = parse_str(text).expect_err("the text should be refused");
    let at = error
        .location
        .as_ref()
        .expect("every NFF error has a location");
    (at.line, at.column, error.message.clone())
}

const VIEW: &str = "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 512 512\n";

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * b.abs().max(1.0)
}

#[test]
fn tiny_scene_with_every_entity() {
    let text = "\
b 0.1 0.2 0.3
v
from 1 2 3
at 0 0 0
up 0 0 1
angle 90
hither 0.01
resolution 4 3
l 10 0 0
l 0 10 0 0.5 0.25 1
s 0 0 0 -2
f 1 0 0 0.7 0.3 20 0.5 1.5
c 0 0 0 1 0 0 2 1
c 0 0 0 1
  1 0 0 0.5
p 3
0 0 0
1 0 0
0 1 0
f 0 1 0 1 0 100000 0 0
pp 3
0 0 0 0 0 1
1 0 0 0 0 2
0 1 0 0 0 1
";
    let scene = parse_str(text).unwrap();
    assert_eq!((scene.width, scene.height), (4, 3));
    assert_eq!(scene.settings.background, Color::new(0.1, 0.2, 0.3));
    assert_eq!(scene.camera.eye, DVec3::new(1.0, 2.0, 3.0));
    assert_eq!(scene.camera.look_at, DVec3::ZERO);
    assert_eq!(scene.camera.up, DVec3::Z);
    // angle 90 at H = 3: tan(fov/2) = tan 45 * 3/2 = 1.5, fov = 2 atan 1.5
    // = 2 * 56.309932474020215 = 112.61986494804043 degrees.
    assert!(
        close(scene.camera.fov, 112.61986494804043),
        "{}",
        scene.camera.fov
    );
    assert_eq!(scene.settings.max_depth, 5);
    assert_eq!(scene.settings.light_attenuation, [1.0, 0.0, 0.0]);

    // Two lights: I_a = sqrt 2 / 4 = 0.35355339059327373 grey.
    let grey = 2f64.sqrt() / 4.0;
    assert!(close(grey, 0.35355339059327373));
    assert_eq!(scene.settings.ambient, Color::splat(grey));
    assert_eq!(scene.lights.len(), 2);
    assert_eq!(scene.lights[0].name, "light 0");
    assert_eq!(scene.lights[0].position(), Some(DVec3::new(10.0, 0.0, 0.0)));
    assert_eq!(scene.lights[0].color, Color::splat(grey));
    assert_eq!(scene.lights[1].name, "light 1");
    assert_eq!(scene.lights[1].color, Color::new(0.5, 0.25, 1.0));

    // The sphere comes before the first `f`: it gets the default white,
    // which is then the first material.
    let names: Vec<_> = scene.materials.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names, ["default", "f 0", "f 1"]);
    assert_eq!(scene.materials[0], Material::default_white());
    let glass = &scene.materials[1];
    assert_eq!(glass.color, Color::new(1.0, 0.0, 0.0));
    assert_eq!(
        (
            glass.kd,
            glass.ks,
            glass.shininess,
            glass.kt,
            glass.ior,
            glass.ka
        ),
        (0.7, 0.3, 20.0, 0.5, 1.5, 1.0)
    );
    // Opaque with ior 0: stored as 1.
    let green = &scene.materials[2];
    assert_eq!(
        (green.kd, green.ks, green.shininess, green.kt, green.ior),
        (1.0, 0.0, 100000.0, 0.0, 1.0)
    );

    let objects: Vec<_> = scene
        .objects
        .iter()
        .map(|o| (o.name.to_string(), o.material))
        .collect();
    assert_eq!(
        objects,
        [
            ("sphere 0", 0),
            ("cylinder 1", 1),
            ("cone 2", 1),
            ("polygon 3", 1),
            ("patch 4", 2)
        ]
        .map(|(name, material)| (name.to_string(), material))
    );
    // Negative radius: its absolute value.
    let Shape::Sphere(sphere) = &scene.objects[0].shape else {
        panic!()
    };
    assert_eq!(sphere.radius, 2.0);
    let Shape::Cone(cone) = &scene.objects[2].shape else {
        panic!()
    };
    assert_eq!(
        (cone.base, cone.base_radius, cone.apex, cone.apex_radius),
        (DVec3::ZERO, 1.0, DVec3::X, 0.5)
    );
    let Shape::Polygon(polygon) = &scene.objects[3].shape else {
        panic!()
    };
    assert_eq!(*polygon.vertices, [DVec3::ZERO, DVec3::X, DVec3::Y]);
    let Shape::Patch(patch) = &scene.objects[4].shape else {
        panic!()
    };
    // Normals are stored unit length: (0, 0, 2) becomes (0, 0, 1).
    assert_eq!(*patch.normals, [DVec3::Z, DVec3::Z, DVec3::Z]);
}

#[test]
fn angle_is_between_row_centres() {
    // angle 45 at H = 512: tan(fov/2) = tan(22.5°) * 512/511
    // = 0.41421356237309503 * 1.0019569471624266 = 0.4150241564286197,
    // fov = 2 atan(0.4150241564286197) = 45.07926148765139 degrees.
    let scene = parse_str(&format!("{VIEW}s 0 0 0 1\n")).unwrap();
    assert!(
        close(scene.camera.fov, 45.07926148765139),
        "{}",
        scene.camera.fov
    );
    let expected = 2.0
        * ((22.5f64).to_radians().tan() * 512.0 / 511.0)
            .atan()
            .to_degrees();
    assert!(close(scene.camera.fov, expected));
    // H = 2: the two row centres are half the image apart, so
    // tan(fov/2) = 2 tan(angle/2); angle 90 gives fov = 2 atan 2 = 126.86989764584402.
    assert!(close(fov_from_angle(90.0, 2), 126.86989764584402));
    // H = 1: the angle itself.
    assert_eq!(fov_from_angle(45.0, 1), 45.0);
}

#[test]
fn resolution_height_is_the_one_converted_with() {
    // 8 x 2, angle 90: tan(fov/2) = 1 * 2/1 = 2, fov = 126.86989764584402;
    // the width does not enter.
    let text = VIEW
        .replace("resolution 512 512", "resolution 8 2")
        .replace("angle 45", "angle 90");
    let scene = parse_str(&text).unwrap();
    assert_eq!((scene.width, scene.height), (8, 2));
    assert!(close(scene.camera.fov, 126.86989764584402));
}

#[test]
fn three_lights_share_the_spd_grey() {
    // n = 3: I_a = sqrt 3 / 6 = 0.28867513459481287.
    let scene = parse_str(&format!("{VIEW}l 1 0 0\nl 0 1 0\nl 0 0 1 1 1 1\n")).unwrap();
    let grey = 3f64.sqrt() / 6.0;
    assert!(close(grey, 0.28867513459481287));
    assert_eq!(scene.settings.ambient, Color::splat(grey));
    assert_eq!(scene.lights[0].color, Color::splat(grey));
    assert_eq!(scene.lights[1].color, Color::splat(grey));
    // A coloured light keeps its colour.
    assert_eq!(scene.lights[2].color, Color::ONE);
}

#[test]
fn no_lights_no_ambient_default_background() {
    let scene = parse_str(VIEW).unwrap();
    assert_eq!(scene.settings.ambient, Color::ZERO);
    assert_eq!(scene.settings.background, Color::ZERO);
    assert!(scene.lights.is_empty() && scene.objects.is_empty() && scene.materials.is_empty());
}

#[test]
fn default_white_only_when_used() {
    let scene = parse_str(&format!("{VIEW}f 1 1 1 1 0 0 0 0\ns 0 0 0 1\n")).unwrap();
    assert_eq!(scene.materials.len(), 1);
    assert_eq!(scene.materials[0].name, "f 0");
    assert_eq!(scene.objects[0].material, 0);
}

#[test]
fn cone_on_one_line_or_three() {
    let one = parse_str(&format!("{VIEW}c 1 2 3 0.5 4 5 6 0.25\n")).unwrap();
    let three = parse_str(&format!("{VIEW}c\n1 2 3 0.5\n4 5 6 0.25\n")).unwrap();
    assert_eq!(one.objects, three.objects);
    assert_eq!(one.objects[0].name, "cone 0");
    let Shape::Cone(cone) = &one.objects[0].shape else {
        panic!()
    };
    assert_eq!(cone.base, DVec3::new(1.0, 2.0, 3.0));
    assert_eq!(cone.apex, DVec3::new(4.0, 5.0, 6.0));
    assert_eq!((cone.base_radius, cone.apex_radius), (0.5, 0.25));
    // Equal radii (after the absolute value) make a cylinder.
    let cylinder = parse_str(&format!("{VIEW}c 0 0 0 -1 0 0 1 1\n")).unwrap();
    assert_eq!(cylinder.objects[0].name, "cylinder 0");
}

#[test]
fn comments_run_to_the_end_of_the_line() {
    let text = format!(
        "# a scene\n{VIEW}#s 9 9 9 9\ns 0 0 0 1 # the only sphere\n#\n  # indented\ns 0 0 0 2#glued\n"
    );
    let scene = parse_str(&text).unwrap();
    assert_eq!(scene.objects.len(), 2);
    // A comment inside an entity is skipped too.
    let scene = parse_str(&format!("{VIEW}s 0 0 0 # centre\n 3 # radius\n")).unwrap();
    let Shape::Sphere(sphere) = &scene.objects[0].shape else {
        panic!()
    };
    assert_eq!(sphere.radius, 3.0);
}

#[test]
fn crlf_tabs_bom_and_exponents() {
    let text = format!(
        "\u{feff}{}s\t1e-1 -2.55836e-17 +3 .5\r\n",
        VIEW.replace('\n', "\r\n")
    );
    let scene = parse_str(&text).unwrap();
    let Shape::Sphere(sphere) = &scene.objects[0].shape else {
        panic!()
    };
    assert_eq!(sphere.center, DVec3::new(0.1, -2.55836e-17, 3.0));
    assert_eq!(sphere.radius, 0.5);
}

#[test]
fn viewpoint_on_one_line_in_any_order() {
    let scene = parse_str("v resolution 10 20 up 0 1 0 angle 30 at 0 0 0 from 0 0 1\n").unwrap();
    assert_eq!((scene.width, scene.height), (10, 20));
    assert_eq!(scene.camera.eye, DVec3::Z);
}

// Errors, with the line and column they point at (both 1-based).
// VIEW has 7 lines, so the first line after it is line 8.

#[test]
fn error_missing_number_names_the_token() {
    let (line, column, message) = error_of(&format!("{VIEW}s 0 0 0\np 3\n"));
    assert_eq!((line, column), (9, 1));
    assert_eq!(
        message,
        "expected a number for the sphere's radius, found `p`"
    );
}

#[test]
fn error_end_of_file_points_after_the_last_token() {
    let (line, column, message) = error_of(&format!("{VIEW}p 3\n0 0 0\n1 0 0\n0 1\n\n"));
    // The last token is `1` on line 11, column 3: the error is right after it.
    assert_eq!((line, column), (11, 4));
    assert_eq!(
        message,
        "expected a number for the polygon's vertex 2 (z), found the end of the file"
    );
}

#[test]
fn error_non_finite_numbers() {
    for (bad, column) in [("nan", 7), ("inf", 7), ("-infinity", 7), ("1e400", 7)] {
        let (line, col, message) = error_of(&format!("{VIEW}s 0 0 {bad} 1\n"));
        assert_eq!((line, col), (8, column), "{bad}");
        assert_eq!(
            message,
            format!("the sphere's centre (z) must be a finite number, got `{bad}`")
        );
    }
    let (line, column, message) = error_of(&format!("{VIEW}l 0 0 0 1 NaN 1\n"));
    assert_eq!((line, column), (8, 11));
    assert_eq!(
        message,
        "the light's colour (green) must be a finite number, got `NaN`"
    );
}

#[test]
fn error_unknown_entity() {
    let (line, column, message) = error_of(&format!("{VIEW}s 0 0 0 1\n  tpp 3\n"));
    assert_eq!((line, column), (9, 3));
    assert_eq!(
        message,
        "unknown entity `tpp`: expected an entity keyword (v, b, l, f, c, s, p, pp)"
    );
    let (line, column, message) = error_of(&format!("{VIEW}s 0 0 0 1\nfrom 0 0 0\n"));
    assert_eq!((line, column), (9, 1));
    assert!(message.starts_with("unknown entity `from`"), "{message}");
    assert!(
        message.ends_with("(`from` belongs to a viewpoint and must follow a `v`)"),
        "{message}"
    );
}

#[test]
fn error_extra_number() {
    let (line, column, message) = error_of(&format!("{VIEW}s 0 0 0 1 3.5\n"));
    assert_eq!((line, column), (8, 11));
    assert_eq!(
        message,
        "unexpected number `3.5`: expected an entity keyword (v, b, l, f, c, s, p, pp)"
    );
}

#[test]
fn error_bad_vertex_counts() {
    for bad in ["0", "-3", "2.5", "1e1"] {
        let (line, column, message) = error_of(&format!("{VIEW}p {bad}\n0 0 0\n1 0 0\n0 1 0\n"));
        assert_eq!((line, column), (8, 3), "{bad}");
        assert_eq!(
            message,
            format!("the polygon's vertex count must be a positive integer, got `{bad}`")
        );
    }
    let (line, column, message) = error_of(&format!("{VIEW}pp x\n"));
    assert_eq!((line, column), (8, 4));
    assert_eq!(
        message,
        "expected a number for the patch's vertex count, found `x`"
    );
    // A count beyond memory is not allocated: the vertices run out first.
    let (line, column, message) = error_of(&format!("{VIEW}p 99999999999999999999999\n0 0 0\n"));
    assert_eq!((line, column), (9, 6));
    assert_eq!(
        message,
        "expected a number for the polygon's vertex 1 (x), found the end of the file"
    );
}

#[test]
fn error_geometry_at_the_keyword() {
    let (line, column, message) = error_of(&format!("{VIEW}s 0 0 0 1\n s 1 1 1 0\n"));
    // A zero radius is out of range, at the number itself (line 9, column 10).
    assert_eq!((line, column), (9, 10));
    assert_eq!(
        message,
        "the sphere's radius must be between 0.001 and 10000 in absolute value, got `0`"
    );
    let (line, column, message) = error_of(&format!("{VIEW}p 3\n0 0 0\n1 0 0\n2 0 0\n"));
    assert_eq!((line, column), (8, 1));
    assert!(
        message.starts_with("polygon 0: vertices 0, 1 and 2 are collinear"),
        "{message}"
    );
    let (_, _, message) = error_of(&format!("{VIEW}p 2\n0 0 0\n1 0 0\n"));
    assert_eq!(
        message,
        "polygon 0: a polygon needs at least 3 vertices, got 2"
    );
    let (line, column, message) = error_of(&format!("{VIEW}c 1 1 1 1 1 1 1 1\n"));
    assert_eq!((line, column), (8, 1));
    assert_eq!(message, "cylinder 0: the cone's two ends coincide");
    let (_, _, message) = error_of(&format!("{VIEW}c 0 0 0 0 0 0 1 0\n"));
    assert_eq!(
        message,
        "cylinder 0: cone radii must be >= 0 and not both 0, got 0 and 0"
    );
    let (line, column, message) = error_of(&format!(
        "{VIEW}pp 3\n0 0 0 0 0 1\n1 0 0 0 0 0\n0 1 0 0 0 1\n"
    ));
    assert_eq!((line, column), (8, 1));
    assert_eq!(message, "patch 0: vertex normal 1 is zero");
}

#[test]
fn error_transmitting_material_without_ior() {
    let (line, column, message) =
        error_of(&format!("{VIEW}f 1 1 1 0 0 0 0 0\nf 1 1 1 0 0 0 0.8 0\n"));
    // The first `f` is opaque: ior 0 is the SPD's "none". The second (index
    // 1) transmits: its ior `0` is on line 9, column 19.
    assert_eq!((line, column), (9, 19));
    assert_eq!(
        message,
        "f 1: the material's index of refraction must be between 0.1 and 10, got `0`"
    );
}

#[test]
fn error_negative_coefficients() {
    let (line, column, message) = error_of(&format!("{VIEW}f 1 1 1 0.5 -0.5 3 0 0\n"));
    assert_eq!((line, column), (8, 13));
    assert_eq!(
        message,
        "the material's Ks must be between 0 and 100, got `-0.5`"
    );
    let (line, column, message) = error_of(&format!("{VIEW}f 1 1 1 0.5 0.5 3 1.5 1.5\n"));
    assert_eq!((line, column), (8, 19));
    assert_eq!(
        message,
        "the material's T must be between 0 and 1, got `1.5`"
    );
    let (line, column, message) = error_of(&format!("{VIEW}l 0 0 0 1 1 -1\n"));
    assert_eq!((line, column), (8, 13));
    assert_eq!(
        message,
        "the light's colour (blue) must be between 0 and 1e6, got `-1`"
    );
}

#[test]
fn error_missing_or_second_viewpoint() {
    let (line, column, message) = error_of("s 0 0 0 1\n");
    assert_eq!((line, column), (1, 1));
    assert_eq!(
        message,
        "the file has no viewpoint `v`: an NFF file must have exactly one"
    );
    assert!(error_of("").2.contains("no viewpoint"));
    let (line, column, message) = error_of(&format!("{VIEW}s 0 0 0 1\n{VIEW}"));
    assert_eq!((line, column), (9, 1));
    assert_eq!(
        message,
        "a second viewpoint `v`: a file has exactly one (the first is on line 1)"
    );
    let (line, column, message) =
        error_of("b 0 0 0\n\nv\nfrom 0 0 1\nat 0 0 0\nup 0 1 0\nresolution 4 4\n");
    assert_eq!((line, column), (3, 1));
    assert_eq!(message, "the viewpoint `v` has no `angle`");
    let (line, column, message) = error_of(&VIEW.replace("hither 1", "from 1 1 1"));
    assert_eq!((line, column), (6, 1));
    assert_eq!(message, "the viewpoint gives `from` twice");
}

#[test]
fn error_image_size_and_camera() {
    let (line, column, message) = error_of(&VIEW.replace("resolution 512 512", "resolution 0 512"));
    assert_eq!((line, column), (7, 1));
    assert_eq!(
        message,
        "image size 0x512 is empty: both sides must be at least 1"
    );
    let (line, column, message) =
        error_of(&VIEW.replace("resolution 512 512", "resolution 512 51.2"));
    assert_eq!((line, column), (7, 16));
    assert_eq!(
        message,
        "the viewpoint's resolution height must be a whole number of pixels, got `51.2`"
    );
    // Camera errors point at `v`.
    let (line, column, message) = error_of(&VIEW.replace("at 0 0 0", "at 0 0 5"));
    assert_eq!((line, column), (1, 1));
    assert!(
        message.starts_with("camera eye and look_at are the same point"),
        "{message}"
    );
    let (line, column, message) = error_of(&VIEW.replace("up 0 1 0", "up 0 0 -2"));
    assert_eq!((line, column), (1, 1));
    assert!(
        message.contains("parallel to the viewing direction"),
        "{message}"
    );
    let (line, column, message) = error_of(&VIEW.replace("angle 45", "angle 180"));
    assert_eq!((line, column), (5, 7));
    assert_eq!(
        message,
        "the viewpoint's `angle` must be between 0 and 180 degrees (exclusive), got 180"
    );
}

#[test]
fn error_display_shows_the_line() {
    let error = parse_str(&format!("{VIEW}s 0 0 0 x\n")).unwrap_err();
    assert_eq!(
        error.to_string(),
        "t.nff:8:9: expected a number for the sphere's radius, found `x`\n  |\n8 | s 0 0 0 x\n  |         ^"
    );
}

#[test]
fn never_panics_on_truncated_or_mangled_input() {
    let text = format!(
        "{VIEW}l 1 2 3\nl 1 2 3 1 1 1\nf 1 0 0 0.5 0.5 3 0.5 1.5\ns 0 0 0 1\nc 0 0 0 1 0 0 1 0.5\n\
         p 3\n0 0 0\n1 0 0\n0 1 0\npp 3\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n# é ü\n"
    );
    for end in (0..=text.len()).filter(|&i| text.is_char_boundary(i)) {
        let _ = parse_str(&text[..end]);
        let _ = parse_str(&text[end..]);
    }
    // Every token replaced, in turn, by awkward words.
    let tokens: Vec<&str> = text.split_ascii_whitespace().collect();
    for i in 0..tokens.len() {
        for odd in [
            "",
            "-0",
            "1e308",
            "-1e-320",
            "é",
            "#",
            "p",
            "pp",
            "v",
            "99999999999",
            "0.0",
            "\u{a0}",
        ] {
            let mut mangled = tokens.clone();
            mangled[i] = odd;
            let _ = parse_str(&mangled.join(" "));
        }
    }
}

mod properties {
    use proptest::prelude::*;

    use super::*;

    proptest! {
        #[test]
        fn random_token_soup_never_panics(
            words in proptest::collection::vec(
                prop_oneof![
                    Just("v".to_string()), Just("b".to_string()), Just("l".to_string()),
                    Just("f".to_string()), Just("c".to_string()), Just("s".to_string()),
                    Just("p".to_string()), Just("pp".to_string()), Just("from".to_string()),
                    Just("at".to_string()), Just("up".to_string()), Just("angle".to_string()),
                    Just("resolution".to_string()), Just("hither".to_string()), Just("#".to_string()),
                    Just("\n".to_string()), Just("nan".to_string()),
                    (-3i32..5).prop_map(|n| n.to_string()),
                    any::<f64>().prop_map(|x| x.to_string()),
                    "\\PC{0,3}",
                ],
                0..60,
            )
        ) {
            let _ = parse_str(&words.join(" "));
        }
    }
}

/// Issue 13, section 2: numbers out of their range (`scene::limits`) gave NaN
/// or infinity; each is refused at its token.
#[test]
fn error_ior_out_of_range() {
    // T = 0.8 with ior 1e-300: eta = 1e300 on entering, k = 1 - inf * 0 = NaN.
    for bad in ["1e-300", "1e300", "-1.5", "0"] {
        let (line, column, message) = error_of(&format!("{VIEW}f 1 1 1 0 0 0 0.8 {bad}\n"));
        assert_eq!((line, column), (8, 19), "{bad}");
        assert_eq!(
            message,
            format!(
                "f 0: the material's index of refraction must be between 0.1 and 10, got `{bad}`"
            )
        );
    }
    // Opaque: the SPD's ior 0 is stored as air's; any other value is an index.
    let scene = parse_str(&format!("{VIEW}f 1 1 1 1 0 0 0 0\nf 1 1 1 1 0 0 0 2\n")).unwrap();
    assert_eq!((scene.materials[0].ior, scene.materials[1].ior), (1.0, 2.0));
    let (line, column, message) = error_of(&format!("{VIEW}f 1 1 1 1 0 0 0 -1\n"));
    assert_eq!((line, column), (8, 17));
    assert_eq!(
        message,
        "f 0: the material's index of refraction must be between 0.1 and 10 (or be 0 where T = 0), got `-1`"
    );
}

#[test]
fn error_huge_numbers() {
    let cases = [
        // (entity, line, column, message); VIEW fills lines 1 to 7.
        (
            "f 1e308 1 1 1 0 0 0 0",
            (8, 3),
            "the material's colour (red) must be between 0 and 1e6, got `1e308`",
        ),
        (
            "f 1 1 1 1 0 1e300 0 0",
            (8, 13),
            "the material's Shine must be between 0 and 1e6, got `1e300`",
        ),
        (
            "f 1 1 1 1e300 0 0 0 0",
            (8, 9),
            "the material's Kd must be between 0 and 100, got `1e300`",
        ),
        (
            "l 0 1e200 0",
            (8, 5),
            "the light's position (y) must be between -10000 and 10000, got `1e200`",
        ),
        (
            "l 0 10 0 1 1e308 1",
            (8, 12),
            "the light's colour (green) must be between 0 and 1e6, got `1e308`",
        ),
        (
            "s 0 0 0 -1e300",
            (8, 9),
            "the sphere's radius must be between 0.001 and 10000 in absolute value, got `-1e300`",
        ),
        (
            "c -1e308 0 0 1 1e308 0 0 1",
            (8, 3),
            "the cone's base (x) must be between -10000 and 10000, got `-1e308`",
        ),
        (
            "c 0 0 0 1 0 1 0 1e-5",
            (8, 17),
            "the cone's apex radius must be between 0.001 and 10000 in absolute value (or be 0), got `1e-5`",
        ),
        (
            "p 3\n0 0 0\n1 0 0\n0 1e9 0",
            (11, 3),
            "the polygon's vertex 2 (y) must be between -10000 and 10000, got `1e9`",
        ),
    ];
    for (entity, at, message) in cases {
        let (line, column, got) = error_of(&format!("{VIEW}{entity}\n"));
        assert_eq!(((line, column), got.as_str()), (at, message), "{entity}");
    }
    // Ends 1e4 apart on each axis, so sqrt(3) 1e4 apart: longer than any size.
    let (line, column, message) = error_of(&format!("{VIEW}c 0 0 0 1 1e4 1e4 1e4 1\n"));
    assert_eq!((line, column), (8, 1));
    assert!(
        message.starts_with("cylinder 0: the distance between the ends is 17320.5"),
        "{message}"
    );
}

#[test]
fn error_negative_background() {
    let (line, column, message) = error_of(&format!("{VIEW}b 0.1 -0.1 0.1\n"));
    assert_eq!((line, column), (8, 7));
    assert_eq!(
        message,
        "the background's green must be between 0 and 1e6, got `-0.1`"
    );
}
