//! `raystep grade` as a teacher and an autograder run it: a class of
//! students made of `raystep render --mistake` images, correct ones and
//! every kind of bad file, graded into REPORT/; the CSV, the JSON, both
//! autograder files, the totals, the exit statuses, what -o refuses, and
//! the same grades whatever the number of threads.

use std::ffi::OsStr;
use std::fs;
use std::os::unix::ffi::OsStrExt;
use std::path::{Path, PathBuf};
use std::process::Output;

use serde_json::Value;

use crate::support::{json, path, raystep, stderr, stdout};

/// Two scenes at 80 x 60: shadows all or nothing, highlights with partial
/// credit (10 × max(0, 1 − FLIP / 0.2)).
const ASSIGNMENT: &str = r#"title = "A5 test"

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
partial = true
max_flip = 0.2
"#;

/// The longest folder name Linux allows: 255 bytes.
const LONG: usize = 255;

/// A folder with the assignment, its two scene files, and raystep's
/// renders at 80 x 60 (correct, and under a few mistakes) to copy from.
struct Class {
    dir: tempfile::TempDir,
}

impl Class {
    fn new() -> Class {
        let dir = tempfile::tempdir().unwrap();
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        for scene in ["shadows.toml", "highlights.toml"] {
            fs::copy(root.join("scenes").join(scene), dir.path().join(scene)).unwrap();
        }
        fs::write(dir.path().join("a5.toml"), ASSIGNMENT).unwrap();
        fs::create_dir(dir.path().join("renders")).unwrap();
        fs::create_dir(dir.path().join("submissions")).unwrap();
        Class { dir }
    }

    fn at(&self, relative: &str) -> PathBuf {
        self.dir.path().join(relative)
    }

    /// raystep's render of `scene` at `size` under `mistake` ("" for none).
    fn render(&self, scene: &str, mistake: &str, size: &str) -> PathBuf {
        let out = self.at(&format!("renders/{scene}-{mistake}-{size}.png"));
        if !out.exists() {
            let toml = self.at(&format!("{scene}.toml"));
            let mut args = vec!["render", path(&toml), "-o", path(&out), "--size", size];
            if !mistake.is_empty() {
                args.extend(["--mistake", mistake]);
            }
            let output = raystep(&args);
            assert!(output.status.success(), "{}", stderr(&output));
        }
        out
    }

    /// The student's folder (its name any bytes), created.
    fn student(&self, name: &[u8]) -> PathBuf {
        let folder = self.at("submissions").join(OsStr::from_bytes(name));
        fs::create_dir_all(&folder).unwrap();
        folder
    }

    /// Copies raystep's render (under `mistake`) into the folder as `scene`.png.
    fn hand_in(&self, folder: &Path, scene: &str, mistake: &str) {
        let render = self.render(scene, mistake, "80x60");
        fs::copy(render, folder.join(format!("{scene}.png"))).unwrap();
    }

    fn grade(&self, extra: &[&str]) -> Output {
        let (a5, submissions) = (self.at("a5.toml"), self.at("submissions"));
        let mut args = vec!["grade", path(&a5), path(&submissions)];
        args.extend(extra);
        raystep(&args)
    }
}

