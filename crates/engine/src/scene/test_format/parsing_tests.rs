use super::*;

fn read(text: &str) -> Result<TestScene, SceneError> {
    parse(text, Path::new("t.test"))
}

/// The (line, column) and message of the error `text` gives.
fn error_of(text: &str) -> (usize, usize, String) {
    let error = read(text).expect_err("the text should be refused");
    let at = error.location.as_ref().expect("every error has a location");
    (at.line, at.column, error.message.clone())
}

const HEAD: &str = "size 40 30\ncamera 0 0 5 0 0 0 0 1 0 45\n";

fn close(a: DVec3, b: DVec3) -> bool {
    (a - b).abs().max_element() <= 1e-12
}

#[test]
fn defaults_and_header() {
    let scene = read("# a comment\n\nsize 40 30\ncamera 0 0 5 0 0 0 0 1 0 45\n").unwrap();
    assert_eq!(scene.size, (40, 30));
    assert_eq!(scene.size_line, 3);
    assert_eq!(scene.maxdepth, 5);
    assert_eq!(scene.output, None);
    assert_eq!(scene.attenuation, DEFAULT_ATTENUATION);
    assert_eq!(scene.attenuation_line, None);
    let c = scene.camera;
    assert_eq!(
        (c.eye, c.look_at, c.up, c.fovy, c.line),
        (DVec3::Z * 5.0, DVec3::ZERO, DVec3::Y, 45.0, 4)
    );
}

#[test]
fn sphere_under_translate_then_scale() {
    // top = T(1,0,0) * S(2): the object is scaled first, then moved.
    // Centre (1, 0, 0) -> scaled (2, 0, 0) -> moved (3, 0, 0).
    let text = format!("{HEAD}translate 1 0 0\nscale 2 2 2\nsphere 1 0 0 0.5\n");
    let scene = read(&text).unwrap();
    let TestShape::Sphere {
        center,
        radius,
        transform,
        world_center,
    } = scene.objects[0].shape
    else {
        panic!("a sphere")
    };
    assert_eq!((center, radius), (DVec3::X, 0.5));
    assert_eq!(world_center, DVec3::new(3.0, 0.0, 0.0));
    let expected = DMat4::from_cols_array(&[
        2.0, 0.0, 0.0, 0.0, //
        0.0, 2.0, 0.0, 0.0, //
        0.0, 0.0, 2.0, 0.0, //
        1.0, 0.0, 0.0, 1.0,
    ]);
    assert_eq!(transform, expected);
    assert_eq!(scene.objects[0].line, 5);
}

#[test]
fn scale_then_translate_moves_by_the_scaled_amount() {
    // top = S(2) * T(1,0,0): the translation is scaled too, centre 0 -> (2, 0, 0).
    let text = format!("{HEAD}scale 2 2 2\ntranslate 1 0 0\nsphere 0 0 0 1\n");
    let TestShape::Sphere { world_center, .. } = read(&text).unwrap().objects[0].shape else {
        panic!("a sphere")
    };
    assert_eq!(world_center, DVec3::new(2.0, 0.0, 0.0));
}

#[test]
fn tri_under_rotate_about_z() {
    // 90 degrees counter-clockwise about z: (1,0,0) -> (0,1,0), (0,1,0) -> (-1,0,0),
    // (0,0,1) stays.
    let text = format!(
        "{HEAD}maxverts 3\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\nrotate 0 0 1 90\ntri 0 1 2\n"
    );
    let scene = read(&text).unwrap();
    let TestShape::Triangle { vertices } = scene.objects[0].shape else {
        panic!("a triangle")
    };
    assert!(close(vertices[0], DVec3::Y), "{vertices:?}");
    assert!(close(vertices[1], -DVec3::X), "{vertices:?}");
    assert!(close(vertices[2], DVec3::Z), "{vertices:?}");
    // The axis is normalised: (0, 0, 5) is the same turn.
    let text = text.replace("rotate 0 0 1 90", "rotate 0 0 5 90");
    assert_eq!(read(&text).unwrap().objects, scene.objects);
}

#[test]
fn push_and_pop_restore_the_transform() {
    let text = format!(
        "{HEAD}translate 0 1 0\npushTransform\ntranslate 5 0 0\nsphere 0 0 0 1\npopTransform\nsphere 0 0 0 1\n"
    );
    let scene = read(&text).unwrap();
    let centres: Vec<DVec3> = scene
        .objects
        .iter()
        .map(|o| match o.shape {
            TestShape::Sphere { world_center, .. } => world_center,
            _ => panic!("spheres"),
        })
        .collect();
    assert_eq!(
        centres,
        [DVec3::new(5.0, 1.0, 0.0), DVec3::new(0.0, 1.0, 0.0)]
    );
}

