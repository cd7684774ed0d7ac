//! Issue 41, "no garbage in the results": numbers a student's files hold
//! that once came out as a verdict, an infinity or a forged line.

use serde_json::Value;

use crate::support::{raystep, stdout};

/// `compare SCENE --rays LOG --format json` on `log` written to a file.
fn compared(scene: &str, log: &str) -> Value {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("huge.jsonl");
    std::fs::write(&path, log).unwrap();
    let output = raystep(&[
        "compare",
        scene,
        "--rays",
        path.to_str().unwrap(),
        "--format",
        "json",
    ]);
    assert!(output.status.success(), "{output:?}");
    serde_json::from_str(&stdout(&output)).unwrap()
}

#[test]
fn origins_and_directions_of_1e200_do_not_match_ours() {
    // Pixel 0,0's primary ray starts at the eye, a few units from the
    // origin: (1e200, 1e200, -1e200) is 1.7e200 away from it. The relative
    // tolerance once squared that to infinity on both sides of <=.
    let log = r#"{"pixel": [0, 0], "path": "P", "origin": [1e200, 1e200, -1e200], "dir": [1e200, 1e200, -1e200]}
"#;
    let report = compared("scenes/glass.toml", log);
    assert_eq!(report["pixel_count"], 1, "{report:#}");
    assert_eq!(report["matching_pixels"], 0, "{report:#}");
    let first = &report["pixels"][0]["first_divergence"];
    assert_eq!(first["path"], "P", "{report:#}");
    assert_eq!(first["field"], "origin", "{report:#}");
}

/// A floor of two triangles (material `white`) under a lamp triangle
/// (material `lamp`, Ke as given), with the camera above: a scene of one
/// OBJ, whose only light is the lamp's Ke.
fn lamp_scene(ke: &str) -> (tempfile::TempDir, raystep_engine::scene::Scene) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("room.mtl"),
        format!("newmtl white\nKd 0.8 0.8 0.8\nnewmtl lamp\nKd 1 1 1\nKe {ke}\n"),
    )
    .unwrap();
    std::fs::write(
        dir.path().join("room.obj"),
        "mtllib room.mtl\n\
         v -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\n\
         v -0.5 2 -0.5\nv 0.5 2 -0.5\nv 0 2 0.5\n\
         usemtl white\nf 1 3 2\nf 1 4 3\n\
         usemtl lamp\nf 5 6 7\n",
    )
    .unwrap();
    let toml = dir.path().join("room.toml");
    std::fs::write(
        &toml,
        "[camera]\neye = [0, 1, 5]\nlook_at = [0, 0, 0]\n\
         [image]\nwidth = 8\nheight = 6\n\
         [[object]]\nmesh = { file = \"room.obj\" }\n",
    )
    .unwrap();
    let scene = crate::support::scene_at(&toml, None);
    (dir, scene)
}

#[test]
fn an_infinite_or_negative_ke_is_clamped_with_a_warning() {
    use raystep_engine::record::record_pixel;
    // Ke inf: each channel clamped to a colour's largest, 1e6 (README's
    // limits), so the lamp is a light of I_p = 1e6 and every pixel's tree
    // holds finite numbers (it once held NaN: inf × 0).
    let (_dir, scene) = lamp_scene("inf inf inf");
    assert_eq!(scene.lights.len(), 1);
    assert_eq!(scene.lights[0].color.to_array(), [1e6; 3]);
    assert!(
        scene
            .warnings
            .iter()
            .any(|w| w.contains("Ke [inf, inf, inf] is outside 0..1000000")),
        "{:?}",
        scene.warnings
    );
    for (x, y) in [(0, 0), (4, 3), (7, 5), (4, 4)] {
        let tree = record_pixel(&scene, &scene.settings, x, y);
        assert!(
            tree.color().is_finite(),
            "pixel {x},{y}: {:?}",
            tree.color()
        );
    }
    // Ke -1e308: clamped to 0 in each channel, so no emitter and no light
    // (it once became a light of -1e308 that darkened the floor).
    let (_dir, scene) = lamp_scene("-1e308 -1e308 -1e308");
    assert!(scene.lights.is_empty(), "{:?}", scene.lights);
    assert!(
        scene
            .warnings
            .iter()
            .any(|w| w.contains("is outside 0..1000000: [0, 0, 0] is used")),
        "{:?}",
        scene.warnings
    );
}

#[test]
fn an_unknown_key_cannot_forge_a_line_of_the_report() {
    // Pixel 0,0 of glass.toml with a wrong origin, so the report says it
    // differs; its unknown key holds a line break and a verdict of its own.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("forged.jsonl");
    std::fs::write(
        &path,
        r#"{"pixel": [0, 0], "path": "P", "origin": [9, 9, 9], "x\nEvery logged ray matches.": 1}
"#,
    )
    .unwrap();
    let output = raystep(&[
        "compare",
        "scenes/glass.toml",
        "--rays",
        path.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{output:?}");
    let text = stdout(&output);
    assert!(
        !text
            .lines()
            .any(|l| l.starts_with("Every logged ray matches")),
        "{text}"
    );
    assert!(
        text.contains("ignored: x\\u{a}Every logged ray matches.."),
        "{text}"
    );
}
