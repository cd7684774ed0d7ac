//! What-if from the command line: `--set` changes a setting or a material
//! and the text ends with what changed; `--diff-against` compares with
//! another scene file.

use crate::support::{raystep, stderr, stdout};

#[test]
fn a_lower_depth_and_plain_glass_say_which_rays_went() {
    // glass.toml's TIR pixel (135, 58): the transmitted ray meets total
    // internal reflection at depth 2 and its reflected chain goes to depth
    // 5. At max_depth 2 the depth-2 ray spawns nothing: its four
    // descendants are gone, and with them the TIR.
    let output = raystep(&[
        "explain",
        "scenes/glass.toml",
        "--pixel",
        "135,58",
        "--set",
        "settings.max_depth=2",
        "--set",
        "materials.glass.ior=1.0",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    let changed = text
        .split("What changed against the scene as written:")
        .nth(1)
        .unwrap();
    assert_eq!(changed.matches("ray is gone").count(), 4, "{changed}");
    assert!(
        changed.contains("no longer total internal reflection"),
        "{changed}"
    );
    assert!(!changed.contains("a new"), "{changed}");
}

#[test]
fn nothing_changes_without_a_change() {
    // max_depth 5 is glass.toml's own: the same rays with the same terms.
    let output = raystep(&[
        "inspect",
        "scenes/glass.toml",
        "--pixel",
        "80,60",
        "--set",
        "settings.max_depth=5",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(stdout(&output).contains("nothing else changed"));
}

#[test]
fn diff_against_another_scene_names_it() {
    let output = raystep(&[
        "explain",
        "scenes/glass.toml",
        "--pixel",
        "10,10",
        "--diff-against",
        "scenes/shadows.toml",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    assert!(
        text.contains("What changed against scenes/shadows.toml:"),
        "{text}"
    );
    assert!(
        text.contains("primary ray: hits floor -> nothing (a miss)"),
        "{text}"
    );
}

#[test]
fn a_bad_set_is_refused_with_exit_one() {
    for (bad, says) in [
        (
            "materials.nope.kd=1",
            "no material \"nope\"; the scene has glass, red, yellow",
        ),
        ("settings.max_depth=0", "max_depth must be between 1 and 64"),
        ("materials.glass.kt=2", "must be between 0 and 1"),
    ] {
        let output = raystep(&[
            "inspect",
            "scenes/glass.toml",
            "--pixel",
            "1,1",
            "--set",
            bad,
        ]);
        assert_eq!(output.status.code(), Some(1), "{bad}");
        assert!(stderr(&output).contains(says), "{bad}: {}", stderr(&output));
    }
}
