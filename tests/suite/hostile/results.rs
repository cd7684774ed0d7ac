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
