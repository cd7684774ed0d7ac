//! Issue 40 through `raystep grade`: a correct render from another tracer
//! (its eye moved by 1e-5, or anti-aliased 2 x 2) scores full points and a
//! mistake's render none; the assignment's knobs (`tolerance`,
//! `far_off_allowed`, `antialiasing`, at the top or per scene) decide the
//! edge cases; an `[[override]]` sets a grade by hand, shown as such, with
//! its reason, in every output.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::Output;

use serde_json::Value;

use crate::support::renders::{eye_moved, render_to, supersampled};
use crate::support::{json, path, raystep, stderr, stdout};

/// A folder with `scenes` copied from `scenes/`, an assignment, renders
/// and a submissions folder.
struct Class {
    dir: tempfile::TempDir,
}

impl Class {
    fn new(scenes: &[&str]) -> Class {
        let dir = tempfile::tempdir().unwrap();
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
        for scene in scenes {
            fs::copy(root.join(scene), dir.path().join(scene)).unwrap();
        }
        for sub in ["renders", "submissions"] {
            fs::create_dir(dir.path().join(sub)).unwrap();
        }
        Class { dir }
    }

    fn at(&self, relative: &str) -> PathBuf {
        self.dir.path().join(relative)
    }

    /// The student's folder, created.
    fn student(&self, name: &str) -> PathBuf {
        let folder = self.at("submissions").join(name);
        fs::create_dir_all(&folder).unwrap();
        folder
    }

    /// `raystep grade ASSIGNMENT submissions/ -o REPORT` with `text` as the
    /// assignment.
    fn grade(&self, text: &str, report: &str) -> Output {
        let assignment = self.at("assignment.toml");
        fs::write(&assignment, text).unwrap();
        raystep(&[
            "grade",
            path(&assignment),
            path(&self.at("submissions")),
            "-o",
            path(&self.at(report)),
        ])
    }
}

fn student<'a>(grades: &'a Value, name: &str) -> &'a Value {
    (grades["students"].as_array().unwrap().iter())
        .find(|s| s["student"] == name)
        .unwrap_or_else(|| panic!("no student {name}"))
}

fn points(student: &Value) -> Vec<f64> {
    (student["scenes"].as_array().unwrap().iter())
        .map(|s| s["points"].as_f64().unwrap())
        .collect()
}

/// The teaching scenes, by file name.
const TEACHING: [&str; 9] = [
    "attenuation.toml",
    "glass.toml",
    "highlights.toml",
    "mirrors.toml",
    "polygons.toml",
    "prism.toml",
    "seven-rays.toml",
    "shadows.toml",
    "two-lights.toml",
];

