//! The class report: index.html (the class summary, links to grades.csv
//! and grades.json, the mistake histogram per scene with who is in each
//! bar, the table of students × scenes) and one page per student. HTML
//! with its style inline, and on index.html one small inline script that
//! sorts the table (`sorting`); no fonts or files fetched, so it opens from
//! `file://` anywhere, and prints, and reads the same without script.
//! Everything the model holds is escaped: student names are folder names,
//! and untrusted.

mod class_table;
mod escape;
mod frame;
mod histogram;
mod images;
#[cfg(test)]
mod sample_class;
mod sorting;
mod student_page;
mod summary;

use std::fmt::Write;

use self::escape::escape;
use crate::grade::model::{ClassGrades, StudentGrades};

/// Every page of the report: its path relative to REPORT/ and its HTML.
/// index.html first, then `students/<slug>.html` in the class's order.
pub(crate) fn pages(class: &ClassGrades) -> Vec<(String, String)> {
    let mut pages = vec![("index.html".to_string(), index(class))];
    for student in &class.students {
        let title = format!("{} · {}", student.student, class.title);
        let body = student_page::body(class, student);
        pages.push((
            student_page_path(student),
            frame::page(&title, &body, false),
        ));
    }
    pages
}

/// A student's page, relative to REPORT/: the file and the links to it.
fn student_page_path(student: &StudentGrades) -> String {
    format!("students/{}.html", student.slug)
}

/// How the student's files were found, when not as named: the student's
/// notes, then each scene's; `None` when there are none.
fn notes_line(student: &StudentGrades) -> Option<String> {
    let scene_notes = student.scenes.iter().filter_map(|s| s.note.as_ref());
    let notes: Vec<&str> = (student.notes.iter().chain(scene_notes))
        .map(String::as_str)
        .collect();
    (!notes.is_empty()).then(|| escape(&notes.join("; ")))
}

/// The anchor of scene `index` (from 0) on a student's page.
fn scene_anchor(index: usize) -> String {
    format!("scene-{}", index + 1)
}

