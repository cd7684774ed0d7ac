//! The class report as a browser reads it (issues 23 and 40): a small
//! class graded by `raystep grade`, REPORT/index.html and a student's page
//! opened in headless Chromium, and their DOM read: every student, every
//! scene, the histograms with their hand-counted bars and who is in each,
//! links and images that lead to files of REPORT/, no hostile name turned
//! into markup, the report's one script sorting the table as a heading's
//! link asks (through the URL's fragment), and six scenes fitting a
//! laptop's screen.

use std::ffi::OsStr;
use std::fs;
use std::os::unix::ffi::OsStrExt;
use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::support::chromium::{Chromium, chromium_or_skip};
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
/// "gif" a file that is no PNG, "six" the correct render with six pixels
/// inverted, "swap" the correct render with red and blue swapped).
const CLASS: [(&[u8], &str, &str); 7] = [
    (b"<script>alert(\"x\") & 'co'", "no-ambient", ""),
    (b"Ben", "six", "swap"),
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

/// raystep's render of `scene` at 80x60 under `mistake` ("" for none;
/// "six" and "swap" are the correct render changed as `CLASS` says), made
/// once in `dir`/renders (a UTF-8 path, which a student's folder need not be).
fn render(dir: &Path, scene: &str, mistake: &str) -> PathBuf {
    let out = dir.join(format!("renders/{scene}-{mistake}.png"));
    if out.exists() {
        return out;
    }
    if mistake == "six" || mistake == "swap" {
        let mut image = image::open(render(dir, scene, "")).unwrap().to_rgb8();
        if mistake == "six" {
            // Six pixels of the middle row, 5 apart, each channel v -> 255 - v.
            for x in [10, 15, 20, 25, 30, 35] {
                image
                    .get_pixel_mut(x, 30)
                    .0
                    .iter_mut()
                    .for_each(|v| *v = 255 - *v);
            }
        } else {
            image.pixels_mut().for_each(|p| p.0.swap(0, 2));
        }
        image.save(&out).unwrap();
    } else {
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
    let class: Vec<(&[u8], Vec<&str>)> = CLASS
        .iter()
        .map(|(name, shadows, highlights)| (*name, vec![*shadows, *highlights]))
        .collect();
    grade(dir, ASSIGNMENT, &["shadows", "highlights"], &class)
}

/// Grades `class` (each folder name with what it hands in for each of
/// `scenes`, as `CLASS` says) on `assignment` into `dir`/REPORT, and
/// returns grades.json.
fn grade(dir: &Path, assignment: &str, scenes: &[&str], class: &[(&[u8], Vec<&str>)]) -> Value {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for scene in scenes {
        let file = format!("{scene}.toml");
        fs::copy(root.join("scenes").join(&file), dir.join(&file)).unwrap();
    }
    fs::write(dir.join("a5.toml"), assignment).unwrap();
    let submissions = dir.join("submissions");
    for (name, handed_in) in class {
        let folder = submissions.join(OsStr::from_bytes(name));
        fs::create_dir_all(&folder).unwrap();
        for (scene, handed_in) in scenes.iter().zip(handed_in) {
            let handed_in = *handed_in;
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

/// `dom` holds one script, the report's own: inline (`<script>` with no
/// `src` or any attribute), the sorting function the page runs at its end;
/// no other element is a script.
fn assert_only_the_sorting_script(dom: &str) {
    let opening = "<script>(function () {";
    assert_eq!(dom.matches("<script").count(), 1, "not one script: {dom}");
    let at = dom
        .find(opening)
        .expect("the script is inline, without attributes");
    let end = at + dom[at..].find("</script>").unwrap();
    assert!(dom[at..end].contains("table.grades"), "{}", &dom[at..end]);
    assert_no_script(&format!("{}{}", &dom[..at], &dom[end..]));
}

/// The students' names in the order index.html's rows show them, as
/// grades.json names each row's slug.
fn row_order(dom: &str, grades: &Value) -> Vec<String> {
    let by_slug = |slug: &str| {
        let students = grades["students"].as_array().unwrap();
        let student = students.iter().find(|s| s["slug"] == slug).unwrap();
        student["student"].as_str().unwrap().to_string()
    };
    dom.match_indices("<tr id=\"row-")
        .map(|(at, opening)| {
            let rest = &dom[at + opening.len()..];
            by_slug(&rest[..rest.find('"').unwrap()])
        })
        .collect()
}

/// `dom`'s row of the student with this slug, up to its end.
fn row_of<'a>(dom: &'a str, slug: &str) -> &'a str {
    let row = &dom[dom.find(&format!("<tr id=\"row-{slug}\"")).unwrap()..];
    &row[..row.find("</tr>").unwrap()]
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

    // No name became an element: a second <script> would be a student's.
    assert_only_the_sorting_script(&dom);
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
    // Each scene heads a column (its name a link the script made, to
    // sort by it) and captions a histogram.
    for (n, scene) in ["shadows.toml", "highlights.toml"].iter().enumerate() {
        let key = format!("scene-{}", n + 1);
        assert!(
            dom.contains(&format!(
                "<th scope=\"col\" class=\"scene\" data-sort=\"{key}\"><a class=\"sort\" href=\"#sort={key}\" title=\"Sort by {scene}\">{scene}</a><"
            )),
            "{scene}: {dom}"
        );
        assert!(
            dom.contains(&format!("<figcaption>{scene}</figcaption>")),
            "{scene}"
        );
    }
    // The histograms, counted by hand from CLASS. shadows: ada, caf\xe9 and
    // cy match; Ben's six pixels are a near match (no mistake named, FLIP
    // under 0.01: checked below); bo is flipped-y, the first no-ambient;
    // bad's GIF is refused. highlights: four match; cy is phong-not-blinn;
    // Ben's swapped channels differ with no mistake named; bad handed in
    // nothing.
    assert_eq!(dom.matches("<svg class=\"histogram\"").count(), 2, "{dom}");
    for counts in [
        "<title>match 3, near match 1, flipped-y 1, no-ambient 1, refused 1</title>",
        "<title>match 4, phong-not-blinn 1, no mistake named 1, refused 1</title>",
    ] {
        assert!(dom.contains(counts), "{counts} is not in index.html: {dom}");
    }
    // Who is in each bar: in its tooltip, and in the list under the chart,
    // each name a link to the student's row (by name: ada before caf\xe9).
    let slug = |name: &[u8]| {
        let name = String::from_utf8_lossy(name);
        let student = students
            .iter()
            .find(|s| s["student"] == name.as_ref())
            .unwrap();
        student["slug"].as_str().unwrap().to_string()
    };
    let link = |name: &[u8]| {
        format!(
            "<a href=\"#row-{}\"><bdi>{}</bdi></a>",
            slug(name),
            as_serialised(name)
        )
    };
    for (bar, tooltip, names) in [
        (
            "match",
            "match, 3 students: ada, caf\u{fffd}, cy",
            &[&b"ada"[..], b"caf\xe9", b"cy"][..],
        ),
        ("near match", "near match, 1 student: Ben", &[b"Ben"]),
        ("flipped-y", "flipped-y, 1 student: bo", &[b"bo"]),
        ("refused", "refused, 1 student: bad", &[b"bad"]),
        (
            "no mistake named",
            "no mistake named, 1 student: Ben",
            &[b"Ben"],
        ),
        (
            "phong-not-blinn",
            "phong-not-blinn, 1 student: cy",
            &[b"cy"],
        ),
    ] {
        assert!(
            dom.contains(&format!("<title>{tooltip}</title>")),
            "{tooltip}"
        );
        let links: Vec<String> = names.iter().map(|n| link(n)).collect();
        let listed = format!(
            "<dt>{bar} ({})</dt><dd>{}</dd>",
            names.len(),
            links.join(", ")
        );
        assert!(
            dom.contains(&listed),
            "{listed} is not in index.html: {dom}"
        );
    }
    assert_eq!(dom.matches("<details class=\"who\">").count(), 2);
    // Every such link leads to a row of the table.
    let anchors = attribute_values(&dom, "href");
    let rows: Vec<&&str> = anchors.iter().filter(|h| h.starts_with("#row-")).collect();
    assert!(rows.len() >= 14, "{rows:?}");
    for anchor in rows {
        assert!(
            dom.contains(&format!("<tr id=\"{}\"", &anchor[1..])),
            "{anchor}"
        );
    }
    // Ben's six pixels are a near match, his swapped channels differ: the
    // report's own FLIP means say so (0.0048 and 0.21 when this was
    // written: under and over 0.01), and neither names a mistake.
    let ben = students.iter().find(|s| s["student"] == "Ben").unwrap();
    let (six, swap) = (&ben["scenes"][0], &ben["scenes"][1]);
    assert!(six["flip_mean"].as_f64().unwrap() < 0.01, "{six}");
    assert!(swap["flip_mean"].as_f64().unwrap() > 0.01, "{swap}");
    assert_eq!(six["mistakes"], serde_json::json!([]));
    assert_eq!(swap["mistakes"], serde_json::json!([]));
    let ben_row = row_of(&dom, &slug(b"Ben"));
    assert_eq!(
        ben_row
            .matches("<span class=\"tag near\" title=\"FLIP 0.00")
            .count(),
        1,
        "{ben_row}"
    );
    assert!(ben_row.contains(">near match</span>"), "{ben_row}");
    assert!(
        ben_row.contains("<span class=\"tag unexplained\">differs</span>"),
        "{ben_row}"
    );
    // The summary counts refusals in students, then files: bad's two.
    assert!(
        dom.contains(" · 1 student had a file refused (2 files)</p>"),
        "{dom}"
    );
    // The grades as files, linked (links_lead_to_files: they are there).
    assert!(
        dom.contains("<a href=\"grades.csv\">grades.csv</a>"),
        "{dom}"
    );
    assert!(
        dom.contains("<a href=\"grades.json\">grades.json</a>"),
        "{dom}"
    );
    // grades.csv opens with UTF-8's byte-order mark (EF BB BF), then its
    // header; caf\xe9's name is U+FFFD, EF BF BD, in UTF-8.
    let csv = fs::read(report.join("grades.csv")).unwrap();
    assert!(csv.starts_with(b"\xef\xbb\xbfstudent,shadows.png points,"));
    assert!(csv.windows(8).any(|w| w == b"\r\ncaf\xef\xbf\xbd"));
    // One row per student, two scene cells in each.
    assert_eq!(dom.matches("<th scope=\"row\"").count(), CLASS.len());
    assert_eq!(
        dom.matches("<td class=\"cell\" data-points=").count(),
        2 * CLASS.len()
    );
    links_lead_to_files(&dom, &index, &report);

    sorted_as_the_fragment_says(&browser, &index, &dom, &grades);

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

/// The rows' order: by name at first (case and punctuation aside, where
/// grades.json keeps the folder names' bytes), then as `#sort=` asks.
fn sorted_as_the_fragment_says(browser: &Chromium, index: &Path, dom: &str, grades: &Value) {
    let names = |order: &[&str]| -> Vec<String> { order.iter().map(|n| n.to_string()).collect() };
    let script = "<script>alert(\"x\") & 'co'";
    let cafe = "caf\u{fffd}";
    // grades.json (and grades.csv) in byte order: `<` is 0x3C, `B` 0x42.
    let json_order: Vec<&str> = grades["students"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["student"].as_str().unwrap())
        .collect();
    assert_eq!(json_order, [script, "Ben", "ada", "bad", "bo", cafe, "cy"]);
    // The page by name, by letters: ada, bad, Ben, bo, caf, cy, then
    // "scriptalertxco" under s. The same in the file as written (no
    // script run) and in the DOM after the script ran.
    let by_name = names(&["ada", "bad", "Ben", "bo", cafe, "cy", script]);
    assert_eq!(row_order(dom, grades), by_name);
    let written = fs::read_to_string(index).unwrap();
    assert_eq!(row_order(&written, grades), by_name);
    assert!(
        dom.contains(
            "data-sort=\"name\" aria-sort=\"ascending\"><a class=\"sort\" href=\"#sort=-name\""
        ),
        "{dom}"
    );
    // Totals (all or nothing, 10 a scene): <script> 10, Ben 0, ada 20,
    // bad 0, bo 10, caf\xe9 20, cy 10. Lowest first, ties by name.
    let by_total = names(&["bad", "Ben", "bo", "cy", script, "ada", cafe]);
    let dom = browser.dump_dom_at(index, "#sort=total");
    assert_only_the_sorting_script(&dom);
    assert_eq!(row_order(&dom, grades), by_total);
    // The Total heading says how it sorts, and its link now goes the other
    // way; the others sort their own way.
    assert!(
        dom.contains(
            "data-sort=\"total\" aria-sort=\"ascending\"><a class=\"sort\" href=\"#sort=-total\""
        ),
        "{dom}"
    );
    assert!(
        dom.contains("data-sort=\"name\"><a class=\"sort\" href=\"#sort=name\""),
        "{dom}"
    );
    // Highest first, ties still by name.
    let dom = browser.dump_dom_at(index, "#sort=-total");
    assert_eq!(
        row_order(&dom, grades),
        names(&["ada", cafe, "bo", "cy", script, "bad", "Ben"])
    );
    // highlights (scene 2): 0 for bad (nothing), Ben (swap), cy
    // (phong-not-blinn); 10 for the others.
    let dom = browser.dump_dom_at(index, "#sort=scene-2");
    assert_eq!(
        row_order(&dom, grades),
        names(&["bad", "Ben", "cy", "ada", "bo", cafe, script])
    );
    let dom = browser.dump_dom_at(index, "#sort=-name");
    let mut backwards = by_name.clone();
    backwards.reverse();
    assert_eq!(row_order(&dom, grades), backwards);
    // A fragment that names no column is name order.
    let dom = browser.dump_dom_at(index, "#sort=nothing");
    assert_eq!(row_order(&dom, grades), by_name);
}

/// An assignment of six scenes at 80x60, all or nothing.
const SIX_SCENES: [&str; 6] = [
    "shadows",
    "highlights",
    "mirrors",
    "glass",
    "attenuation",
    "two-lights",
];

#[test]
fn six_scenes_fit_a_laptop_screen() {
    let Some(browser) = chromium_or_skip("grade_report") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let mut assignment = String::from("title = \"Six scenes\"\n");
    for scene in SIX_SCENES {
        assignment += &format!(
            "\n[[scene]]\nfile = \"{scene}.toml\"\nsubmit = \"{scene}.png\"\npoints = 10\nsize = [80, 60]\n"
        );
    }
    // Correct images, nothing (a refusal's reason in every cell), and the
    // catalogue's longest name with another (a long tag, "+1").
    let class: Vec<(&[u8], Vec<&str>)> = vec![
        (b"ada", vec![""; 6]),
        (b"Bartholomew Featherstonehaugh-Cholmondeley", vec!["-"; 6]),
        (b"cy", vec!["refraction-outward-normal"; 6]),
    ];
    grade(dir.path(), &assignment, &SIX_SCENES, &class);
    let index = dir.path().join("REPORT/index.html");
    // A 1366-pixel screen less a 15-pixel scroll bar (the screenshot hides
    // it), tall enough for the whole table. The page keeps 18 pixels of
    // margin at its right: a table that fits leaves the last 12 columns
    // of pixels white from top to bottom; one cut by the window's edge
    // draws its borders and heading there.
    let (width, height) = (1351, 2000);
    let shot = dir.path().join("six.png");
    browser.screenshot(&index, &shot, (width, height));
    let pixels = image::open(&shot).unwrap().to_rgb8();
    assert_eq!(pixels.dimensions(), (width, height));
    let heading = [0xee, 0xf1, 0xf5]; // the table heading's background
    let rightmost_heading = pixels
        .enumerate_pixels()
        .filter(|(_, _, p)| p.0 == heading)
        .map(|(x, _, _)| x)
        .max()
        .expect("the table's heading is on the screen");
    assert!(rightmost_heading > width / 2, "{rightmost_heading}");
    for x in width - 12..width {
        for y in 0..height {
            let p = pixels.get_pixel(x, y).0;
            assert_eq!(
                p,
                [255, 255, 255],
                "pixel ({x}, {y}) is not the page's white: the table runs past the screen's edge (its heading reaches x = {rightmost_heading})"
            );
        }
    }
}