#[test]
fn trinormal_normals_use_the_inverse_transpose() {
    // scale 2 1 1: the normal (1, 1, 0) becomes (1/2, 1, 0), normalised
    // (1, 2, 0) / sqrt(5); the vertex (1, 0, 0) becomes (2, 0, 0).
    let text = format!(
        "{HEAD}maxvertnorms 3\nvertexnormal 1 0 0 1 1 0\nvertexnormal 0 1 0 0 0 1\nvertexnormal 0 0 0 0 0 3\nscale 2 1 1\ntrinormal 0 1 2\n"
    );
    let scene = read(&text).unwrap();
    let TestShape::NormalTriangle { vertices, normals } = scene.objects[0].shape else {
        panic!("a trinormal")
    };
    assert_eq!(vertices, [DVec3::new(2.0, 0.0, 0.0), DVec3::Y, DVec3::ZERO]);
    assert!(close(normals[0], DVec3::new(1.0, 2.0, 0.0) / 5f64.sqrt()));
    assert_eq!((normals[1], normals[2]), (DVec3::Z, DVec3::Z));
}

#[test]
fn material_state_is_copied_when_each_object_is_made() {
    let text = format!(
        "{HEAD}sphere 0 0 0 1\nambient 0 0 0\ndiffuse 1 0 0\nspecular 0.5 0.5 0.5\nshininess 20\nemission 0.1 0.2 0.3\nsphere 0 0 0 1\n"
    );
    let scene = read(&text).unwrap();
    assert_eq!(scene.objects[0].material, TestMaterial::default());
    assert_eq!(scene.objects[0].material.ambient, DVec3::splat(0.2));
    assert_eq!(
        scene.objects[1].material,
        TestMaterial {
            ambient: DVec3::ZERO,
            diffuse: DVec3::X,
            specular: DVec3::splat(0.5),
            shininess: 20.0,
            emission: DVec3::new(0.1, 0.2, 0.3),
        }
    );
}

#[test]
fn lights_are_transformed_and_attenuation_recorded() {
    // translate 0 0 10 moves a point light but not a direction (w = 0);
    // rotate 0 0 1 90 turns the direction (1, 0, 0) to (0, 1, 0).
    let text = format!(
        "{HEAD}point 1 0 0 1 1 1\nattenuation 0 0 1\ntranslate 0 0 10\npoint 1 0 0 0.5 0.5 0.5\nrotate 0 0 1 90\ndirectional 1 0 0 1 0 0\nattenuation 1 0.1 0.05\n"
    );
    let scene = read(&text).unwrap();
    let [first, second, third] = scene.lights[..] else {
        panic!("three lights")
    };
    assert_eq!(first.kind, TestLightKind::Point { position: DVec3::X });
    assert_eq!(first.attenuation, Some(DEFAULT_ATTENUATION));
    assert_eq!(
        second.kind,
        TestLightKind::Point {
            position: DVec3::new(1.0, 0.0, 10.0)
        }
    );
    let inverse_square = Attenuation {
        constant: 0.0,
        linear: 0.0,
        quadratic: 1.0,
    };
    assert_eq!(second.attenuation, Some(inverse_square));
    assert_eq!(second.color, DVec3::splat(0.5));
    let TestLightKind::Directional { direction } = third.kind else {
        panic!("a directional light")
    };
    assert!(close(direction, DVec3::Y), "{direction}");
    assert_eq!(
        (third.attenuation, third.color, third.line),
        (None, DVec3::X, 8)
    );
    // The global value is the last one set.
    assert_eq!(
        scene.attenuation,
        Attenuation {
            constant: 1.0,
            linear: 0.1,
            quadratic: 0.05
        }
    );
    assert_eq!(scene.attenuation_line, Some(9));
}

#[test]
fn maxdepth_output_comments_crlf_and_bom() {
    let text = "\u{feff}size 2 2\r\n  # indented comment\r\ncamera 0 0 5 0 0 0 0 1 0 45 # trailing\r\nmaxdepth 0\r\nmaxdepth 3\r\noutput scene.png\r\n";
    let scene = read(text).unwrap();
    assert_eq!(scene.maxdepth, 3);
    assert_eq!(scene.output, Some(("scene.png".into(), 6)));
}