fn index(class: &ClassGrades) -> String {
    let mut body = format!(
        "<header><h1>{}</h1>{}{}<p class=\"files\">The grades as files: \
         <a href=\"grades.csv\">grades.csv</a> (a row per student, for a spreadsheet) · \
         <a href=\"grades.json\">grades.json</a> (everything, for scripts)</p></header>",
        escape(&class.title),
        summary::summary(class),
        summary::ignored(class)
    );
    body.push_str(
        "<section class=\"histograms\"><h2>Mistakes across the class</h2>\
         <p class=\"note\">Per scene, how many students matched, how many nearly \
         (no mistake named, FLIP under 0.01: a few pixels apart), how many each mistake \
         <code>compare</code> named fits, and how many submissions were refused. \
         A student's image may fit up to three mistakes. Hover over a bar, or open \
         the list under it, to see who.</p><div class=\"cards\">",
    );
    for (index, scene) in class.scenes.iter().enumerate() {
        let _ = write!(
            body,
            "<figure class=\"card\"><figcaption>{}</figcaption>{}{}</figure>",
            escape(&scene.file),
            histogram::svg(class, index),
            histogram::who(class, index)
        );
    }
    body.push_str(
        "</div></section><section><h2>Grades</h2>\
         <p class=\"note\">Each cell: your image, the reference and FLIP's error map \
         (black: equal, yellow: most visible); the points; match, near match, the first \
         mistake <code>compare</code> names (+ how many more), or why the file was refused. \
         A name or a cell opens the student's page; a heading sorts by its column \
         (lowest points first; again, the other way).</p>",
    );
    body.push_str(&class_table::table(class));
    body.push_str("</section>");
    let _ = write!(body, "<script>{}</script>", sorting::SCRIPT);
    frame::page(&format!("{} · class report", class.title), &body, true)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grade::html::sample_class::{class, compared, matched, refused};

    #[test]
    fn every_student_has_a_page_and_index_links_to_it() {
        let class = class(&[
            ("ada", vec![matched(), refused("missing")]),
            ("bob", vec![compared(&["no-ambient"]), matched()]),
            ("cy", vec![refused("not a PNG"), compared(&[])]),
        ]);
        let pages = pages(&class);
        let paths: Vec<&str> = pages.iter().map(|(p, _)| p.as_str()).collect();
        assert_eq!(
            paths,
            [
                "index.html",
                "students/s0.html",
                "students/s1.html",
                "students/s2.html"
            ]
        );
        let index = &pages[0].1;
        for (student, (_, page)) in class.students.iter().zip(&pages[1..]) {
            assert!(index.contains(&format!("href=\"students/{}.html\"", student.slug)));
            assert!(
                page.contains(&format!("<bdi>{}</bdi>", student.student)),
                "{page}"
            );
        }
        // One histogram per scene, one row per student, the files linked.
        assert_eq!(index.matches("<svg class=\"histogram\"").count(), 2);
        assert_eq!(index.matches("<th scope=\"row\"").count(), 3);
        assert!(index.contains("<a href=\"grades.csv\">grades.csv</a>"));
        assert!(index.contains("<a href=\"grades.json\">grades.json</a>"));
    }

    #[test]
    fn a_hostile_name_is_text_everywhere() {
        let name = "<script>alert(\"x\")</script> & 'co' \u{7}\u{fffd}";
        let escaped =
            "&lt;script&gt;alert(&quot;x&quot;)&lt;/script&gt; &amp; &#39;co&#39; \u{2407}\u{fffd}";
        let class = class(&[(name, vec![matched()])]);
        for (path, page) in pages(&class) {
            // The index's own script is the only one.
            let page = page.replace(&format!("<script>{}</script>", sorting::SCRIPT), "");
            assert!(!page.contains("<script"), "{path}: {page}");
            assert!(!page.contains('\u{7}'), "{path}");
            assert!(page.contains(escaped), "{path}: {page}");
        }
        // In the title attribute of the index's link too, and the <title>.
        let index = &pages(&class)[0].1;
        assert!(index.contains(&format!("title=\"{escaped}\"")), "{index}");
        let student = &pages(&class)[1].1;
        assert!(
            student.contains(&format!("<title>{escaped} · A5")),
            "{student}"
        );
    }

    #[test]
    fn the_pages_fetch_nothing_and_only_the_index_sorts() {
        let class = class(&[("ada", vec![compared(&["gamma"])])]);
        for (path, page) in pages(&class) {
            // The SVG's namespace is a name, not a fetch.
            let page = page.replace("xmlns=\"http://www.w3.org/2000/svg\"", "");
            for forbidden in ["http://", "https://", "@import", "<link", "url("] {
                assert!(!page.contains(forbidden), "{path} has {forbidden}");
            }
            // One script, inline, at the end of index.html; none elsewhere.
            let scripts = usize::from(path == "index.html");
            assert_eq!(page.matches("<script").count(), scripts, "{path}");
            if scripts == 1 {
                let script = format!("<script>{}</script></body>", sorting::SCRIPT);
                assert!(page.contains(&script), "{path}");
            }
        }
        // The script reads the page and its URL, and fetches nothing.
        for forbidden in [
            "fetch",
            "XMLHttpRequest",
            "import",
            "eval",
            "innerHTML",
            "src",
        ] {
            assert!(!sorting::SCRIPT.contains(forbidden), "{forbidden}");
        }
    }

    #[test]
    fn the_table_comes_by_name_each_column_sortable() {
        // Byte order would put Zed and _x first; by name: ada, bob, _x, Zed.
        // Totals and cells carry their points for the script.
        let class = class(&[
            ("Zed", vec![matched(), compared(&[])]),
            ("_x", vec![compared(&["gamma"]), matched()]),
            ("ada", vec![refused("missing"), refused("missing")]),
            ("bob", vec![matched(), matched()]),
        ]);
        let index = index(&class);
        let rows: Vec<usize> = ["row-s2", "row-s3", "row-s1", "row-s0"]
            .iter()
            .map(|id| index.find(&format!("<tr id=\"{id}\">")).unwrap())
            .collect();
        assert!(rows.is_sorted(), "{rows:?}");
        for key in ["name", "total", "scene-1", "scene-2"] {
            assert!(index.contains(&format!(" data-sort=\"{key}\">")), "{key}");
        }
        // Zed: 10 + 0; the cells say 10 and 0.
        let zed = &index[index.find("<tr id=\"row-s0\">").unwrap()..];
        let zed = &zed[..zed.find("</tr>").unwrap()];
        assert!(
            zed.contains("<td class=\"total\" data-points=\"10\">"),
            "{zed}"
        );
        assert_eq!(
            zed.matches("<td class=\"cell\" data-points=\"").count(),
            2,
            "{zed}"
        );
        assert!(
            zed.contains("data-points=\"10\"><a class=\"thumbs\""),
            "{zed}"
        );
        assert!(
            zed.contains("data-points=\"0\"><a class=\"thumbs\""),
            "{zed}"
        );
    }
}