#[test]
fn another_tracers_correct_renders_score_full_points_and_mistakes_none() {
    // Every teaching scene at its own size, 10 points, all or nothing. Four
    // students: `eye` hands in renders with the eye moved by 1e-5 along x;
    // `aa` raystep's renders averaged 2 x 2; `corner` pixel-corner's; `wrap`
    // byte-wrap's. On main `eye` lost prism.toml (one silhouette pixel 200
    // steps off) and `aa` every scene.
    let class = Class::new(&TEACHING);
    let mut assignment = String::from("title = \"fair\"\n");
    let (eye, aa, corner, wrap) = (
        class.student("eye"),
        class.student("aa"),
        class.student("corner"),
        class.student("wrap"),
    );
    // Where byte-wrap's render is raystep's own, `wrap` keeps the points.
    let mut wrap_expected = Vec::new();
    let mut eye_differs = 0;
    for file in TEACHING {
        let scene = class.at(file);
        let stem = file.trim_end_matches(".toml");
        assignment +=
            &format!("[[scene]]\nfile = {file:?}\nsubmit = \"{stem}.png\"\npoints = 10\n");
        let loaded = raystep_engine::scene::load(&scene).unwrap();
        let size = (loaded.width, loaded.height);
        let ours = class.at(&format!("renders/{stem}.png"));
        render_to(&scene, &ours, size, &[]);
        let moved = eye_moved(&scene, &class.at("renders"), 0, 1e-5);
        let submitted = eye.join(format!("{stem}.png"));
        render_to(&moved, &submitted, size, &[]);
        eye_differs += usize::from(fs::read(&ours).unwrap() != fs::read(&submitted).unwrap());
        supersampled(&scene, &class.at("renders"), size)
            .save(aa.join(format!("{stem}.png")))
            .unwrap();
        render_to(
            &scene,
            &corner.join(format!("{stem}.png")),
            size,
            &["--mistake", "pixel-corner"],
        );
        let wrapped = wrap.join(format!("{stem}.png"));
        render_to(&scene, &wrapped, size, &["--mistake", "byte-wrap"]);
        let same =
            image::open(&ours).unwrap().into_rgb8() == image::open(&wrapped).unwrap().into_rgb8();
        wrap_expected.push(if same { 10.0 } else { 0.0 });
    }
    // The test can fail: moving the eye changes bytes on several scenes,
    // and byte-wrap changes glass.toml and highlights.toml.
    assert!(eye_differs >= 5, "{eye_differs}");
    assert_eq!(wrap_expected.iter().filter(|&&p| p == 0.0).count(), 2);
    let output = class.grade(&assignment, "report");
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let grades = json(&class.at("report/grades.json"));
    assert_eq!(points(student(&grades, "eye")), [10.0; 9]);
    let anti_aliased = student(&grades, "aa");
    assert_eq!(points(anti_aliased), [10.0; 9]);
    for scene in anti_aliased["scenes"].as_array().unwrap() {
        assert_eq!(scene["anti_aliased"], true);
        assert!(
            scene["report_text"]
                .as_str()
                .unwrap()
                .contains("anti-aliased")
        );
    }
    // The class table says it under the points.
    let index = fs::read_to_string(class.at("report/index.html")).unwrap();
    assert_eq!(
        index
            .matches("<div class=\"flip\">anti-aliased</div>")
            .count(),
        9
    );
    assert_eq!(points(student(&grades, "corner")), [0.0; 9]);
    assert_eq!(points(student(&grades, "wrap")), wrap_expected);
    // The rule each scene was graded by: the defaults.
    for sheet in grades["scenes"].as_array().unwrap() {
        assert_eq!(
            [
                &sheet["tolerance"],
                &sheet["far_off_allowed"],
                &sheet["antialiasing"]
            ],
            [&Value::from(3), &Value::from(0), &Value::from(true)]
        );
    }
}

/// shadows.toml at 80 x 60, 10 points, with `top` before the scene and
/// `scene` in it.
fn shadows_assignment(top: &str, scene: &str) -> String {
    format!(
        "{top}\n[[scene]]\nfile = \"shadows.toml\"\nsubmit = \"shadows.png\"\npoints = 10\nsize = [80, 60]\n{scene}\n"
    )
}

