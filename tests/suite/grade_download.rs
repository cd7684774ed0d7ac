//! `raystep grade` on a class download as it comes (issue 40): what macOS,
//! Windows and archivers leave is not graded as students and is named once;
//! a student whose files sit one folder down, or are named `Shadows.PNG`,
//! `x.png.png` or `x .png`, is graded with a note saying so, unless the
//! assignment asks for exact names; a missing file's refusal names the
//! closest names held. And the autograders' files as their documentation
//! defines them: Gradescope's `output_format` and `visibility`,
//! PrairieLearn's `gradable`.

use std::fs;
use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::support::{json, path, raystep, stderr, stdout};

/// Two scenes at 80 x 60, all or nothing, 10 points each.
const ASSIGNMENT: &str = r#"title = "A5 <meshes> test"

[[scene]]
file = "shadows.toml"
submit = "shadows.png"
points = 10
size = [80, 60]

[[scene]]
file = "highlights.toml"
submit = "highlights.png"
points = 10
size = [80, 60]
"#;

/// A folder with the assignment (`assignment` as its text), its scenes, and
/// raystep's correct renders of both to hand in.
struct Download {
    dir: tempfile::TempDir,
}

impl Download {
    fn new(assignment: &str) -> Download {
        let dir = tempfile::tempdir().unwrap();
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        for scene in ["shadows", "highlights"] {
            let toml = dir.path().join(format!("{scene}.toml"));
            fs::copy(root.join(format!("scenes/{scene}.toml")), &toml).unwrap();
            let png = dir.path().join(format!("{scene}.png"));
            let output = raystep(&["render", path(&toml), "-o", path(&png), "--size", "80x60"]);
            assert!(output.status.success(), "{}", stderr(&output));
        }
        fs::write(dir.path().join("a5.toml"), assignment).unwrap();
        Download { dir }
    }

    fn at(&self, relative: &str) -> PathBuf {
        self.dir.path().join(relative)
    }

    /// raystep's correct render of `scene` handed in as `relative` (under
    /// submissions/, folders made as needed).
    fn hand_in(&self, scene: &str, relative: &str) {
        let to = self.at("submissions").join(relative);
        fs::create_dir_all(to.parent().unwrap()).unwrap();
        fs::copy(self.at(&format!("{scene}.png")), to).unwrap();
    }

    /// Some file that is no image, at `relative` under submissions/.
    fn junk(&self, relative: &str) {
        let to = self.at("submissions").join(relative);
        fs::create_dir_all(to.parent().unwrap()).unwrap();
        fs::write(to, b"\0\0junk\n").unwrap();
    }

    /// `raystep grade` on one folder under submissions/, with both
    /// autograders' results: its summary, Gradescope's and PrairieLearn's.
    fn one(&self, student: &str) -> (String, Value, Value) {
        let (gs, pl) = (self.at("gs.json"), self.at("pl.json"));
        let output = raystep(&[
            "grade",
            path(&self.at("a5.toml")),
            "--submission",
            path(&self.at("submissions").join(student)),
            "--gradescope",
            path(&gs),
            "--prairielearn",
            path(&pl),
        ]);
        assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
        (stdout(&output), json(&gs), json(&pl))
    }
}

fn student<'a>(grades: &'a Value, name: &str) -> &'a Value {
    grades["students"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["student"] == name)
        .unwrap_or_else(|| panic!("no student {name}"))
}

/// (points, refused, note) of each scene of a student in grades.json.
fn scenes(student: &Value) -> Vec<(f64, String, String)> {
    let text = |v: &Value| v.as_str().unwrap_or("").to_string();
    student["scenes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| {
            (
                s["points"].as_f64().unwrap(),
                text(&s["refused"]),
                text(&s["note"]),
            )
        })
        .collect()
}