/// The class of every case. Names, sorted by their bytes, and what each
/// should score (shadows all or nothing, highlights partial):
///
/// | student | shadows | highlights | total |
/// |---|---|---|---|
/// | `<img src=x onerror=alert(1)>` | correct: 10 | correct: 10 | 20 |
/// | `=HYPERLINK("x")` | not a PNG: 0 | truncated PNG: 0 | 0 |
/// | `O'Brien, "Q"` | missing: 0 | correct: 10 | 10 |
/// | `ada` | correct: 10 | correct: 10 | 20 |
/// | `bo` | flipped-y: 0 | correct: 10 | 10 |
/// | `caf\xe9` (not UTF-8) | rendered at 160x120: 0 | correct: 10 | 10 |
/// | `cy` | correct: 10 | phong-not-blinn: 10 × (1 − FLIP / 0.2) | 10 + that |
/// | `fifo` | a FIFO: 0 | too large: 0 | 0 |
/// | `linked` | link inside its folder to a correct image: 10 | link to ../ada's: 0 | 10 |
/// | 255 × `x` | link out to ada's image: 0 | a folder: 0 | 0 |
///
/// Beside them a file (`submission_metadata.yml`) and a hidden folder,
/// which are no students.
fn whole_class() -> Class {
    let class = Class::new();
    for name in [&b"<img src=x onerror=alert(1)>"[..], b"ada"] {
        let folder = class.student(name);
        class.hand_in(&folder, "shadows", "");
        class.hand_in(&folder, "highlights", "");
    }
    let ada = class.at("submissions/ada");

    let formula = class.student(b"=HYPERLINK(\"x\")");
    fs::write(formula.join("shadows.png"), "not an image\n").unwrap();
    let whole = fs::read(class.render("highlights", "", "80x60")).unwrap();
    fs::write(formula.join("highlights.png"), &whole[..whole.len() / 2]).unwrap();

    let quoted = class.student(b"O'Brien, \"Q\"");
    class.hand_in(&quoted, "highlights", "");

    let bo = class.student(b"bo");
    class.hand_in(&bo, "shadows", "flipped-y");
    class.hand_in(&bo, "highlights", "");

    let cafe = class.student(b"caf\xe9");
    fs::copy(
        class.render("shadows", "", "160x120"),
        cafe.join("shadows.png"),
    )
    .unwrap();
    class.hand_in(&cafe, "highlights", "");

    let cy = class.student(b"cy");
    class.hand_in(&cy, "shadows", "");
    class.hand_in(&cy, "highlights", "phong-not-blinn");

    let fifo = class.student(b"fifo");
    let name = std::ffi::CString::new(path(&fifo.join("shadows.png"))).unwrap();
    assert_eq!(unsafe { libc::mkfifo(name.as_ptr(), 0o644) }, 0);
    // 2 MB: more than 80 × 60 × 8 bytes and a megabyte to spare.
    fs::write(fifo.join("highlights.png"), vec![0u8; 2_000_000]).unwrap();

    let linked = class.student(b"linked");
    fs::create_dir(linked.join("inner")).unwrap();
    fs::copy(
        class.render("shadows", "", "80x60"),
        linked.join("inner/ok.png"),
    )
    .unwrap();
    std::os::unix::fs::symlink("inner/ok.png", linked.join("shadows.png")).unwrap();
    std::os::unix::fs::symlink("../ada/highlights.png", linked.join("highlights.png")).unwrap();

    let long = class.student(&[b'x'; LONG]);
    std::os::unix::fs::symlink(ada.join("shadows.png"), long.join("shadows.png")).unwrap();
    fs::create_dir(long.join("highlights.png")).unwrap();

    fs::write(class.at("submissions/submission_metadata.yml"), "x: 1\n").unwrap();
    let hidden = class.student(b".hidden");
    class.hand_in(&hidden, "shadows", "");
    class
}

fn student<'a>(grades: &'a Value, name: &str) -> &'a Value {
    grades["students"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["student"] == name)
        .unwrap_or_else(|| panic!("no student {name}"))
}

/// What the scene's grade says was refused, "" when compared.
fn refused(scene: &Value) -> &str {
    scene["refused"].as_str().unwrap_or("")
}

