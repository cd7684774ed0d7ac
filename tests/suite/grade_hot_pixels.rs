//! Issue 42 through `raystep grade`: an assignment may list `.test` scenes
//! and grade them by CSE 167's pass rule, at most N hot pixels an image
//! (`hot_pixels_allowed`), in place of the match rule: every pixel with a
//! channel more than the tolerance apart counts, none is excused.

use std::fs;
use std::path::Path;

use serde_json::Value;

use crate::support::renders::{render_to, supersampled};
use crate::support::{json, path, raystep, stderr};

/// cse167/directional.test (160 x 120), 10 points, with `rule` at the top.
fn assignment(rule: &str) -> String {
    format!(
        "{rule}\n[[scene]]\nfile = \"directional.test\"\nsubmit = \"directional.png\"\npoints = 10\n"
    )
}

fn scene_of<'a>(grades: &'a Value, name: &str) -> &'a Value {
    let students = grades["students"].as_array().unwrap();
    let student = students.iter().find(|s| s["student"] == name).unwrap();
    &student["scenes"][0]
}

#[test]
fn a_test_scene_graded_by_hot_pixels_counts_every_pixel_past_the_tolerance() {
    let dir = tempfile::tempdir().unwrap();
    let at = |relative: &str| dir.path().join(relative);
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/cse167");
    fs::copy(root.join("directional.test"), at("directional.test")).unwrap();
    for folder in ["submissions/specks", "submissions/aa"] {
        fs::create_dir_all(at(folder)).unwrap();
    }
    // `specks` hands in raystep's render with five pixels' red moved 10
    // steps: five hot pixels, none far off, 5 / 19,200 = 0.026% of the
    // pixels, which the match rule allows (0.1%). `aa` hands in raystep's
    // render averaged 2 x 2: its edges differ, which the match rule
    // excuses as anti-aliased and the hot-pixel rule counts.
    let ours = at("ours.png");
    render_to(&at("directional.test"), &ours, (160, 120), &[]);
    let mut specks = image::open(&ours).unwrap().into_rgb8();
    for x in [10, 40, 70, 100, 130] {
        let p = specks.get_pixel_mut(x, 60);
        p.0[0] = if p.0[0] < 128 {
            p.0[0] + 10
        } else {
            p.0[0] - 10
        };
    }
    specks
        .save(at("submissions/specks/directional.png"))
        .unwrap();
    let aa = supersampled(&at("directional.test"), dir.path(), (160, 120));
    let aa_hot = (aa
        .pixels()
        .zip(image::open(&ours).unwrap().into_rgb8().pixels()))
    .filter(|(a, b)| (0..3).any(|c| a.0[c].abs_diff(b.0[c]) > 3))
    .count();
    // The test can fail: averaging moves more than five pixels (225,
    // docs/TEACHERS.md).
    assert_eq!(aa_hot, 225);
    aa.save(at("submissions/aa/directional.png")).unwrap();
    let graded = |rule: &str, report: &str| -> Value {
        fs::write(at("assignment.toml"), assignment(rule)).unwrap();
        let output = raystep(&[
            "grade",
            path(&at("assignment.toml")),
            path(&at("submissions")),
            "-o",
            path(&at(report)),
        ]);
        assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
        json(&at(&format!("{report}/grades.json")))
    };
    // The match rule: both match, and grades.json says nothing of hot pixels.
    let plain = graded("", "plain");
    for name in ["specks", "aa"] {
        assert_eq!(scene_of(&plain, name)["points"], 10.0, "{name}");
    }
    assert_eq!(scene_of(&plain, "aa")["anti_aliased"], true);
    assert!(plain["scenes"][0].get("hot_pixels_allowed").is_none());
    assert!(
        scene_of(&plain, "specks")["compare"]["metrics"]
            .get("hot_pixels")
            .is_none()
    );
    // At most 4 hot pixels: both fail; the report counts them.
    let four = graded("hot_pixels_allowed = 4", "four");
    assert_eq!(four["scenes"][0]["hot_pixels_allowed"], 4);
    let specks = scene_of(&four, "specks");
    assert_eq!(specks["points"], 0.0);
    assert_eq!(specks["compare"]["metrics"]["hot_pixels"], 5);
    let text = specks["report_text"].as_str().unwrap();
    assert!(
        text.contains(
            "they differ: 5 pixels are hot, with a channel more than 3 steps of 255 apart (the assignment's hot-pixel rule allows at most 4)."
        ),
        "{text}"
    );
    let aa = scene_of(&four, "aa");
    assert_eq!(
        (aa["points"].as_f64(), aa["anti_aliased"].as_bool()),
        (Some(0.0), Some(false))
    );
    assert_eq!(aa["compare"]["metrics"]["hot_pixels"], aa_hot);
    // At most 5: specks passes; aa still fails.
    let five = graded("hot_pixels_allowed = 5", "five");
    assert_eq!(scene_of(&five, "specks")["points"], 10.0);
    assert_eq!(scene_of(&five, "aa")["points"], 0.0);
    // With the tolerance at 10 steps, the specks are not hot at all.
    let tolerant = graded("tolerance = 10\nhot_pixels_allowed = 0", "tolerant");
    assert_eq!(
        scene_of(&tolerant, "specks")["compare"]["metrics"]["hot_pixels"],
        0
    );
    assert_eq!(scene_of(&tolerant, "specks")["points"], 10.0);
}
