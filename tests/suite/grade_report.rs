//! The class report as a browser reads it (issue 23): a small class graded
//! by `raystep grade`, REPORT/index.html and a student's page opened in
//! headless Chromium, and their DOM read: every student, every scene, the
//! histograms with their hand-counted bars, links and images that lead to
//! files of REPORT/, and no hostile name turned into markup.

use std::ffi::OsStr;
use std::fs;
use std::os::unix::ffi::OsStrExt;
use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::support::chromium::chromium_or_skip;
use crate::support::{raystep, stderr};

const ASSIGNMENT: &str = r#"title = "A5 <report> test"

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

/// The class, by folder name (bytes; no `/`, which a folder name cannot
/// hold): what each hands in for shadows and
/// highlights, as `render --mistake` names ("" correct, "-" nothing,
/// "gif" a file that is no PNG).
const CLASS: [(&[u8], &str, &str); 6] = [
    (b"<script>alert(\"x\") & 'co'", "no-ambient", ""),
    (b"ada", "", ""),
    (b"bad", "gif", "-"),
    (b"bo", "flipped-y", ""),
    (b"caf\xe9", "", ""),
    (b"cy", "", "phong-not-blinn"),
];

/// How each name reads in the DOM as Chromium serialises a text node:
/// invalid UTF-8 read as U+FFFD, then `&`, `<` and `>` as entities.
fn as_serialised(name: &[u8]) -> String {
    String::from_utf8_lossy(name)
        .replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// raystep's render of `scene` at 80x60 under `mistake` ("" for none), made
/// once in `dir`/renders (a UTF-8 path, which a student's folder need not be).
fn render(dir: &Path, scene: &str, mistake: &str) -> PathBuf {
    let out = dir.join(format!("renders/{scene}-{mistake}.png"));
    if !out.exists() {
        fs::create_dir_all(out.parent().unwrap()).unwrap();
        let scene_file = dir.join(format!("{scene}.toml"));
        let (scene_file, path) = (scene_file.to_str().unwrap(), out.to_str().unwrap());
        let mut args = vec!["render", scene_file, "-o", path, "--size", "80x60"];
        if !mistake.is_empty() {
            args.extend(["--mistake", mistake]);
        }
        let rendered = raystep(&args);
        assert!(rendered.status.success(), "{}", stderr(&rendered));
    }
    out
}

/// Grades the class into `dir`/REPORT and returns grades.json.
fn graded_class(dir: &Path) -> Value {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for scene in ["shadows.toml", "highlights.toml"] {
        fs::copy(root.join("scenes").join(scene), dir.join(scene)).unwrap();
    }
    fs::write(dir.join("a5.toml"), ASSIGNMENT).unwrap();
    let submissions = dir.join("submissions");
    for (name, shadows, highlights) in CLASS {
        let folder = submissions.join(OsStr::from_bytes(name));
        fs::create_dir_all(&folder).unwrap();
        for (scene, handed_in) in [("shadows", shadows), ("highlights", highlights)] {
            let png = folder.join(format!("{scene}.png"));
            match handed_in {
                "-" => {}
                "gif" => fs::write(&png, "GIF89a").unwrap(),
                mistake => {
                    fs::copy(render(dir, scene, mistake), &png).unwrap();
                }
            }
        }
    }
    let report = dir.join("REPORT");
    let graded = raystep(&[
        "grade",
        dir.join("a5.toml").to_str().unwrap(),
        submissions.to_str().unwrap(),
        "-o",
        report.to_str().unwrap(),
    ]);
    assert!(graded.status.success(), "{}", stderr(&graded));
    serde_json::from_slice(&fs::read(report.join("grades.json")).unwrap()).unwrap()
}

/// No element of `dom` is a script: a name made markup would be one.
fn assert_no_script(dom: &str) {
    if let Some(at) = dom.find("<script") {
        let mut start = at.saturating_sub(80);
        while !dom.is_char_boundary(start) {
            start -= 1;
        }
        let around: String = dom[start..].chars().take(200).collect();
        panic!("a <script> element in the DOM: ...{around}...");
    }
}

/// Every value of `attribute` in `dom` (as `attribute="..."`).
fn attribute_values<'a>(dom: &'a str, attribute: &str) -> Vec<&'a str> {
    let opening = format!(" {attribute}=\"");
    dom.match_indices(&opening)
        .map(|(at, _)| {
            let rest = &dom[at + opening.len()..];
            &rest[..rest.find('"').unwrap()]
        })
        .collect()
}

/// `value` with its `%XX` escapes decoded.
fn percent_decoded(value: &str) -> Vec<u8> {
    let bytes = value.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            out.push(u8::from_str_radix(&value[i + 1..i + 3], 16).unwrap());
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    out
}