#[test]
fn the_assignment_decides_anti_aliasing_far_off_pixels_and_the_tolerance() {
    // Three students on shadows.toml at 80 x 60: `aa` hands in raystep's
    // render averaged 2 x 2 (250 pixels past 3 steps, 5.2%, all
    // blends); `far` raystep's render with two floor pixels magenta, far
    // from every value around them (green 0 where the floor has 60 and
    // more); `lossy` raystep's render with every channel moved 5 steps up
    // or down (a lossy codec's noise: every pixel past 3 steps, none past
    // 5).
    let class = Class::new(&["shadows.toml"]);
    let scene = class.at("shadows.toml");
    let ours = class.at("renders/shadows.png");
    render_to(&scene, &ours, (80, 60), &[]);
    let ours = image::open(&ours).unwrap().into_rgb8();
    supersampled(&scene, &class.at("renders"), (80, 60))
        .save(class.student("aa").join("shadows.png"))
        .unwrap();
    let mut far = ours.clone();
    for (x, y) in [(20, 52), (60, 55)] {
        let floor = far.get_pixel(x, y).0;
        assert!(floor[1] >= 60, "{floor:?}");
        far.put_pixel(x, y, image::Rgb([255, 0, 255]));
    }
    far.save(class.student("far").join("shadows.png")).unwrap();
    let mut lossy = ours.clone();
    for (x, y, p) in lossy.enumerate_pixels_mut() {
        for c in &mut p.0 {
            // Up where x + y is even, down where odd, and away from the ends.
            *c = if (x + y) % 2 == 0 {
                c.saturating_add(5).min(250)
            } else {
                c.saturating_sub(5).max(5)
            };
        }
    }
    lossy
        .save(class.student("lossy").join("shadows.png"))
        .unwrap();
    let graded = |top: &str, scene: &str, report: &str| -> Value {
        let output = class.grade(&shadows_assignment(top, scene), report);
        assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
        json(&class.at(&format!("{report}/grades.json")))
    };
    let scores = |grades: &Value| -> Vec<f64> {
        ["aa", "far", "lossy"]
            .map(|s| points(student(grades, s))[0])
            .to_vec()
    };
    // The defaults: anti-aliasing matches, no far-off pixel, 3 steps.
    let defaults = graded("", "", "defaults");
    assert_eq!(scores(&defaults), [10.0, 0.0, 0.0]);
    // At the top, for every scene: anti-aliasing refused, two far-off
    // pixels allowed, 5 steps of tolerance.
    let top = "antialiasing = false\nfar_off_allowed = 2\ntolerance = 5";
    let lenient = graded(top, "", "top");
    assert_eq!(scores(&lenient), [0.0, 10.0, 10.0]);
    let sheet = &lenient["scenes"][0];
    assert_eq!(
        [
            &sheet["tolerance"],
            &sheet["far_off_allowed"],
            &sheet["antialiasing"]
        ],
        [&Value::from(5), &Value::from(2), &Value::from(false)]
    );
    // The scene's own win over the top's: anti-aliasing accepted, one
    // far-off pixel (of two), 4 steps (of 5).
    let own = graded(
        top,
        "antialiasing = true\nfar_off_allowed = 1\ntolerance = 4",
        "scene",
    );
    assert_eq!(scores(&own), [10.0, 0.0, 0.0]);
    let far = &student(&own, "far")["scenes"][0];
    assert_eq!(far["compare"]["metrics"]["far_off_pixels"], 2);
    assert!(
        far["report_text"]
            .as_str()
            .unwrap()
            .contains("but 2 pixels differ by more than 32 (a match allows 1):"),
        "{far}"
    );
    // A bad knob is refused at its line and column before anything is
    // written.
    let output = class.grade(&shadows_assignment("tolerance = 40", ""), "bad");
    assert_eq!(output.status.code(), Some(1));
    assert!(
        stderr(&output).contains(&format!("{}:1:13: ", class.at("assignment.toml").display())),
        "{}",
        stderr(&output)
    );
    assert!(!class.at("bad").exists());
}

/// The class of the override test: shadows (all or nothing) and
/// highlights, 80 x 60; ada hands in highlights only, bo both.
fn override_class() -> Class {
    let class = Class::new(&["shadows.toml", "highlights.toml"]);
    for (name, scenes) in [
        ("ada", &["highlights"][..]),
        ("bo", &["shadows", "highlights"]),
    ] {
        let folder = class.student(name);
        for scene in scenes {
            let toml = class.at(&format!("{scene}.toml"));
            render_to(&toml, &folder.join(format!("{scene}.png")), (80, 60), &[]);
        }
    }
    class
}

const OVERRIDDEN: &str = r#"title = "A5"

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

[[override]]
student = "ada"
scene = "shadows.png"
points = 7.5
reason = "sent by mail <on time>, late"

[[override]]
student = "bo"
scene = "highlights.png"
points = 0
reason = "copied"
"#;

