//! Issue 40: differences smaller than a pixel are no mistake. A correct
//! render whose eye moved by 1e-5 (a silhouette pixel takes its
//! neighbour's colour) and a render anti-aliased 2 x 2 match; a whole
//! image moved half a pixel (`pixel-corner`) and wrapped bytes do not.

use std::path::Path;

use serde_json::Value;

use crate::support::renders::{eye_moved, largest_gap, render_to, supersampled};
use crate::support::{TEACHING_SCENES, raystep, stderr, stdout};

fn path(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// A scene's own size, read from its `[image]`.
fn own_size(scene: &str) -> (u32, u32) {
    let scene = raystep_engine::scene::load(Path::new(scene)).unwrap();
    (scene.width, scene.height)
}

/// `compare --format json` of `image` against `scene` (at the image's size).
fn compared(scene: &str, image: &Path) -> Value {
    let output = raystep(&["compare", scene, path(image), "--format", "json"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    serde_json::from_str(&stdout(&output)).unwrap()
}

#[test]
fn a_render_with_the_eye_moved_by_1e_5_matches_on_every_teaching_scene() {
    // Another correct tracer's eye sits a hair away (float32, another order
    // of operations). Moved along x and along z, at each scene's own size,
    // and at 320 x 240 along x, y and z for glass.toml: where the images
    // differ, a few silhouette pixels took a neighbour's colour. Before
    // issue 40, one such pixel more than 32 steps off made them differ ("1
    // pixel differs by more than 32 (a match allows none)": prism.toml
    // moved along x, glass.toml at 320 x 240). Along y at seven-rays.toml's
    // own size (161 x 121) the level centre row is the horizon of its
    // endless floor: an eye 1e-5 higher turns the whole row from sky to
    // floor (161 pixels, 0.83%, 41 steps apart in blue), which differed
    // until pixels on an edge through their centres were excused.
    let dir = tempfile::tempdir().unwrap();
    let mut cases: Vec<(&str, usize, (u32, u32))> = Vec::new();
    for scene in TEACHING_SCENES {
        for axis in 0..3 {
            cases.push((scene, axis, own_size(scene)));
        }
    }
    for axis in 0..3 {
        cases.push(("scenes/glass.toml", axis, (320, 240)));
    }
    let (mut differing, mut far_off, mut horizon) = (0, 0, false);
    for (scene, axis, size) in cases {
        let ours = dir.path().join("ours.png");
        render_to(Path::new(scene), &ours, size, &[]);
        let moved_scene = eye_moved(Path::new(scene), dir.path(), axis, 1e-5);
        let moved = dir.path().join("moved.png");
        render_to(&moved_scene, &moved, size, &[]);
        let (a, b) = (
            image::open(&ours).unwrap().into_rgb8(),
            image::open(&moved).unwrap().into_rgb8(),
        );
        if a == b {
            continue;
        }
        differing += 1;
        far_off += usize::from(largest_gap(&a, &b) > 32);
        let report = compared(scene, &moved);
        assert_eq!(
            report["matches"], true,
            "{scene} axis {axis} {size:?}: {report:#}"
        );
        assert_eq!(report["metrics"]["far_off_pixels"], 0, "{scene}");
        if scene.ends_with("seven-rays.toml") && axis == 1 {
            // The horizon row: most of its 161 pixels on an edge through
            // their centres (those seen through the glass balls may not
            // be), the rest within the share a match allows (19 of 19,481).
            let on_edge = report["metrics"]["on_edge_pixels"].as_u64().unwrap();
            horizon = on_edge > 161 - 19;
        }
    }
    // The test can fail: some moves change bytes, and some past 32 steps,
    // the horizon's among them.
    assert!(
        differing >= 5 && far_off >= 3 && horizon,
        "{differing} differ, {far_off} far off, horizon {horizon}"
    );
}

#[test]
fn a_render_anti_aliased_2x2_matches_and_is_said_so() {
    // Four rays a pixel through its quarter points, averaged: every edge
    // pixel is a blend of both sides, far more than the 0.1% of pixels a
    // match allows past 3 steps (1 to 8% of them on these scenes), some
    // past 32 (glass.toml's thin bright rims). Each lies within what the
    // scene shows inside its pixel and the edges moved no way: a match,
    // said to be anti-aliased.
    let dir = tempfile::tempdir().unwrap();
    for scene in TEACHING_SCENES {
        let size = own_size(scene);
        let image = dir.path().join("aa.png");
        supersampled(Path::new(scene), dir.path(), size)
            .save(&image)
            .unwrap();
        let report = compared(scene, &image);
        let metrics = &report["metrics"];
        let over = metrics["pixels_over_tolerance"].as_f64().unwrap();
        assert!(over > 0.001, "{scene}: {over}");
        assert_eq!(report["matches"], true, "{scene}: {metrics:#}");
        let pixels = f64::from(size.0 * size.1);
        // A few may lie on an edge through their centres, which a blend
        // lies within too (highlights.toml: 4 of 341, where the balls'
        // silhouettes pass within 1e-3 pixel of a centre).
        let anti_aliased = metrics["anti_aliased_pixels"].as_f64().unwrap();
        let on_edge = metrics["on_edge_pixels"].as_f64().unwrap();
        assert!(on_edge < anti_aliased / 20.0, "{scene}: {metrics:#}");
        assert!(
            over - (anti_aliased + on_edge) / pixels <= 0.001,
            "{scene}: {metrics:#}"
        );
        let text = stdout(&raystep(&["compare", scene, path(&image)]));
        assert!(
            text.contains("they match: ") && text.contains("anti-aliased edges"),
            "{text}"
        );
        assert!(text.contains("\n  anti-aliased: each of those "), "{text}");
    }
}

#[test]
fn a_half_pixel_shift_and_wrapped_bytes_still_differ() {
    // pixel-corner moves the whole image half a pixel: its edge pixels
    // take values the scene shows right there, as blends do, but every
    // edge moved down and right (the shift compare estimates is past half
    // a pixel on every teaching scene), so none is taken as anti-aliasing
    // and the pixels past 3 steps (over 0.6%) make it differ. byte-wrap's
    // wrapped pixels (glass.toml: 6) lie far outside the values around them.
    let dir = tempfile::tempdir().unwrap();
    for scene in TEACHING_SCENES {
        let image = dir.path().join("corner.png");
        render_to(
            Path::new(scene),
            &image,
            own_size(scene),
            &["--mistake", "pixel-corner"],
        );
        let report = compared(scene, &image);
        assert_eq!(report["matches"], false, "{scene}");
        let metrics = &report["metrics"];
        assert_eq!(metrics["anti_aliased_pixels"], 0, "{scene}");
        let shift: Vec<f64> = (metrics["edge_shift"].as_array().unwrap().iter())
            .map(|v| v.as_f64().unwrap())
            .collect();
        assert!(shift[0].hypot(shift[1]) >= 0.5, "{scene}: {shift:?}");
        assert_eq!(report["mistakes"][0]["name"], "pixel-corner", "{scene}");
    }
    let image = dir.path().join("wrapped.png");
    render_to(
        Path::new("scenes/glass.toml"),
        &image,
        (160, 120),
        &["--mistake", "byte-wrap"],
    );
    let report = compared("scenes/glass.toml", &image);
    assert_eq!(report["matches"], false);
    assert_eq!(report["metrics"]["far_off_pixels"], 6);
    assert_eq!(report["metrics"]["sub_pixel_pixels"], 0);
}