/// Each `href` and `src` of the page at `page` names a file of REPORT/
/// (fragments and the page's own folder taken into account).
fn links_lead_to_files(dom: &str, page: &Path, report: &Path) {
    let folder = page.parent().unwrap();
    let mut checked = 0;
    for value in [attribute_values(dom, "href"), attribute_values(dom, "src")].concat() {
        let file = value.split('#').next().unwrap();
        if file.is_empty() {
            continue; // an anchor on the page itself
        }
        let relative = String::from_utf8(percent_decoded(file)).unwrap();
        let target = fs::canonicalize(folder.join(&relative))
            .unwrap_or_else(|e| panic!("{} links to {value}: {e}", page.display()));
        assert!(target.starts_with(report) && target.is_file(), "{value}");
        checked += 1;
    }
    assert!(checked > 0, "{}: no links", page.display());
}

#[test]
fn the_report_opened_in_a_browser_shows_every_student_scene_and_histogram() {
    let Some(browser) = chromium_or_skip("grade_report") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let grades = graded_class(dir.path());
    let report = fs::canonicalize(dir.path().join("REPORT")).unwrap();
    let index = report.join("index.html");
    let dom = browser.dump_dom(&index);

    // No name became an element: the only <script> would be a student's.
    assert_no_script(&dom);
    assert!(dom.contains("<h1>A5 &lt;report&gt; test</h1>"), "{dom}");
    let students = grades["students"].as_array().unwrap();
    assert_eq!(students.len(), CLASS.len());
    for (name, _, _) in CLASS {
        let shown = format!("<bdi>{}</bdi>", as_serialised(name));
        assert!(dom.contains(&shown), "{shown} is not in index.html");
    }
    for student in students {
        let page = format!("students/{}.html", student["slug"].as_str().unwrap());
        assert!(
            dom.contains(&format!("href=\"{page}\"")),
            "no link to {page}"
        );
        assert!(report.join(&page).is_file(), "{page}");
    }
    // Each scene heads a column and captions a histogram.
    for scene in ["shadows.toml", "highlights.toml"] {
        assert!(
            dom.contains(&format!("<th scope=\"col\" class=\"scene\">{scene}<")),
            "{scene}"
        );
        assert!(
            dom.contains(&format!("<figcaption>{scene}</figcaption>")),
            "{scene}"
        );
    }
    // The histograms, counted by hand from CLASS. shadows: ada, caf\xe9 and
    // cy match; bo is flipped-y, the first no-ambient; bad's GIF is refused.
    // highlights: four match; cy is phong-not-blinn; bad handed in nothing.
    assert_eq!(dom.matches("<svg class=\"histogram\"").count(), 2, "{dom}");
    for counts in [
        "<title>match 3, flipped-y 1, no-ambient 1, refused 1</title>",
        "<title>match 4, phong-not-blinn 1, refused 1</title>",
    ] {
        assert!(dom.contains(counts), "{counts} is not in index.html: {dom}");
    }
    // One row per student, two scene cells in each.
    assert_eq!(dom.matches("<th scope=\"row\"").count(), CLASS.len());
    assert_eq!(dom.matches("<td class=\"cell\">").count(), 2 * CLASS.len());
    links_lead_to_files(&dom, &index, &report);

    // Drawn, not only parsed: a laptop's first screen holds the bars in
    // the style's colours, the match green #1e7b34 and the refused red
    // #b3261e (the cells' tags are further down).
    let shot = dir.path().join("index.png");
    browser.screenshot(&index, &shot, (1366, 768));
    let pixels = image::open(&shot).unwrap().to_rgb8();
    for colour in [[0x1e, 0x7b, 0x34], [0xb3, 0x26, 0x1e]] {
        assert!(
            pixels.pixels().any(|p| p.0 == colour),
            "no pixel of {colour:?} in the screenshot"
        );
    }

    // The first student's page: the name, both scenes, the report's text.
    let hostile = &students[0];
    assert_eq!(
        hostile["student"],
        String::from_utf8_lossy(CLASS[0].0).as_ref()
    );
    let page = report.join(format!(
        "students/{}.html",
        hostile["slug"].as_str().unwrap()
    ));
    let dom = browser.dump_dom(&page);
    assert_no_script(&dom);
    assert!(
        dom.contains(&format!(
            "<h1 class=\"name\"><bdi>{}</bdi></h1>",
            as_serialised(CLASS[0].0)
        )),
        "{dom}"
    );
    for (anchor, scene) in [("scene-1", "shadows.toml"), ("scene-2", "highlights.toml")] {
        assert!(
            dom.contains(&format!(
                "<section class=\"scene\" id=\"{anchor}\"><h2>{scene} "
            )),
            "{dom}"
        );
    }
    assert!(
        dom.contains("<span class=\"tag mistake\">no-ambient</span>"),
        "{dom}"
    );
    assert!(
        dom.contains("<pre class=\"report\">shadows.png against shadows.toml"),
        "{dom}"
    );
    links_lead_to_files(&dom, &page, &report);
}