#[test]
fn an_override_sets_a_grade_by_hand_in_every_output() {
    let class = override_class();
    let output = class.grade(OVERRIDDEN, "report");
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    // ada: shadows missing (0), set to 7.5; highlights correct, 10: 17.5.
    // bo: both correct (10 + 10), highlights set to 0: 10.
    let grades = json(&class.at("report/grades.json"));
    let (ada, bo) = (student(&grades, "ada"), student(&grades, "bo"));
    assert_eq!(
        (points(ada), &ada["total"]),
        (vec![7.5, 10.0], &Value::from(17.5))
    );
    assert_eq!(
        (points(bo), &bo["total"]),
        (vec![10.0, 0.0], &Value::from(10.0))
    );
    let by_hand = &ada["scenes"][0];
    assert_eq!(
        by_hand["override"]["reason"],
        "sent by mail <on time>, late"
    );
    assert_eq!(by_hand["override"]["graded_points"], 0.0);
    assert!(by_hand["refused"].as_str().unwrap().starts_with("missing"));
    assert_eq!(bo["scenes"][1]["override"]["graded_points"], 10.0);
    assert_eq!(ada["scenes"][1]["override"], Value::Null);
    // The mean of 17.5 and 10.
    assert!(
        stdout(&output).contains("mean 13.75 of 20 points"),
        "{}",
        stdout(&output)
    );
    // grades.csv: the points as set; after the total, a column per scene
    // with the graded points and the reason.
    let csv = fs::read_to_string(class.at("report/grades.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert!(
        lines[0].ends_with(",total,shadows.png override,highlights.png override"),
        "{csv}"
    );
    assert!(lines[1].starts_with("ada,7.5,,,,missing"), "{csv}");
    assert!(
        lines[1].ends_with(",17.5,\"graded 0: sent by mail <on time>, late\","),
        "{csv}"
    );
    assert!(lines[2].ends_with(",10,,graded 10: copied"), "{csv}");
    // The class table and the student's page say so where the points are.
    let marked =
        "<div class=\"overridden\">overridden: sent by mail &lt;on time&gt;, late (graded 0)</div>";
    let index = fs::read_to_string(class.at("report/index.html")).unwrap();
    assert!(
        index.contains(&format!(
            "<b>7.5</b>/10</span> <span class=\"tag refused\">refused</span></div>{marked}"
        )),
        "{index}"
    );
    let slug = ada["slug"].as_str().unwrap();
    let page = fs::read_to_string(class.at(&format!("report/students/{slug}.html"))).unwrap();
    assert!(
        page.contains(
            "<p class=\"overridden\">overridden: sent by mail &lt;on time&gt;, late (graded 0)</p>"
        ),
        "{page}"
    );

    // One submission (an autograder's): ada's folder takes ada's override.
    let (gs, pl) = (class.at("gs.json"), class.at("pl.json"));
    let output = raystep(&[
        "grade",
        path(&class.at("assignment.toml")),
        "--submission",
        path(&class.at("submissions/ada")),
        "--gradescope",
        path(&gs),
        "--prairielearn",
        path(&pl),
    ]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let gradescope = json(&gs);
    assert_eq!(gradescope["score"], 17.5);
    assert_eq!(
        gradescope["tests"][0]["output"],
        "7.5 of 10 points, overridden by hand: sent by mail <on time>, late (graded 0 of 10 points): not graded, missing: the folder holds no shadows.png.\n"
    );
    let prairie = json(&pl);
    assert_eq!(prairie["tests"][0]["points"], 7.5);
    assert_eq!(
        prairie["tests"][0]["message"],
        "not graded: missing: the folder holds no shadows.png; overridden by hand: sent by mail <on time>, late"
    );
    assert!(
        stdout(&output).contains("7.5 of 10      not graded: missing: the folder holds no shadows.png; overridden by hand: sent by mail <on time>, late (graded 0)"),
        "{}",
        stdout(&output)
    );
}

#[test]
fn an_override_for_a_student_not_in_the_class_is_refused_at_its_line() {
    let class = override_class();
    let text = OVERRIDDEN.replace("student = \"bo\"", "student = \"zed\"");
    let output = class.grade(&text, "report");
    assert_eq!(output.status.code(), Some(1));
    // `student = "zed"` is line 23, its value from column 11.
    let said = stderr(&output);
    assert!(
        said.contains(&format!(
            "{}:23:11: ",
            class.at("assignment.toml").display()
        )) && said.contains("no student folder named \"zed\" in the class"),
        "{said}"
    );
    assert!(!class.at("report").exists());
    // One submission is not the class: the override for another is left.
    let output = raystep(&[
        "grade",
        path(&class.at("assignment.toml")),
        "--submission",
        path(&class.at("submissions/bo")),
    ]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert!(
        stdout(&output).starts_with("A5: 20 of 20 points"),
        "{}",
        stdout(&output)
    );
}