#[test]
fn a_class_download_grades_as_it_comes() {
    let class = Download::new(ASSIGNMENT);
    // What a Mac's zip, a Windows Explorer and git leave: never students.
    class.hand_in("shadows", "__MACOSX/ada/._shadows.png");
    class.hand_in("shadows", ".git/shadows.png");
    for junk in ["Thumbs.db", "desktop.ini", ".DS_Store"] {
        class.junk(junk);
    }
    // ada: both files as named.
    class.hand_in("shadows", "ada/shadows.png");
    class.hand_in("highlights", "ada/highlights.png");
    // down: both one folder down, beside a Mac's leftovers.
    class.hand_in("shadows", "down/lab4-submission/shadows.png");
    class.hand_in("highlights", "down/lab4-submission/highlights.png");
    class.junk("down/__MACOSX/lab4-submission/._shadows.png");
    class.junk("down/.DS_Store");
    // near: the case of one name, the doubled extension of the other.
    class.hand_in("shadows", "near/Shadows.PNG");
    class.hand_in("highlights", "near/highlights.png.png");
    // spaced: a space before the extension; highlights misspelt (an "s"
    // short: no near miss, so missing, and the file it holds named).
    class.hand_in("shadows", "spaced/shadows .png");
    class.hand_in("highlights", "spaced/highlight.png");
    // twice: two near misses of shadows.png: which is meant is a guess.
    class.hand_in("shadows", "twice/Shadows.png");
    class.hand_in("shadows", "twice/shadows.PNG");
    class.hand_in("highlights", "twice/highlights.png");

    let report = class.at("report");
    let output = raystep(&[
        "grade",
        path(&class.at("a5.toml")),
        path(&class.at("submissions")),
        "-o",
        path(&report),
    ]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let grades = json(&report.join("grades.json"));
    let names: Vec<&str> = (grades["students"].as_array().unwrap().iter())
        .map(|s| s["student"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["ada", "down", "near", "spaced", "twice"]);
    // Named once, by their bytes: '.' < 'T' < '_' < 'd'.
    assert_eq!(
        grades["ignored"],
        serde_json::json!([".DS_Store", ".git", "Thumbs.db", "__MACOSX", "desktop.ini"])
    );
    let none = String::new;
    assert_eq!(
        scenes(student(&grades, "ada")),
        [(10.0, none(), none()), (10.0, none(), none())]
    );
    let down = student(&grades, "down");
    assert_eq!(
        scenes(down),
        [(10.0, none(), none()), (10.0, none(), none())]
    );
    assert_eq!(
        down["notes"],
        serde_json::json!([
            "your files were read from the folder lab4-submission/, the one folder in yours"
        ])
    );
    assert_eq!(
        scenes(student(&grades, "near")),
        [
            (10.0, none(), "took Shadows.PNG for shadows.png".into()),
            (
                10.0,
                none(),
                "took highlights.png.png for highlights.png".into()
            ),
        ]
    );
    assert_eq!(student(&grades, "near")["notes"], serde_json::json!([]));
    assert_eq!(
        scenes(student(&grades, "spaced")),
        [
            (10.0, none(), "took \"shadows .png\" for shadows.png".into()),
            (
                0.0,
                "missing: the folder holds no highlights.png; the folder holds highlight.png"
                    .into(),
                none()
            ),
        ]
    );
    assert_eq!(
        scenes(student(&grades, "twice")),
        [
            (
                0.0,
                "2 files could be shadows.png: Shadows.png and shadows.PNG; rename the one you \
                 mean to shadows.png"
                    .into(),
                none()
            ),
            (10.0, none(), none()),
        ]
    );
    // 20 + 20 + 20 + 10 + 10 over 5 students: 16, __MACOSX not among them.
    assert!(
        stdout(&output).starts_with("graded 5 students on 2 scenes: mean 16 of 20 points"),
        "{}",
        stdout(&output)
    );

    // The report: the ignored names once in the summary, each student's
    // notes on their row and their page.
    let index = fs::read_to_string(report.join("index.html")).unwrap();
    assert_eq!(
        index
            .matches(
                "Not students, not graded: <bdi>.DS_Store</bdi>, <bdi>.git</bdi>, \
             <bdi>Thumbs.db</bdi>, <bdi>__MACOSX</bdi>, <bdi>desktop.ini</bdi>"
            )
            .count(),
        1,
        "{index}"
    );
    assert!(
        !index.contains(">__MACOSX</bdi></a>"),
        "no row for __MACOSX"
    );
    let near = "took Shadows.PNG for shadows.png; took highlights.png.png for highlights.png";
    assert!(index.contains(&format!(
        "<div class=\"notes\" title=\"{near}\">{near}</div>"
    )));
    let slug = student(&grades, "near")["slug"].as_str().unwrap();
    let page = fs::read_to_string(report.join(format!("students/{slug}.html"))).unwrap();
    assert!(
        page.contains(&format!("<p class=\"notes\">Note: {near}.</p>")),
        "{page}"
    );
    let slug = student(&grades, "spaced")["slug"].as_str().unwrap();
    let page = fs::read_to_string(report.join(format!("students/{slug}.html"))).unwrap();
    assert!(
        page.contains(
            "<p class=\"notes\">Note: took &quot;shadows .png&quot; for shadows.png.</p>"
        ),
        "{page}"
    );
    let slug = student(&grades, "down")["slug"].as_str().unwrap();
    let page = fs::read_to_string(report.join(format!("students/{slug}.html"))).unwrap();
    assert!(page.contains("Note: your files were read from the folder lab4-submission/"));
}

#[test]
fn one_submission_takes_a_near_name_and_the_autograders_are_told() {
    let class = Download::new(ASSIGNMENT);
    class.hand_in("shadows", "near/Shadows.PNG");
    class.hand_in("highlights", "near/highlights.png.png");
    let (summary, gradescope, prairie) = class.one("near");
    assert!(
        summary.starts_with("A5 <meshes> test: 20 of 20 points\n"),
        "{summary}"
    );
    assert!(
        summary.ends_with(
            "  note: took Shadows.PNG for shadows.png\n  note: took highlights.png.png for highlights.png\n"
        ),
        "{summary}"
    );
    // Gradescope: plain text everywhere, so the title's <meshes> shows as
    // written; visible, the default.
    assert_eq!(gradescope["score"], 20.0);
    assert_eq!(gradescope["output"], "A5 <meshes> test: 20 of 20 points.");
    assert_eq!(gradescope["output_format"], "text");
    assert_eq!(gradescope["visibility"], "visible");
    let tests = gradescope["tests"].as_array().unwrap();
    for test in tests {
        assert_eq!(test["output_format"], "text");
        assert_eq!(test["visibility"], "visible");
        assert_eq!(test["score"], 10.0);
    }
    let said = tests[0]["output"].as_str().unwrap();
    assert!(
        said.starts_with(
            "10 of 10 points: your image matches raystep's.\nNote: took Shadows.PNG for shadows.png.\n\n"
        ),
        "{said}"
    );
    // PrairieLearn: gradable, the note in the test's message.
    assert_eq!(prairie["gradable"], true);
    assert_eq!(prairie["score"], 1.0);
    assert!(prairie.get("format_errors").is_none());
    assert_eq!(
        prairie["tests"][1]["message"],
        "matches (took highlights.png.png for highlights.png)"
    );

    // With strict_names the same folder is refused, naming what it holds:
    // nothing was compared, so PrairieLearn does not count the attempt.
    fs::write(
        class.at("a5.toml"),
        format!("strict_names = true\n{ASSIGNMENT}"),
    )
    .unwrap();
    let (summary, gradescope, prairie) = class.one("near");
    let refusals = [
        "missing: the folder holds no shadows.png, only Shadows.PNG (the assignment asks for \
         exact names: strict_names = true)",
        "missing: the folder holds no highlights.png, only highlights.png.png (the assignment \
         asks for exact names: strict_names = true)",
    ];
    for (i, refusal) in refusals.iter().enumerate() {
        assert!(
            summary.contains(&format!("not graded: {refusal}")),
            "{summary}"
        );
        assert_eq!(
            gradescope["tests"][i]["output"],
            format!("0 of 10 points: not graded, {refusal}.\n")
        );
    }
    assert_eq!(gradescope["score"], 0.0);
    assert_eq!(prairie["gradable"], false);
    assert_eq!(
        prairie["format_errors"],
        serde_json::json!([
            format!("shadows.png: {}", refusals[0]),
            format!("highlights.png: {}", refusals[1])
        ])
    );
    let message = prairie["message"].as_str().unwrap();
    assert!(message.contains("Nothing could be graded"), "{message}");
    assert!(message.contains("not counted as an attempt"), "{message}");
}

#[test]
fn an_empty_submission_is_not_gradable_and_visibility_is_the_assignments() {
    // The assignment's visibility for every test, one scene's own.
    let assignment =
        format!("visibility = \"after_due_date\"\n{ASSIGNMENT}visibility = \"hidden\"\n");
    let class = Download::new(&assignment);
    fs::create_dir_all(class.at("submissions/empty")).unwrap();
    class.junk("empty/.DS_Store");
    let (_, gradescope, prairie) = class.one("empty");
    assert_eq!(gradescope["visibility"], "after_due_date");
    assert_eq!(gradescope["tests"][0]["visibility"], "after_due_date");
    assert_eq!(gradescope["tests"][1]["visibility"], "hidden");
    assert_eq!(gradescope["score"], 0.0);
    assert_eq!(prairie["gradable"], false);
    assert_eq!(
        prairie["format_errors"],
        serde_json::json!([
            "shadows.png: missing: the folder holds no shadows.png",
            "highlights.png: missing: the folder holds no highlights.png"
        ])
    );
    // One file compared, even a wrong one: gradable, and scored.
    class.junk("empty/highlights.png");
    class.hand_in("shadows", "empty/shadows.png");
    let (_, _, prairie) = class.one("empty");
    assert_eq!(prairie["gradable"], true);
    assert_eq!(prairie["score"], 0.5);
    // A value Gradescope does not know is refused at its line and column.
    fs::write(
        class.at("a5.toml"),
        format!("visibility = \"soon\"\n{ASSIGNMENT}"),
    )
    .unwrap();
    let output = raystep(&[
        "grade",
        path(&class.at("a5.toml")),
        "--submission",
        path(&class.at("submissions/empty")),
    ]);
    assert_eq!(output.status.code(), Some(1));
    assert!(
        stderr(&output).starts_with(&format!(
            "error: {}:1:14: unknown variant `soon`",
            class.at("a5.toml").display()
        )),
        "{}",
        stderr(&output)
    );
}

#[test]
fn a_missing_files_refusal_names_the_closest_names_held() {
    let class = Download::new(ASSIGNMENT);
    class.hand_in("highlights", "ada/highlights.png");
    // Distances to shadows.png: shadow.png 1 (an "s" short), shadows.jpg 2
    // (j for p, p for n), shadows.png.txt 4 (".txt" more), zz.bin at least
    // 5 (5 characters shorter). highlights.png is taken for its scene.
    for name in ["zz.bin", "shadows.png.txt", "shadow.png", "shadows.jpg"] {
        class.junk(&format!("ada/{name}"));
    }
    let (summary, gradescope, _) = class.one("ada");
    let refusal = "missing: the folder holds no shadows.png; the folder holds shadow.png, \
                   shadows.jpg, shadows.png.txt and 1 more";
    assert!(
        summary.contains(&format!("not graded: {refusal}\n")),
        "{summary}"
    );
    assert_eq!(
        gradescope["tests"][0]["output"],
        format!("0 of 10 points: not graded, {refusal}.\n")
    );
    assert_eq!(gradescope["score"], 10.0);
}
