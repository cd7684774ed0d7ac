//! Issue 42's done-when: a CSE 167 tracer of our own, `tests/student/cse167.py`,
//! written from the course's spec alone (its HW3 raytracer spec and HW2's
//! skeleton `readfile.cpp`; MODEL §11 and the `.test` reader's module docs
//! only where the course is silent), never from raystep's code, renders
//! every scene of `scenes/cse167/` as raystep does.
//!
//! The rule: the same bytes, or every channel within one step and at most
//! one pixel in a thousand differing. Both tracers evaluate the same
//! equation in f64, but not in the same order (raystep sums its terms per
//! light and in its own matrix code; the script in Python's): a colour that
//! lands within ~1e-15 of a rounding boundary, floor(255 c + 0.5), may round
//! either way, a one-step difference on a rare pixel. Anything more is a
//! different equation. (Measured when written: all eight scenes identical,
//! 0 differing pixels.) Needs python3: skipped without it, failing under CI
//! (`program_or_skip`).

use std::path::Path;

use crate::support::student::run_tracer;
use crate::support::{path, program_or_skip, raystep, stderr};

/// The script's path from the repository's root.
const TRACER: &str = "tests/student/cse167.py";

/// How many pixels differ between `a` and `b`, and the largest difference
/// of one channel.
fn differences(a: &image::RgbImage, b: &image::RgbImage) -> (usize, u8) {
    let gaps: Vec<u8> = (a.pixels().zip(b.pixels()))
        .map(|(p, q)| (0..3).map(|c| p.0[c].abs_diff(q.0[c])).max().unwrap())
        .filter(|&gap| gap > 0)
        .collect();
    (gaps.len(), gaps.iter().copied().max().unwrap_or(0))
}

#[test]
fn a_cse167_tracer_written_from_the_course_spec_renders_every_scene_as_raystep() {
    if program_or_skip("python3").is_none() {
        return;
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut scenes: Vec<_> = std::fs::read_dir(root.join("scenes/cse167"))
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "test"))
        .collect();
    scenes.sort();
    // README.md names eight scenes: none may go missing unnoticed.
    assert!(scenes.len() >= 8, "scenes/cse167: {scenes:?}");
    let dir = tempfile::tempdir().unwrap();
    for scene in &scenes {
        let name = scene.file_stem().unwrap().to_str().unwrap();
        let ours = dir.path().join(format!("{name}-raystep.png"));
        let theirs = dir.path().join(format!("{name}-cse167py.png"));
        let output = raystep(&[
            "render",
            scene.to_str().unwrap(),
            "-o",
            ours.to_str().unwrap(),
        ]);
        assert!(output.status.success(), "{name}: {}", stderr(&output));
        run_tracer(&[TRACER, path(scene), "-o", path(&theirs)]);
        let ours = image::open(&ours).unwrap().into_rgb8();
        let theirs = image::open(&theirs).unwrap().into_rgb8();
        assert_eq!(ours.dimensions(), theirs.dimensions(), "{name}");
        let (count, largest) = differences(&ours, &theirs);
        let (w, h) = ours.dimensions();
        let allowed = (w * h / 1000) as usize;
        assert!(
            largest <= 1 && count <= allowed,
            "{name}: {count} pixels differ (at most {allowed} by one step allowed), by up to {largest}"
        );
    }
}
