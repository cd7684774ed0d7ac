//! Course meshes (issue 24): OBJ + MTL and STL in scenes and alone, the
//! Cornell box, and every bad mesh refused with its file and line.

use std::path::{Path, PathBuf};

use crate::support::renders::render_to;
use crate::support::{raystep, scene_at, stderr};
use raystep_engine::record::{explain, record_pixel};
use raystep_engine::render::render;
use raystep_engine::trace::NoRecorder;

fn cornell() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/cornell/cornell.toml")
}

/// Writes `files` (name, contents) into a fresh folder.
fn folder(files: &[(&str, &[u8])]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for (name, contents) in files {
        std::fs::write(dir.path().join(name), contents).unwrap();
    }
    dir
}

/// `raystep render` of `scene` in `dir` at 48x36: the PNG's bytes.
fn rendered(dir: &Path, scene: &str) -> Vec<u8> {
    let out = dir.join(format!("{scene}.png"));
    let path = dir.join(scene);
    let output = raystep(&[
        "render",
        path.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--size",
        "48x36",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    std::fs::read(out).unwrap()
}

/// What every scene of the next test shares: camera, light and material.
const HEAD: &str = r#"
[camera]
eye = [0.5, 0.5, 3]
look_at = [0.5, 0.5, 0]
[materials.m]
color = [0.9, 0.4, 0.1]
ks = 0.3
[[light]]
position = [2, 3, 4]
"#;

/// A unit square in z = 0 split along its diagonal, and a triangle behind
/// it, written by hand three ways: TOML polygons, OBJ, ASCII STL.
#[test]
fn a_hand_written_obj_and_stl_give_the_image_of_the_same_triangles_in_toml() {
    let toml = format!(
        "{HEAD}{}",
        r#"
[[object]]
material = "m"
polygon = { vertices = [[0, 0, 0], [1, 0, 0], [1, 1, 0]] }
[[object]]
material = "m"
polygon = { vertices = [[0, 0, 0], [1, 1, 0], [0, 1, 0]] }
[[object]]
material = "m"
polygon = { vertices = [[-1, -1, -1], [2, -1, -1], [0.5, 2, -1]] }
"#
    );
    let obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv -1 -1 -1\nv 2 -1 -1\nv 0.5 2 -1\n\
               g square\nf 1 2 3 4\ng back\nf 5 6 7\n";
    let stl = "solid s\n\
        facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nendloop\nendfacet\n\
        facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\n\
        facet normal 0 0 1\nouter loop\nvertex -1 -1 -1\nvertex 2 -1 -1\nvertex 0.5 2 -1\nendloop\nendfacet\n\
        endsolid s\n";
    let with_mesh = |file: &str| {
        format!("{HEAD}[[object]]\nmaterial = \"m\"\nmesh = {{ file = \"{file}\" }}\n")
    };
    let empty = HEAD.to_string();
    let dir = folder(&[
        ("t.toml", toml.as_bytes()),
        ("o.toml", with_mesh("s.obj").as_bytes()),
        ("s.toml", with_mesh("s.stl").as_bytes()),
        ("e.toml", empty.as_bytes()),
        ("s.obj", obj.as_bytes()),
        ("s.stl", stl.as_bytes()),
    ]);
    let reference = rendered(dir.path(), "t.toml");
    assert_ne!(
        reference,
        rendered(dir.path(), "e.toml"),
        "the triangles show"
    );
    assert_eq!(reference, rendered(dir.path(), "o.toml"), "OBJ");
    assert_eq!(reference, rendered(dir.path(), "s.toml"), "STL");
}

#[test]
fn mesh_triangles_are_named_by_mesh_group_index_and_material() {
    let scene = scene_at(&cornell(), None);
    let names: Vec<String> = scene.objects.iter().map(|o| o.name.to_string()).collect();
    // cornell.obj: 6 quads of the room and light, 5 per block, 2 triangles each.
    assert_eq!(names.len(), (6 + 5 + 5) * 2 + 2);
    assert!(
        names
            .iter()
            .any(|n| n == "cornell tallBox triangle 7 (material white)")
    );
    assert!(
        names
            .iter()
            .any(|n| n == "cornell light triangle 1 (material light)")
    );
    // The light panel's Ke is the scene's one light.
    assert_eq!(scene.lights.len(), 1);
}

/// The Cornell box at 32 x 32, one line of hex colours per row: the red
/// left wall, the green right wall, the dark box fronts (lit by ambient
/// only: the light is above them), the balls.
#[test]
fn cornell_box_pixels() {
    let scene = scene_at(&cornell(), Some((32, 32)));
    let (image, _) = render::<NoRecorder>(&scene, &scene.settings, &|| {});
    let mut text = String::new();
    for row in image.rows() {
        let line: Vec<String> = row
            .map(|p| format!("{:02x}{:02x}{:02x}", p[0], p[1], p[2]))
            .collect();
        text.push_str(&line.join(" "));
        text.push('\n');
    }
    snapshot!("cornell_pixels", text);
}

/// Two pixels of the 256 x 256 box explained: the back wall in the tall
/// block's shadow, and the red wall seen in the mirror ball.
#[test]
fn cornell_box_shadow_and_mirror_explained() {
    let scene = scene_at(&cornell(), None);
    for (x, y, name) in [
        (63, 172, "cornell_63_172_shadow"),
        (62, 196, "cornell_62_196_mirror"),
        // Both in one tree: the mirror ball, whose reflected ray finds the
        // red wall in the tall block's shadow. By hand: ambient 0.2 · 1 ·
        // 0.9 = 0.18; the reflected ray weighs k_s = 0.9; unblocked, the
        // wall's diffuse would add 0.9 · Kd · N·L = 0.9 · 0.63 · 0.5691 =
        // 0.323 of red to the pixel.
        (62, 182, "cornell_62_182_mirror_and_shadow"),
    ] {
        let tree = record_pixel(&scene, &scene.settings, x, y);
        snapshot!(name, explain(&tree));
    }
}

/// A bad mesh: exit 1, one `error:` line naming the file (and its line where
/// the format has lines), no panic, no image written.
fn refused(files: &[(&str, &[u8])], scene: &str, expected: &str) {
    let dir = folder(files);
    let out = dir.path().join("out.png");
    let output = raystep(&[
        "render",
        dir.path().join(scene).to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    let err = stderr(&output);
    assert_eq!(output.status.code(), Some(1), "{err}");
    assert!(err.starts_with("error: "), "{err}");
    assert!(err.contains(expected), "expected {expected:?} in {err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(!out.exists());
}

const TRIANGLE: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

#[test]
fn bad_obj_faces_and_numbers_are_refused_at_their_line() {
    let cases: &[(&str, &str)] = &[
        (
            "f 1 2 4\n",
            "m.obj:4:7: face vertex index 4 is out of range: 3 `v`",
        ),
        (
            "f 1 0 2\n",
            "m.obj:4:5: face vertex index 0: OBJ indices start at 1",
        ),
        (
            "f -4 1 2\n",
            "m.obj:4:3: face vertex index -4 is out of range",
        ),
        (
            "f 1//2 2//2 3//2\n",
            "m.obj:4:3: face normal index 2 is out of range: 0 `vn`",
        ),
        (
            "f 1 2\n",
            "m.obj:4:1: a face needs at least 3 vertices, got 2",
        ),
        ("v nan 0 0\n", "m.obj:4:3: numbers must be finite, got nan"),
        ("v 0 inf 0\n", "m.obj:4:5: numbers must be finite, got inf"),
        (
            "v 1e5 0 0\n",
            "m.obj:4:3: vertex coordinate 1e5 must be between -10000 and 10000",
        ),
        ("v 1 x 0\n", "m.obj:4:5: `x` is not a number"),
    ];
    for (line, expected) in cases {
        let obj = format!("{TRIANGLE}{line}");
        refused(&[("m.obj", obj.as_bytes())], "m.obj", expected);
    }
}

#[test]
fn bad_stl_files_are_refused() {
    let mut truncated = vec![0u8; 84 + 50];
    truncated[80] = 2; // two triangles promised, one given
    refused(
        &[("t.stl", &truncated)],
        "t.stl",
        "t.stl: truncated binary STL: 2 triangles need 184 bytes, the file has 134",
    );
    refused(
        &[("g.stl", b"solid g\nfacet garbage\n")],
        "g.stl",
        "g.stl:2:1: expected `facet normal x y z` or `endsolid`, got `facet garbage`",
    );
    let mut nan = vec![0u8; 84 + 50];
    nan[80] = 1;
    nan[96..100].copy_from_slice(&f32::NAN.to_le_bytes()); // vertex 0's x
    refused(
        &[("n.stl", &nan)],
        "n.stl",
        "n.stl: triangle 0: numbers must be finite",
    );
}

#[test]
fn a_missing_mesh_a_scene_named_as_its_own_mesh_and_a_mesh_placed_out_of_bounds_are_refused() {
    let scene = |mesh: &str| format!("{HEAD}[[object]]\nmesh = {{ {mesh} }}\n");
    refused(
        &[("s.toml", scene(r#"file = "gone.obj""#).as_bytes())],
        "s.toml",
        "cannot read mesh file",
    );
    // A scene that names itself as its mesh: read only as a mesh, and a
    // .toml is none.
    refused(
        &[("s.toml", scene(r#"file = "s.toml""#).as_bytes())],
        "s.toml",
        "s.toml:11:17: mesh file `s.toml` must end in .obj or .stl",
    );
    refused(
        &[
            (
                "s.toml",
                scene(r#"file = "m.obj", scale = 5000, translate = [9000, 0, 0]"#).as_bytes(),
            ),
            ("m.obj", format!("{TRIANGLE}f 1 2 3\n").as_bytes()),
        ],
        "s.toml",
        "lies outside the scene's bounds once placed",
    );
}

#[test]
fn a_missing_mtl_and_degenerate_triangles_are_warned_about_once_and_listed_in_stats() {
    // Two faces share the missing material; one face is a line.
    let obj = "mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\n\
               usemtl a\nf 1 2 3\nf 1 3 2\nf 1 2 4\n";
    let dir = folder(&[("m.obj", obj.as_bytes())]);
    let out = dir.path().join("m.png");
    let output = raystep(&[
        "render",
        dir.path().join("m.obj").to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--stats",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let err = stderr(&output);
    assert_eq!(err.matches("warning: ").count(), 2, "{err}");
    assert!(err.contains("gone.mtl") && err.contains("the default material is used"));
    assert!(err.contains("1 degenerate triangle(s) skipped"), "{err}");
    let stats: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(stats["warnings"].as_array().unwrap().len(), 2);
    assert_eq!(stats["objects"], 2);
}

#[test]
fn mtl_warnings_come_once_per_material() {
    // Three faces of one material with a coloured Ks and a texture.
    let obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n\
               usemtl shiny\nf 1 2 3\nf 2 4 3\nf 1 3 2\n";
    let mtl = "newmtl shiny\nKd 1 0 0\nKs 0.2 0.4 0.6\nmap_Kd wood.png\nillum 3\n";
    let dir = folder(&[("m.obj", obj.as_bytes()), ("m.mtl", mtl.as_bytes())]);
    let scene = raystep_engine::scene::load(&dir.path().join("m.obj")).unwrap();
    let warnings = scene.warnings.join("\n");
    assert_eq!(scene.warnings.len(), 2, "{warnings}");
    // k_s is the mean of Ks: (0.2 + 0.4 + 0.6) / 3 = 0.4.
    assert!(
        warnings.contains("Ks [0.2, 0.4, 0.6] is coloured"),
        "{warnings}"
    );
    assert!(warnings.contains("their mean 0.4"), "{warnings}");
    assert!(warnings.contains("map_Kd ignored"), "{warnings}");
}

/// `reflect = false` keeps the highlight and drops the mirror ray: a ball
/// in front of a red wall, lit from the eye, seen at its centre. With the
/// mirror, the reflected ray goes straight back to the eye (nothing there:
/// background black, adds 0), so compare the trees, not the colours.
#[test]
fn reflect_false_keeps_the_highlight_and_casts_no_mirror_ray() {
    let scene_with = |reflect: bool| {
        crate::support::scene(&format!(
            r#"
[camera]
eye = [0, 0, 5]
look_at = [0, 0, 0]
[materials.shiny]
color = [0.2, 0.2, 0.2]
ks = 0.5
reflect = {reflect}
[[light]]
position = [0, 0, 5]
[[object]]
material = "shiny"
sphere = {{ center = [0, 0, 0], radius = 1 }}
"#
        ))
    };
    let rays = |scene: &raystep_engine::scene::Scene| {
        let tree = crate::support::record(scene, [0.0, 0.0, 5.0], [0.0, 0.0, -1.0]);
        raystep_engine::record::explain(&tree)
    };
    let mirror = rays(&scene_with(true));
    let matte_mirror = rays(&scene_with(false));
    assert!(mirror.contains("Reflected ray (weight 0.5)"), "{mirror}");
    assert!(!matte_mirror.contains("Reflected ray"), "{matte_mirror}");
    // The highlight stays: N·H = 1 at the centre, so specular = k_s = 0.5,
    // plus diffuse 0.2: the pixel is 0.7 grey either way.
    assert!(
        matte_mirror.contains("(0.700, 0.700, 0.700)"),
        "{matte_mirror}"
    );
}

/// The same unnamed mesh placed twice: the second copy's triangles are told
/// apart by the object's place in the list (`mesh 1`), as unnamed spheres
/// are ("sphere 3"); the first keeps the file's own names.
#[test]
fn the_same_mesh_placed_twice_without_a_name_gets_names_of_its_own() {
    let obj = format!("{TRIANGLE}f 1 2 3\n");
    let scene = format!(
        "{HEAD}[[object]]\nmesh = {{ file = \"m.obj\" }}\n\
         [[object]]\nmesh = {{ file = \"m.obj\", translate = [0, 0, -1] }}\n"
    );
    let dir = folder(&[("m.obj", obj.as_bytes()), ("s.toml", scene.as_bytes())]);
    let scene = raystep_engine::scene::load(&dir.path().join("s.toml")).unwrap();
    let names: Vec<String> = scene.objects.iter().map(|o| o.name.to_string()).collect();
    assert_eq!(names, ["m triangle 0", "mesh 1 m triangle 0"]);
}

/// `mtllib` may name any path: whatever it names is read only as MTL, and
/// a file that is no MTL gives no material, so `usemtl` falls back to the
/// default with a warning that says so. Nothing is written but the image,
/// and every file is left as it was.
#[test]
fn an_mtllib_pointing_anywhere_is_read_only_as_mtl() {
    let dir = folder(&[
        ("scene.toml", b"[camera]\neye = [0, 0, 3]\n"),
        ("notes.txt", b"newmtl x\nKd 1 0 0\n"),
    ]);
    std::fs::create_dir(dir.path().join("sub")).unwrap();
    let before = |name: &str| std::fs::read(dir.path().join(name)).unwrap();
    let (scene_bytes, notes_bytes) = (before("scene.toml"), before("notes.txt"));
    for (library, expected) in [
        (
            "../scene.toml",
            "`usemtl x` names no material of the file's MTL",
        ),
        (
            "/etc/passwd",
            "`usemtl x` names no material of the file's MTL",
        ),
        (
            ".",
            "sub/.: it is a directory, not a regular file: the default material is used",
        ),
        (
            "/dev/zero",
            "/dev/zero: it is a character device, not a regular file",
        ),
    ] {
        let obj = format!("mtllib {library}\n{TRIANGLE}usemtl x\nf 1 2 3\n");
        std::fs::write(dir.path().join("sub/m.obj"), &obj).unwrap();
        let out = dir.path().join("out.png");
        let output = raystep(&[
            "render",
            dir.path().join("sub/m.obj").to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--size",
            "8x8",
        ]);
        let err = stderr(&output);
        assert!(output.status.success(), "{library}: {err}");
        assert_eq!(err.matches("warning: ").count(), 1, "{library}: {err}");
        assert!(err.contains(expected), "{library}: {err}");
        std::fs::remove_file(&out).unwrap();
    }
    // The MTL named in the folder above is read and used: red.
    let obj = format!("mtllib ../notes.txt\n{TRIANGLE}usemtl x\nf 1 2 3\n");
    std::fs::write(dir.path().join("sub/m.obj"), &obj).unwrap();
    let scene = raystep_engine::scene::load(&dir.path().join("sub/m.obj")).unwrap();
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    assert_eq!(scene.objects[0].name, "m triangle 0 (material x)");
    assert_eq!(before("scene.toml"), scene_bytes);
    assert_eq!(before("notes.txt"), notes_bytes);
    let mut left: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    left.sort();
    assert_eq!(left, ["notes.txt", "scene.toml", "sub"]);
}

/// `compare` takes a mesh as its scene: its own render matches, and a
/// render without the ambient term (the shadow on the floor goes black) is
/// named for it.
#[test]
fn compare_takes_a_mesh_as_its_scene() {
    // A floor quad and a small triangle above it, lit from straight above:
    // the triangle's shadow falls on the floor.
    let obj = "v -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\n\
               v -0.5 1 -0.5\nv 0.5 1 -0.5\nv 0 1 0.5\n\
               g floor\nf 1 4 3 2\ng leaf\nf 5 7 6\n";
    let dir = folder(&[("m.obj", obj.as_bytes())]);
    let scene = dir.path().join("m.obj");
    let image = |name: &str, mistake: &[&str]| {
        let out = dir.path().join(name);
        render_to(&scene, &out, (64, 48), mistake);
        out
    };
    let compare = |image: &Path| {
        let output = raystep(&[
            "compare",
            scene.to_str().unwrap(),
            image.to_str().unwrap(),
            "--format",
            "json",
        ]);
        assert!(output.status.success(), "{}", stderr(&output));
        serde_json::from_slice::<serde_json::Value>(&output.stdout).unwrap()
    };
    let same = compare(&image("same.png", &[]));
    assert_eq!(same["matches"], true, "{same}");
    let dark = compare(&image("dark.png", &["--mistake", "no-ambient"]));
    assert_eq!(dark["matches"], false, "{dark}");
    assert_eq!(dark["mistakes"][0]["name"], "no-ambient", "{dark}");
}

/// A UV sphere of radius 1 about the origin, `rings` x `segments` quads
/// (triangles at the poles), with each vertex's normal its position (`vn`),
/// wound counter-clockwise seen from outside.
fn smooth_ball_obj(rings: usize, segments: usize) -> String {
    use std::f64::consts::PI;
    let mut obj = String::new();
    let vertex = |ring: usize, segment: usize| -> [f64; 3] {
        let (theta, phi) = (
            PI * ring as f64 / rings as f64,
            2.0 * PI * segment as f64 / segments as f64,
        );
        [
            theta.sin() * phi.cos(),
            theta.cos(),
            -theta.sin() * phi.sin(),
        ]
    };
    for ring in 0..=rings {
        for segment in 0..segments {
            let [x, y, z] = vertex(ring, segment);
            obj += &format!("v {x} {y} {z}\nvn {x} {y} {z}\n");
        }
    }
    let index = |ring: usize, segment: usize| ring * segments + segment % segments + 1;
    for ring in 0..rings {
        for segment in 0..segments {
            let (a, b) = (index(ring, segment), index(ring, segment + 1));
            let (c, d) = (index(ring + 1, segment + 1), index(ring + 1, segment));
            if ring > 0 {
                obj += &format!("f {a}//{a} {d}//{d} {b}//{b}\n");
            }
            if ring + 1 < rings {
                obj += &format!("f {b}//{b} {d}//{d} {c}//{c}\n");
            }
        }
    }
    obj
}

/// `smooth_ball_obj(6, 8)` seen from (0, 0, 4), 40°, at `size` x `size`,
/// lit from (−4, 4, 4), its material `material` (TOML keys, a line each).
fn smooth_ball_scene(size: u32, material: &str) -> raystep_engine::scene::Scene {
    let dir = folder(&[("ball.obj", smooth_ball_obj(6, 8).as_bytes())]);
    let toml = dir.path().join("ball.toml");
    std::fs::write(
        &toml,
        format!(
            "[camera]\neye = [0, 0, 4]\nlook_at = [0, 0, 0]\nfov = 40\n\
             [image]\nwidth = {size}\nheight = {size}\n\
             [materials.m]\n{material}\n\
             [[light]]\nposition = [-4, 4, 4]\n\
             [[object]]\nmaterial = \"m\"\nmesh = {{ file = \"ball.obj\" }}\n"
        ),
    )
    .unwrap();
    scene_at(&toml, None)
}

/// Issue 41: a smooth ball's rim. Where a ray meets a triangle's front but
/// the blended normal N_s faces away from it (N_s·d > 0, only near the
/// silhouette), the side is the triangle's plane's: entering, "front", and
/// N = N_s. It once read as the back side (N = −N_s, the rim shaded as if
/// from inside; made glass, total internal reflection on the first hit).
#[test]
fn a_smooth_balls_rim_is_its_front_side() {
    let scene = smooth_ball_scene(
        128,
        "color = [0.9, 0.9, 0.9]\nkd = 0.2\nks = 0.1\nkt = 0.8\nior = 1.5",
    );
    let mut rim = 0;
    for y in 0..128 {
        for x in 0..128 {
            let tree = record_pixel(&scene, &scene.settings, x, y);
            let root = tree.root();
            let Some(hit) = root.hit.as_ref() else {
                continue;
            };
            // The eye is outside the ball: every first hit is on its front.
            assert!(hit.entering, "pixel {x},{y}: {hit:?}");
            if hit.geometric_normal.dot(root.direction) > 0.0 {
                rim += 1;
                assert_eq!(hit.normal, hit.geometric_normal, "pixel {x},{y}");
                assert!(
                    explain(&tree).contains("on its front side"),
                    "pixel {x},{y}: {}",
                    explain(&tree)
                );
            }
        }
    }
    // The case the rule is for occurs (6 x 8 facets: a rim of pixels).
    assert!(rim > 0, "no pixel meets a blended normal facing away");
}

/// Issue 41: a triangle's number runs per name, however often the OBJ
/// starts the object again (tobj starts a new model at each `usemtl`), and
/// a mesh file alone is not named twice.
#[test]
fn mesh_triangles_are_numbered_once_per_name_and_named_once() {
    let dir = folder(&[
        (
            "m.mtl",
            b"newmtl a\nKd 1 0 0\nnewmtl b\nKd 0 1 0\nnewmtl c\nKd 0 0 1\n",
        ),
        (
            "crate.obj",
            b"mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\no crate\n\
              usemtl a\nf 1 2 3\nf 1 3 4\nusemtl b\nf 1 2 5\nf 2 3 5\n\
              usemtl c\nf 3 4 5\nf 4 1 5\n",
        ),
        (
            "pyramid.stl",
            b"solid pyramid\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n\
              vertex 0 1 0\nendloop\nendfacet\nendsolid pyramid\n",
        ),
    ]);
    let names = |file: &str| -> Vec<String> {
        let scene = scene_at(&dir.path().join(file), None);
        scene.objects.iter().map(|o| o.name.to_string()).collect()
    };
    // Six triangles of one object "crate", numbered 0 to 5 in file order
    // whatever their material (they ran 0, 1 under each of a, b and c).
    assert_eq!(
        names("crate.obj"),
        [
            "crate triangle 0 (material a)",
            "crate triangle 1 (material a)",
            "crate triangle 2 (material b)",
            "crate triangle 3 (material b)",
            "crate triangle 4 (material c)",
            "crate triangle 5 (material c)",
        ]
    );
    // A TOML object named "pyramid" whose STL's solid is "pyramid": one
    // "pyramid", not "pyramid pyramid triangle 0".
    std::fs::write(
        dir.path().join("p.toml"),
        "[camera]\neye = [0.3, 0.3, 3]\nlook_at = [0.3, 0.3, 0]\n\
         [[object]]\nname = \"pyramid\"\nmesh = { file = \"pyramid.stl\" }\n",
    )
    .unwrap();
    assert_eq!(names("p.toml"), ["pyramid triangle 0"]);
}

/// The vertices of object `index` of `scene`: a mesh triangle's three.
fn corners(scene: &raystep_engine::scene::Scene, index: usize) -> Vec<[f64; 3]> {
    use raystep_model::shapes::Shape;
    match &scene.objects[index].shape {
        Shape::Polygon(p) => p.vertices.iter().map(|v| v.to_array()).collect(),
        Shape::Patch(p) => p.polygon.vertices.iter().map(|v| v.to_array()).collect(),
        other => panic!("object {index} is not a triangle: {other:?}"),
    }
}

/// Issue 41: a ray that hits a smooth ball's triangle near an edge crosses
/// the planes of the triangles around it just before (the ball is convex:
/// the ray enters it through its last plane), inside their bounding boxes
/// and outside them: every such neighbour was listed, and explained, as a
/// near miss. A triangle of the same mesh that shares a corner with the
/// one hit is the same surface, not something the ray went past: none is
/// listed. A ray that misses the ball still lists the triangles it passed.
#[test]
fn a_mesh_hits_neighbours_are_not_near_misses() {
    let scene = smooth_ball_scene(64, "color = [0.9, 0.4, 0.1]");
    let (mut hits, mut passed_by) = (0, 0);
    for y in 0..64 {
        for x in 0..64 {
            let tree = record_pixel(&scene, &scene.settings, x, y);
            let root = tree.root();
            let Some(hit) = root.hit.as_ref() else {
                passed_by += root.near_misses.len();
                continue;
            };
            hits += 1;
            let hit_corners = corners(&scene, hit.object_index);
            for near in &root.near_misses {
                let shared = corners(&scene, near.object_index)
                    .iter()
                    .any(|c| hit_corners.contains(c));
                assert!(
                    !shared,
                    "pixel {x},{y}: {} shares a corner with {}:\n{}",
                    near.object,
                    hit.object,
                    explain(&tree)
                );
            }
        }
    }
    assert!(hits > 0);
    // Rays that miss the ball near its rim pass by its triangles' planes.
    assert!(passed_by > 0, "no ray passes the ball by");
}

/// The same for NFF's teapot, whose `pp` patches name no mesh: a patch
/// sharing a corner, and the normal there, with the patch hit is the same
/// smooth surface, not a near miss.
#[test]
fn a_patchs_smooth_neighbours_are_not_near_misses() {
    use raystep_model::shapes::Shape;
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/spd/teapot-small.nff");
    let scene = scene_at(&path, Some((128, 128)));
    let smooth_corners = |index: usize| -> Vec<([f64; 3], [f64; 3])> {
        match &scene.objects[index].shape {
            Shape::Patch(p) => p
                .polygon
                .vertices
                .iter()
                .zip(&p.normals)
                .map(|(v, n)| (v.to_array(), n.to_array()))
                .collect(),
            _ => Vec::new(),
        }
    };
    let mut patch_hits = 0;
    for y in 0..128 {
        for x in 0..128 {
            let tree = record_pixel(&scene, &scene.settings, x, y);
            let root = tree.root();
            let Some(hit) = root.hit.as_ref() else {
                continue;
            };
            let hit_corners = smooth_corners(hit.object_index);
            if hit_corners.is_empty() {
                continue;
            }
            patch_hits += 1;
            for near in &root.near_misses {
                assert!(
                    !smooth_corners(near.object_index)
                        .iter()
                        .any(|c| hit_corners.contains(c)),
                    "pixel {x},{y}: {} shares a corner and its normal with {}",
                    near.object,
                    hit.object
                );
            }
        }
    }
    assert!(patch_hits > 0, "no pixel hits the teapot");
}

/// Whether a pixel's primary ray hits something one light reaches: facing
/// it and not blocked (MODEL §4).
fn lit(tree: &raystep_engine::record::RayTree) -> bool {
    tree.root()
        .lights
        .iter()
        .any(|l| !l.faces_away && l.shadow.as_ref().is_none_or(|s| s.s > 0.0))
}

/// Issue 41: `raystep render cornell.obj` alone showed a dark cube: the
/// camera outside the box saw the walls' outsides, which the box's own
/// light (the MTL's Ke, under the ceiling) lights from behind. The box is a
/// room: its faces are wound to face inward (the floor's first corners
/// (552.8, 0, 0), (0, 0, 0), (0, 0, 559.2) give (v1 - v0) x (v2 - v0) =
/// (-552.8, 0, 0) x (-552.8, 0, 559.2) = (0, +309127, 0): up, into the
/// room), so it is looked at from inside (SCENES.md "A mesh file alone").
#[test]
fn the_cornell_obj_alone_is_seen_from_inside_and_lit() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/cornell/cornell.obj");
    let scene = scene_at(&path, None);
    // The box: x 0 to 556 (ceiling and left wall), y 0 to 548.8, z 0 to
    // 559.2; centre (278, 274.4, 279.6). No triangle lies in the tenth of
    // the box nearest z = 0 (the nearest centroid is the short block's
    // front, z >= 65): the open side is -z. The camera stands a hundredth
    // of the depth in, z = 5.592, and looks at the back wall's centre.
    let camera = scene.camera;
    let close = |a: glam::DVec3, b: [f64; 3]| (a - glam::DVec3::from(b)).length() < 1e-9;
    assert!(close(camera.eye, [278.0, 274.4, 5.592]), "{camera:?}");
    assert!(close(camera.look_at, [278.0, 274.4, 559.2]), "{camera:?}");
    assert!(close(camera.up, [0.0, 1.0, 0.0]), "{camera:?}");
    // The back wall half as large again just fills the image: its half
    // height 274.4 (its half width 278 is 208.5 at 320:240) at 553.608:
    // fov = 2 atan(1.5 x 274.4 / 553.608) = 2 atan(0.743487) = 73.2613°.
    assert!((camera.fov - 73.2613).abs() < 1e-3, "{camera:?}");
    // Inside the room, every ray heads into it (+z) and meets a wall: no
    // background. Most of what it sees the light reaches (only the blocks'
    // fronts, facing the camera, and their shadows do not); before, none.
    let (w, h) = (64, 48);
    let scene = scene.with_size(w, h).unwrap();
    let mut hits = 0;
    let mut lit_pixels = 0;
    for y in 0..h {
        for x in 0..w {
            let tree = record_pixel(&scene, &scene.settings, x, y);
            hits += usize::from(tree.root().hit.is_some());
            lit_pixels += usize::from(lit(&tree));
        }
    }
    assert_eq!(hits, (w * h) as usize);
    assert!(
        lit_pixels * 2 > (w * h) as usize,
        "{lit_pixels} of {}",
        w * h
    );
}

/// The unit cube's six faces as an OBJ, wound counter-clockwise seen from
/// outside (`outward`) or from inside.
fn cube_obj(outward: bool) -> String {
    let mut obj = String::new();
    for z in 0..2 {
        for y in 0..2 {
            for x in 0..2 {
                obj += &format!("v {x} {y} {z}\n");
            }
        }
    }
    // Vertex (x, y, z) is number 1 + x + 2y + 4z; each face counter-clockwise
    // seen from outside.
    let faces = [
        [1, 3, 4, 2], // z = 0, seen from -z
        [5, 6, 8, 7], // z = 1, seen from +z
        [1, 2, 6, 5], // y = 0, seen from -y
        [3, 7, 8, 4], // y = 1, seen from +y
        [1, 5, 7, 3], // x = 0, seen from -x
        [2, 4, 8, 6], // x = 1, seen from +x
    ];
    for mut face in faces {
        if !outward {
            face.reverse();
        }
        obj += &format!("f {} {} {} {}\n", face[0], face[1], face[2], face[3]);
    }
    obj
}

/// A closed cube wound outward is an object, framed from outside as
/// before; wound inward it is a room, seen from inside. All its sides are
/// walls alike, so the first side in the order +z, -z, +x, -x, +y, -y is
/// taken as the open one: +z.
#[test]
fn a_mesh_alone_wound_inward_is_a_room_and_outward_an_object() {
    let dir = folder(&[
        ("out.obj", cube_obj(true).as_bytes()),
        ("in.obj", cube_obj(false).as_bytes()),
    ]);
    let close = |a: glam::DVec3, b: glam::DVec3| (a - b).length() < 1e-9;
    let object = scene_at(&dir.path().join("out.obj"), None).camera;
    // Centre (0.5, 0.5, 0.5), half diagonal sqrt(3)/2, three of them from
    // the centre along (0.4, 0.3, 1) normalised; fov 45.
    let centre = glam::DVec3::splat(0.5);
    let eye = centre + glam::DVec3::new(0.4, 0.3, 1.0).normalize() * (3.0 * 3f64.sqrt() / 2.0);
    assert!(close(object.eye, eye), "{object:?}");
    assert!(close(object.look_at, centre), "{object:?}");
    assert_eq!(object.fov, 45.0);
    let room = scene_at(&dir.path().join("in.obj"), None).camera;
    // A hundredth of the depth in from z = 1, looking at z = 0's centre;
    // fov = 2 atan(1.5 x 0.5 / 0.99) = 2 atan(0.757576) = 74.29°.
    assert!(
        close(room.eye, glam::DVec3::new(0.5, 0.5, 0.99)),
        "{room:?}"
    );
    assert!(
        close(room.look_at, glam::DVec3::new(0.5, 0.5, 0.0)),
        "{room:?}"
    );
    let fov = 2.0 * (0.75f64 / 0.99).atan().to_degrees();
    assert!((room.fov - fov).abs() < 1e-9, "{room:?}");
    assert!((fov - 74.29).abs() < 0.01, "{fov}");
}