#[test]
fn error_unknown_command() {
    let (line, col, message) = error_of(&format!("{HEAD}  pushtransform\n"));
    assert_eq!((line, col), (3, 3));
    assert!(
        message.starts_with("unknown command `pushtransform`"),
        "{message}"
    );
    assert!(
        message.contains("did you mean `pushTransform`"),
        "{message}"
    );
}

#[test]
fn error_wrong_number_of_values() {
    let (line, col, message) = error_of(&format!("{HEAD}sphere 0 0 0\n"));
    // The end of `sphere 0 0 0`: column 13.
    assert_eq!((line, col), (3, 13));
    assert_eq!(
        message,
        "`sphere` takes 4 values (x y z radius), found 3: radius is missing"
    );
    let (line, col, message) = error_of(&format!("{HEAD}sphere 0 0 0 1 2\n"));
    assert_eq!((line, col), (3, 16));
    assert!(message.contains("`2` is one too many"), "{message}");
    let (line, col, _) = error_of(&format!("{HEAD}popTransform x\n"));
    assert_eq!((line, col), (3, 14));
}

#[test]
fn error_not_a_number_or_not_finite() {
    let (line, col, message) = error_of(&format!("{HEAD}sphere 0 abc 0 1\n"));
    assert_eq!((line, col), (3, 10));
    assert_eq!(
        message,
        "expected a number for the sphere's centre (y), found `abc`"
    );
    let (line, col, message) = error_of(&format!("{HEAD}diffuse 1 inf 0\n"));
    assert_eq!((line, col), (3, 11));
    assert_eq!(
        message,
        "the diffuse colour (green) must be a finite number, got `inf`"
    );
    let (line, col, _) = error_of(&format!("{HEAD}translate NaN 0 0\n"));
    assert_eq!((line, col), (3, 11));
}

#[test]
fn error_size_not_first_or_missing_or_twice() {
    let (line, col, message) = error_of("# c\ncamera 0 0 5 0 0 0 0 1 0 45\nsize 2 2\n");
    assert_eq!((line, col), (2, 1));
    assert_eq!(
        message,
        "`size` must be the first command, found `camera` first"
    );
    let (line, col, message) = error_of("# only a comment\n");
    assert_eq!((line, col), (1, 1));
    assert!(message.starts_with("the file has no `size`"), "{message}");
    let (line, col, message) = error_of(&format!("{HEAD}size 2 2\n"));
    assert_eq!((line, col), (3, 1));
    assert!(message.contains("it is on line 1"), "{message}");
    let (line, col, _) = error_of("size 0 2\n");
    assert_eq!((line, col), (1, 6));
    let (line, col, _) = error_of("size 2.5 2\n");
    assert_eq!((line, col), (1, 6));
}

#[test]
fn error_no_camera_or_two() {
    let (line, _, message) = error_of("size 2 2\nsphere 0 0 0 1\n");
    assert_eq!(line, 3);
    assert!(message.starts_with("the file has no `camera`"), "{message}");
    let (line, col, message) = error_of(&format!("{HEAD}camera 0 0 5 0 0 0 0 1 0 45\n"));
    assert_eq!((line, col), (3, 1));
    assert!(message.contains("the first is on line 2"), "{message}");
    let (line, col, message) = error_of("size 2 2\ncamera 0 0 5 0 0 0 0 0 1 45\n");
    assert_eq!((line, col), (2, 1));
    assert!(message.contains("parallel"), "{message}");
}

#[test]
fn error_tri_names_an_undefined_vertex() {
    let (line, col, message) = error_of(&format!("{HEAD}vertex 0 0 0\nvertex 1 0 0\ntri 0 1 2\n"));
    assert_eq!((line, col), (5, 9));
    assert_eq!(
        message,
        "vertex 2 is not defined yet: `vertex`s 0 to 1 are defined so far"
    );
    let (line, col, message) = error_of(&format!("{HEAD}trinormal 0 0 0\n"));
    assert_eq!((line, col), (3, 11));
    assert!(
        message.contains("no `vertexnormal` is defined yet"),
        "{message}"
    );
    let (_, col, message) = error_of(&format!("{HEAD}vertex 0 0 0\ntri 0 0 -1\n"));
    assert_eq!(col, 9);
    assert!(message.contains("whole number"), "{message}");
}

