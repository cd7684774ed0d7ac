//! A CSE 167 student's ray log (issue 42): the course weighs the mirror ray
//! by the specular colour S (I = … + S I_R), so a reflected ray's weight is
//! a colour, logged as [r, g, b] (or as a number when S is grey), and a log
//! that weighs it by S agrees with ours, where one that leaves S out does
//! not.

use std::fs;

use serde_json::Value;

use crate::support::{path, raystep, stderr, stdout};

/// A 3x3 scene: the centre pixel's primary ray meets the unit sphere at
/// (0, 0, 1) head on; its mirror ray goes back along +z and misses.
fn scene(specular: &str) -> String {
    format!("size 3 3\ncamera 0 0 5 0 0 0 0 1 0 30\nspecular {specular}\nsphere 0 0 0 1\n")
}

/// raystep's log of the centre pixel of the scene with `specular`.
fn our_log(dir: &std::path::Path, specular: &str) -> Vec<Value> {
    let file = dir.join("scene.test");
    fs::write(&file, scene(specular)).unwrap();
    let output = raystep(&[
        "inspect",
        path(&file),
        "--pixel",
        "1,1",
        "--format",
        "raylog",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    (stdout(&output).lines())
        .map(|line| serde_json::from_str(line).unwrap())
        .collect()
}

fn weight_of<'a>(log: &'a [Value], ray: &str) -> &'a Value {
    &log.iter().find(|l| l["path"] == ray).unwrap()["weight"]
}

/// `compare --rays` of `log` against the scene written last in `dir`.
fn compared(dir: &std::path::Path, log: &[Value]) -> String {
    let file = dir.join("mine.jsonl");
    let text: String = log.iter().map(|l| format!("{l}\n")).collect();
    fs::write(&file, text).unwrap();
    let output = raystep(&[
        "compare",
        path(&dir.join("scene.test")),
        "--rays",
        path(&file),
    ]);
    stdout(&output)
}

#[test]
fn a_mirror_rays_weight_is_the_specular_colour() {
    let dir = tempfile::tempdir().unwrap();
    // S = (0.3, 0.2, 0.1): k_s = 1 and O_s = S in raystep's terms, so the
    // mirror ray's weight is 1 × (1 × S) = [0.3, 0.2, 0.1], the primary's 1.
    let log = our_log(dir.path(), "0.3 0.2 0.1");
    assert_eq!(weight_of(&log, "P"), &serde_json::json!(1.0));
    assert_eq!(weight_of(&log, "P/R"), &serde_json::json!([0.3, 0.2, 0.1]));
    assert!(compared(dir.path(), &log).contains("matches ours"));
    // A log that leaves S out (weight 1, k_s alone) parts at the weight.
    let mut without_s = log.clone();
    for line in &mut without_s {
        if line["path"] == "P/R" {
            line["weight"] = serde_json::json!(1.0);
        }
    }
    let report = compared(dir.path(), &without_s);
    assert!(report.contains("First divergence: P/R weight"), "{report}");
    assert!(
        report.contains("a mirror ray's k_s O_s per channel"),
        "{report}"
    );
    // S grey, 0.4: the weight is the number 0.4, as a tracer with a
    // scalar weight logs it; [0.4, 0.4, 0.4] is the same weight.
    let log = our_log(dir.path(), "0.4 0.4 0.4");
    assert_eq!(weight_of(&log, "P/R"), &serde_json::json!(0.4));
    let mut as_colour = log.clone();
    for line in &mut as_colour {
        if line["path"] == "P/R" {
            line["weight"] = serde_json::json!([0.4, 0.4, 0.4]);
        }
    }
    assert!(compared(dir.path(), &as_colour).contains("matches ours"));
}