fn points(student: &Value) -> Vec<f64> {
    student["scenes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["points"].as_f64().unwrap())
        .collect()
}

/// cy's highlights: 10 × max(0, 1 − FLIP / 0.2) from the FLIP reported,
/// rounded to hundredths.
fn partial_points(scene: &Value) -> f64 {
    let flip = scene["flip_mean"].as_f64().unwrap();
    ((10.0 * (1.0 - flip / 0.2)).clamp(0.0, 10.0) * 100.0).round() / 100.0
}

/// Points as the CSV and the summaries write them: 10, 7.5, 3.85.
fn number(x: f64) -> String {
    let text = format!("{x:.2}");
    text.trim_end_matches('0').trim_end_matches('.').to_string()
}

#[test]
fn a_class_is_graded_with_every_bad_file_scored_0_and_why() {
    let class = whole_class();
    let report = class.at("report");
    let output = class.grade(&["-o", path(&report)]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let grades = json(&report.join("grades.json"));
    assert_eq!(grades["title"], "A5 test");
    assert_eq!(grades["max_total"], 20.0);
    let names: Vec<&str> = grades["students"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["student"].as_str().unwrap())
        .collect();
    let long = "x".repeat(LONG);
    assert_eq!(
        names,
        [
            "<img src=x onerror=alert(1)>",
            "=HYPERLINK(\"x\")",
            "O'Brien, \"Q\"",
            "ada",
            "bo",
            "caf\u{fffd}",
            "cy",
            "fifo",
            "linked",
            long.as_str(),
        ]
    );
    // Hand-derived points (the table above whole_class).
    for (name, expected) in [
        ("<img src=x onerror=alert(1)>", [10.0, 10.0]),
        ("=HYPERLINK(\"x\")", [0.0, 0.0]),
        ("O'Brien, \"Q\"", [0.0, 10.0]),
        ("ada", [10.0, 10.0]),
        ("bo", [0.0, 10.0]),
        ("caf\u{fffd}", [0.0, 10.0]),
        ("fifo", [0.0, 0.0]),
        ("linked", [10.0, 0.0]),
        (long.as_str(), [0.0, 0.0]),
    ] {
        let s = student(&grades, name);
        assert_eq!(points(s), expected, "{name}");
        assert_eq!(s["total"], expected[0] + expected[1], "{name}");
    }
    let cy = student(&grades, "cy");
    let highlights = &cy["scenes"][1];
    assert_eq!(highlights["matches"], false);
    assert_eq!(highlights["mistakes"][0], "phong-not-blinn");
    let partial = partial_points(highlights);
    assert!(partial > 0.0 && partial < 10.0, "{partial}");
    assert_eq!(points(cy), [10.0, partial]);
    assert_eq!(cy["total"], 10.0 + partial);
    let bo = student(&grades, "bo");
    assert_eq!(bo["scenes"][0]["mistakes"][0], "flipped-y");
    // The totals of the table above whole_class add up to 90 + cy's
    // partial points, over 10 students.
    assert_eq!(
        stdout(&output),
        format!(
            "graded 10 students on 2 scenes: mean {} of 20 points; the report is in {}\n",
            number(((90.0 + partial) / 10.0 * 100.0).round() / 100.0),
            report.display()
        )
    );
    // The reasons, one per bad file.
    let reasons = [
        ("=HYPERLINK(\"x\")", 0, "shadows.png is not a PNG image"),
        (
            "=HYPERLINK(\"x\")",
            1,
            "highlights.png is a damaged or truncated PNG",
        ),
        (
            "O'Brien, \"Q\"",
            0,
            "missing: the folder holds no shadows.png",
        ),
        (
            "caf\u{fffd}",
            0,
            "rendered at 160x120, the assignment asks for 80x60",
        ),
        (
            "fifo",
            0,
            "shadows.png is a device, pipe or socket, not a PNG file",
        ),
        ("fifo", 1, "highlights.png is too large: 2000000 bytes"),
        (
            "linked",
            1,
            "highlights.png is a symbolic link that leads out of the student's folder",
        ),
        (
            long.as_str(),
            0,
            "shadows.png is a symbolic link that leads out of the student's folder",
        ),
        (
            long.as_str(),
            1,
            "highlights.png is a folder, not a PNG file",
        ),
    ];
    for (name, scene, reason) in reasons {
        let graded = &student(&grades, name)["scenes"][scene];
        assert!(refused(graded).starts_with(reason), "{name}: {graded}");
        assert_eq!(graded["points"], 0.0);
        assert_eq!(graded["compare"], Value::Null);
        assert_eq!(graded["yours_image"], Value::Null);
    }
    // A compared image has compare --format json's whole value and its files.
    let ada = student(&grades, "ada");
    assert_eq!(ada["scenes"][0]["compare"]["matches"], true);
    assert!(ada["scenes"][0]["compare"]["metrics"]["flip_mean"].is_number());
    let mut slugs = Vec::new();
    for s in grades["students"].as_array().unwrap() {
        let slug = s["slug"].as_str().unwrap();
        assert!(
            !slug.is_empty()
                && slug.bytes().all(|b| b.is_ascii_lowercase()
                    || b.is_ascii_digit()
                    || b == b'_'
                    || b == b'-'),
            "{slug}"
        );
        slugs.push(slug.to_string());
        for scene in s["scenes"].as_array().unwrap() {
            for key in ["yours_image", "error_map_image"] {
                if let Some(file) = scene[key].as_str() {
                    let image = image::open(report.join(file)).unwrap();
                    assert_eq!((image.width(), image.height()), (80, 60), "{file}");
                }
            }
        }
    }
    let unique: std::collections::BTreeSet<_> = slugs.iter().collect();
    assert_eq!(unique.len(), slugs.len(), "{slugs:?}");
    for sheet in grades["scenes"].as_array().unwrap() {
        let reference = sheet["reference_image"].as_str().unwrap();
        assert!(image::open(report.join(reference)).is_ok(), "{reference}");
    }
    // Nothing but the inputs and the report beside them: no temporaries.
    let mut top: Vec<String> = fs::read_dir(class.dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    top.sort();
    assert_eq!(
        top,
        [
            "a5.toml",
            "highlights.toml",
            "renders",
            "report",
            "shadows.toml",
            "submissions"
        ]
    );
}

/// RFC 4180 fields of one CSV text: quoted fields may hold commas, quotes
/// (doubled) and line breaks.
fn csv_rows(text: &str) -> Vec<Vec<String>> {
    let mut rows = Vec::new();
    let (mut row, mut field) = (Vec::new(), String::new());
    let mut chars = text.chars().peekable();
    let mut quoted = false;
    while let Some(c) = chars.next() {
        match (quoted, c) {
            (true, '"') if chars.peek() == Some(&'"') => {
                chars.next();
                field.push('"');
            }
            (true, '"') => quoted = false,
            (true, c) => field.push(c),
            (false, '"') => quoted = true,
            (false, ',') => row.push(std::mem::take(&mut field)),
            (false, '\r') => {}
            (false, '\n') => {
                row.push(std::mem::take(&mut field));
                rows.push(std::mem::take(&mut row));
            }
            (false, c) => field.push(c),
        }
    }
    rows
}

#[test]
fn the_csv_has_a_row_per_student_quoted_and_without_formulas() {
    let class = whole_class();
    let report = class.at("report");
    let output = class.grade(&["-o", path(&report)]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let text = fs::read_to_string(report.join("grades.csv")).unwrap();
    // UTF-8's byte-order mark first, for spreadsheets (docs/TEACHERS.md).
    let text = text
        .strip_prefix('\u{feff}')
        .expect("grades.csv opens with a byte-order mark");
    assert!(text.ends_with("\r\n"));
    // The quoted names, as written in the file.
    assert!(text.contains("\r\n\"O'Brien, \"\"Q\"\"\",0,"), "{text}");
    let rows = csv_rows(text);
    assert_eq!(
        rows[0],
        [
            "student",
            "shadows.png points",
            "shadows.png match",
            "shadows.png flip",
            "shadows.png mistake",
            "shadows.png refused",
            "highlights.png points",
            "highlights.png match",
            "highlights.png flip",
            "highlights.png mistake",
            "highlights.png refused",
            "total",
        ]
    );
    assert_eq!(rows.len(), 11, "a header and 10 students");
    let row = |name: &str| {
        rows.iter()
            .find(|r| r[0] == name)
            .unwrap_or_else(|| panic!("{name}"))
    };
    // The formula is defused with a leading quote: text, not =HYPERLINK.
    let formula = row("'=HYPERLINK(\"x\")");
    assert_eq!(formula[1..3], ["0", ""]);
    assert!(formula[5].starts_with("shadows.png is not a PNG image"));
    assert_eq!(formula[11], "0");
    let ada = row("ada");
    assert_eq!(ada[1..3], ["10", "yes"]);
    assert_eq!(ada[4..6], ["", ""]);
    assert_eq!(ada[11], "20");
    let bo = row("bo");
    assert_eq!(bo[1..3], ["0", "no"]);
    assert_eq!(bo[4], "flipped-y");
    assert_eq!(bo[11], "10");
    assert_eq!(row("caf\u{fffd}")[11], "10");
    assert_eq!(row("<img src=x onerror=alert(1)>")[11], "20");
    // The total column is the sum of the points columns, for every row.
    for r in &rows[1..] {
        let sum: f64 = r[1].parse::<f64>().unwrap() + r[6].parse::<f64>().unwrap();
        assert_eq!(number(sum), r[11], "{r:?}");
    }
}

/// Every file under `dir`, relative, with its bytes.
fn tree(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let mut files = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(folder) = stack.pop() {
        for entry in fs::read_dir(&folder).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else {
                files.push((
                    path.strip_prefix(dir).unwrap().to_owned(),
                    fs::read(&path).unwrap(),
                ));
            }
        }
    }
    files.sort();
    files
}

#[test]
fn the_report_is_the_same_whatever_the_number_of_threads() {
    let class = whole_class();
    // Two more students with the same mistake: the second takes the
    // renders the first made, and must be graded the same.
    for name in [&b"dee"[..], b"eve"] {
        let folder = class.student(name);
        class.hand_in(&folder, "shadows", "no-ambient");
        class.hand_in(&folder, "highlights", "gamma");
    }
    let one = class.at("one");
    let two = class.at("two");
    for (dir, jobs) in [(&one, "1"), (&two, "2")] {
        let output = class.grade(&["-o", path(dir), "--jobs", jobs]);
        assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    }
    let (one, two) = (tree(&one), tree(&two));
    assert!(one.len() > 20, "{} files", one.len());
    assert_eq!(
        one.iter().map(|f| &f.0).collect::<Vec<_>>(),
        two.iter().map(|f| &f.0).collect::<Vec<_>>()
    );
    for ((name, a), (_, b)) in one.iter().zip(&two) {
        assert!(a == b, "{} differs between --jobs 1 and 2", name.display());
    }
    let grades: Value = serde_json::from_slice(
        &one.iter()
            .find(|f| f.0 == Path::new("grades.json"))
            .unwrap()
            .1,
    )
    .unwrap();
    let (dee, eve) = (student(&grades, "dee"), student(&grades, "eve"));
    for (a, b) in dee["scenes"]
        .as_array()
        .unwrap()
        .iter()
        .zip(eve["scenes"].as_array().unwrap())
    {
        for key in [
            "points",
            "matches",
            "flip_mean",
            "mistakes",
            "compare",
            "report_text",
        ] {
            assert_eq!(a[key], b[key], "{key}");
        }
    }
    assert_eq!(dee["scenes"][0]["mistakes"][0], "no-ambient");
    assert_eq!(dee["scenes"][1]["mistakes"][0], "gamma");
}

#[test]
fn one_submission_writes_gradescopes_and_prairielearns_results() {
    let class = Class::new();
    let folder = class.student(b"cy");
    class.hand_in(&folder, "shadows", "");
    class.hand_in(&folder, "highlights", "phong-not-blinn");
    let results = class.at("results");
    let (gs, pl) = (
        results.join("gradescope.json"),
        results.join("pl/results.json"),
    );
    let output = raystep(&[
        "grade",
        path(&class.at("a5.toml")),
        "--submission",
        path(&folder),
        "--gradescope",
        path(&gs),
        "--prairielearn",
        path(&pl),
    ]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));

    // Gradescope's shape (its autograder specification): a score, and per
    // test a name, score, max_score, output and visibility.
    let gradescope = json(&gs);
    let tests = gradescope["tests"].as_array().unwrap();
    assert_eq!(tests.len(), 2);
    for test in tests {
        assert!(test["name"].is_string() && test["output"].is_string());
        assert!(test["score"].is_number() && test["max_score"] == 10.0);
        assert_eq!(test["visibility"], "visible");
    }
    assert_eq!(tests[0]["name"], "shadows.png (shadows.toml)");
    assert_eq!(tests[0]["score"], 10.0);
    let partial = tests[1]["score"].as_f64().unwrap();
    assert!(partial > 0.0 && partial < 10.0, "{partial}");
    // The total is the tests' sum.
    assert_eq!(gradescope["score"], 10.0 + partial);
    let said = tests[1]["output"].as_str().unwrap();
    assert!(said.contains("phong-not-blinn"), "{said}");
    assert!(
        said.starts_with(&format!(
            "{} of 10 points: your image differs; partial credit",
            number(partial)
        )),
        "{said}"
    );

    // PrairieLearn's (its external grading documentation): gradable, a
    // score from 0 to 1, tests with points, max_points and images as data
    // URLs; under 1 MB.
    let text = fs::read(&pl).unwrap();
    assert!(text.len() < 1_000_000, "{} bytes", text.len());
    let prairie: Value = serde_json::from_slice(&text).unwrap();
    assert_eq!(prairie["gradable"], true);
    let score = prairie["score"].as_f64().unwrap();
    assert!((score - (10.0 + partial) / 20.0).abs() < 1e-12, "{score}");
    let tests = prairie["tests"].as_array().unwrap();
    assert_eq!(tests[0]["points"], 10.0);
    assert_eq!(tests[0]["max_points"], 10.0);
    assert_eq!(tests[1]["points"], partial);
    assert_eq!(tests[1]["message"], "differs: likely phong-not-blinn");
    let images = tests[1]["images"].as_array().unwrap();
    let labels: Vec<_> = images
        .iter()
        .map(|i| i["label"].as_str().unwrap())
        .collect();
    assert_eq!(labels, ["your image", "raystep's render", "FLIP error map"]);
    for image in images {
        let url = image["url"].as_str().unwrap();
        let data = url.strip_prefix("data:image/png;base64,").expect(url);
        use base64::Engine;
        let png = base64::engine::general_purpose::STANDARD
            .decode(data)
            .unwrap();
        let decoded = image::load_from_memory(&png).unwrap();
        assert_eq!((decoded.width(), decoded.height()), (80, 60));
    }

    // And the summary on stdout, scene by scene.
    let summary = stdout(&output);
    let lines: Vec<&str> = summary.lines().collect();
    assert_eq!(
        lines[0],
        format!("A5 test: {} of 20 points", number(10.0 + partial))
    );
    assert!(
        lines[1].starts_with("  shadows.png         10 of 10      matches (FLIP "),
        "{summary}"
    );
    assert!(
        lines[2].starts_with(&format!(
            "  highlights.png  {:>6} of 10      differs, likely phong-not-blinn (FLIP ",
            number(partial)
        )),
        "{summary}"
    );
}

#[test]
fn a_missing_file_is_graded_0_in_the_autograder_files_too() {
    let class = Class::new();
    let folder = class.student(b"empty");
    let gs = class.at("gs.json");
    let output = raystep(&[
        "grade",
        path(&class.at("a5.toml")),
        "--submission",
        path(&folder),
        "--gradescope",
        path(&gs),
    ]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let gradescope = json(&gs);
    assert_eq!(gradescope["score"], 0.0);
    assert_eq!(
        gradescope["tests"][0]["output"],
        "0 of 10 points: not graded, missing: the folder holds no shadows.png.\n"
    );
    assert!(stdout(&output).contains("not graded: missing: the folder holds no highlights.png"));
}

#[test]
fn a_bad_assignment_or_folder_exits_1_before_anything_is_written() {
    let class = Class::new();
    class.hand_in(&class.student(b"ada"), "shadows", "");
    let report = class.at("report");
    let a5 = class.at("a5.toml");
    // A misspelt key, on line 6.
    fs::write(
        &a5,
        ASSIGNMENT.replace("points = 10\nsize", "pionts = 10\nsize"),
    )
    .unwrap();
    let output = class.grade(&["-o", path(&report)]);
    assert_eq!(output.status.code(), Some(1));
    let message = stderr(&output);
    assert!(
        message.starts_with(&format!(
            "error: {}:6:1: unknown field `pionts`",
            a5.display()
        )),
        "{message}"
    );
    assert!(!report.exists());
    // A scene that does not load: its own file, line and column.
    fs::write(&a5, ASSIGNMENT).unwrap();
    fs::write(class.at("shadows.toml"), "[camera]\nfov = 400\n").unwrap();
    let output = class.grade(&["-o", path(&report)]);
    assert_eq!(output.status.code(), Some(1));
    let message = stderr(&output);
    assert!(
        message.starts_with(&format!("error: {}:", class.at("shadows.toml").display())),
        "{message}"
    );
    assert!(!report.exists());
    // Submissions that cannot be read, or hold no student folder.
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    fs::copy(root.join("scenes/shadows.toml"), class.at("shadows.toml")).unwrap();
    for submissions in [class.at("nowhere"), class.at("renders")] {
        let output = raystep(&["grade", path(&a5), path(&submissions), "-o", path(&report)]);
        assert_eq!(output.status.code(), Some(1), "{}", stderr(&output));
        assert!(
            stderr(&output).starts_with("error: "),
            "{}",
            stderr(&output)
        );
        assert!(!report.exists());
    }
    // A command line without -o, or with nothing to grade: 2.
    for args in [
        vec!["grade", path(&a5), path(&report)],
        vec!["grade", path(&a5)],
        vec!["grade", path(&a5), "--gradescope", "x.json"],
    ] {
        assert_eq!(raystep(&args).status.code(), Some(2), "{args:?}");
    }
}

#[test]
fn the_report_never_replaces_an_input_or_a_folder_that_is_not_a_report() {
    let class = Class::new();
    let ada = class.student(b"ada");
    class.hand_in(&ada, "shadows", "");
    let top = class.dir.path();
    // However spelt: the folder of the assignment and scenes, the
    // submissions themselves, a folder inside them, through `..`.
    let refused = [
        (top.join("renders/.."), "it holds the assignment"),
        (top.join("submissions"), "it is the submissions folder"),
        (
            top.join("submissions/../submissions/ada"),
            "it lies inside the submissions folder",
        ),
        (
            top.join("submissions/new"),
            "it lies inside the submissions folder",
        ),
        (top.join("a5.toml"), "it is the assignment"),
    ];
    for (dir, why) in refused {
        let output = class.grade(&["-o", path(&dir)]);
        assert_eq!(output.status.code(), Some(1), "{}", dir.display());
        let message = stderr(&output);
        assert!(message.contains(why), "{}: {message}", dir.display());
    }
    assert!(!top.join("submissions/new").exists());
    assert!(ada.join("shadows.png").exists());
    // A folder of someone's files is not replaced; a previous report is.
    let mine = class.at("mine");
    fs::create_dir(&mine).unwrap();
    fs::write(mine.join("notes.txt"), "keep me").unwrap();
    let output = class.grade(&["-o", path(&mine)]);
    assert_eq!(output.status.code(), Some(1));
    assert!(
        stderr(&output).contains("is not a raystep report"),
        "{}",
        stderr(&output)
    );
    assert_eq!(
        fs::read_to_string(mine.join("notes.txt")).unwrap(),
        "keep me"
    );
    let report = class.at("report");
    assert_eq!(class.grade(&["-o", path(&report)]).status.code(), Some(0));
    fs::write(report.join("stale.txt"), "from before").unwrap();
    assert_eq!(class.grade(&["-o", path(&report)]).status.code(), Some(0));
    // Of the old report only raystep's files are replaced (issue 41).
    assert_eq!(
        fs::read_to_string(report.join("stale.txt")).unwrap(),
        "from before",
        "a file the teacher saved in the report is kept"
    );
    assert!(report.join("grades.json").exists());
    // A results file may not be a submission.
    let output = raystep(&[
        "grade",
        path(&class.at("a5.toml")),
        "--submission",
        path(&ada),
        "--gradescope",
        path(&ada.join("shadows.png")),
    ]);
    assert_eq!(output.status.code(), Some(1));
    assert!(
        stderr(&output).contains("it is the submission"),
        "{}",
        stderr(&output)
    );
    assert!(image::open(ada.join("shadows.png")).is_ok());
}

#[test]
fn a_large_image_of_the_wrong_size_is_told_its_size_not_its_length() {
    // 1024 x 768 of noise: a PNG of about 2.4 MB, past the 80 x 60 × 8
    // bytes and a megabyte that an 80 x 60 PNG can take; its header is
    // read first, and says the size.
    let class = Class::new();
    let folder = class.student(b"big");
    let mut state = 1u32;
    let noise = image::RgbImage::from_fn(1024, 768, |_, _| {
        state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        image::Rgb([(state >> 24) as u8, (state >> 16) as u8, (state >> 8) as u8])
    });
    noise.save(folder.join("shadows.png")).unwrap();
    assert!(fs::metadata(folder.join("shadows.png")).unwrap().len() > 80 * 60 * 8 + (1 << 20));
    let output = raystep(&[
        "grade",
        path(&class.at("a5.toml")),
        "--submission",
        path(&folder),
    ]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert!(
        stdout(&output).contains("not graded: rendered at 1024x768, the assignment asks for 80x60"),
        "{}",
        stdout(&output)
    );
}