#[test]
fn error_vertex_past_maxverts() {
    let (line, col, message) = error_of(&format!("{HEAD}maxverts 1\nvertex 0 0 0\nvertex 1 0 0\n"));
    assert_eq!((line, col), (5, 1));
    assert_eq!(
        message,
        "`vertex` number 1 is past `maxverts 1` (line 3): maxverts counts them all"
    );
}

#[test]
fn error_pop_on_an_empty_stack() {
    let (line, col, message) = error_of(&format!(
        "{HEAD}pushTransform\npopTransform\n  popTransform\n"
    ));
    assert_eq!((line, col), (5, 3));
    assert!(
        message.starts_with("`popTransform` with no `pushTransform`"),
        "{message}"
    );
}

#[test]
fn error_negative_radius_and_ranges() {
    let (line, col, message) = error_of(&format!("{HEAD}sphere 0 0 0 -1\n"));
    assert_eq!((line, col), (3, 14));
    assert_eq!(message, "the sphere's radius is negative (-1)");
    let (_, col, message) = error_of(&format!("{HEAD}sphere 2e4 0 0 1\n"));
    assert_eq!(col, 8);
    assert!(
        message.contains("must be between -10000 and 10000"),
        "{message}"
    );
    // A sphere scaled past the size range: 1e4 * 2 across its longest axis.
    let (line, col, message) = error_of(&format!("{HEAD}scale 1e4 1 1\nsphere 0 0 0 2\n"));
    assert_eq!((line, col), (4, 1));
    assert!(message.contains("longest axis is 20000"), "{message}");
    let (_, col, _) = error_of(&format!("{HEAD}scale 0 1 1\n"));
    assert_eq!(col, 7);
    let (_, col, _) = error_of(&format!("{HEAD}rotate 0 0 0 30\n"));
    assert_eq!(col, 8);
    let (_, col, message) = error_of(&format!("{HEAD}attenuation 0 0 0\n"));
    assert_eq!(col, 13);
    assert!(message.contains("divides by zero"), "{message}");
    let (_, col, _) = error_of(&format!("{HEAD}diffuse -1 0 0\n"));
    assert_eq!(col, 9);
    // maxdepth counts bounces: 63 of them make raystep's deepest tree.
    let (_, col, _) = error_of(&format!("{HEAD}maxdepth 64\n"));
    assert_eq!(col, 10);
    // A translated point light out of range is reported at its command.
    let (line, col, message) =
        error_of(&format!("{HEAD}translate 9000 0 0\npoint 9000 0 0 1 1 1\n"));
    assert_eq!((line, col), (4, 1));
    assert!(message.contains("world position (x) is 18000"), "{message}");
}

#[test]
fn error_composed_transform_and_stack_depth() {
    let many = "scale 1000 1000 1000\n".repeat(3);
    let (line, _, message) = error_of(&format!("{HEAD}{many}"));
    assert_eq!(line, 5);
    assert!(message.contains("composed transform"), "{message}");
    let deep = "pushTransform\n".repeat(MAX_TRANSFORM_DEPTH + 1);
    let (line, _, message) = error_of(&format!("{HEAD}{deep}"));
    assert_eq!(line, 3 + MAX_TRANSFORM_DEPTH);
    assert!(message.contains("nested"), "{message}");
}

#[test]
fn errors_print_file_line_col_with_the_line() {
    let error = read(&format!("{HEAD}sphere 0 0 0 -1\n")).unwrap_err();
    assert_eq!(
        error.to_string(),
        "t.test:3:14: the sphere's radius is negative (-1)\n  |\n3 | sphere 0 0 0 -1\n  |              ^^"
    );
}

#[test]
fn a_test_path_is_read_as_a_test_file_under_the_cse167_profile() {
    // By its extension, not as TOML: `HEAD` is no TOML at all.
    let scene = crate::scene::parse(Path::new("scenes/a.test"), HEAD).unwrap();
    assert_eq!(scene.settings.profile, crate::scene::Profile::Cse167);
    assert!(crate::scene::parse(Path::new("scenes/a.toml"), HEAD).is_err());
}

#[test]
fn error_trinormal_under_a_vanishing_transform() {
    // 120 scales by 0.001 leave a determinant of 1e-1080: zero in f64.
    let shrink = "scale 0.001 0.001 0.001\n".repeat(120);
    let text = format!("{HEAD}vertexnormal 0 0 0 0 0 1\n{shrink}trinormal 0 0 0\n");
    let (line, col, message) = error_of(&text);
    assert_eq!((line, col), (124, 1));
    assert!(message.contains("singular"), "{message}");
}
