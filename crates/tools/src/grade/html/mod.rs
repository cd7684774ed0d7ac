//! The class report: index.html (the class summary, the mistake histogram
//! per scene, the table of students × scenes) and one page per student.
//! Plain HTML with its style inline: no script, no fonts or files fetched,
//! so it opens from `file://` anywhere, and prints. Everything the model
//! holds is escaped: student names are folder names, and untrusted.

mod class_table;
mod escape;
mod frame;
mod histogram;
mod images;
#[cfg(test)]
mod sample_class;
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
        "<header><h1>{}</h1>{}{}</header>",
        escape(&class.title),
        summary::summary(class),
        summary::ignored(class)
    );
    body.push_str(
        "<section class=\"histograms\"><h2>Mistakes across the class</h2>\
         <p class=\"note\">Per scene, how many students matched, how many each mistake \
         <code>compare</code> named fits, and how many submissions were refused. \
         A student's image may fit up to three mistakes.</p><div class=\"cards\">",
    );
    for (index, scene) in class.scenes.iter().enumerate() {
        let _ = write!(
            body,
            "<figure class=\"card\"><figcaption>{}</figcaption>{}</figure>",
            escape(&scene.file),
            histogram::svg(class, index)
        );
    }
    body.push_str(
        "</div></section><section><h2>Grades</h2>\
         <p class=\"note\">Each cell: your image, the reference and FLIP's error map \
         (black: equal, yellow: most visible); the points; match, the first mistake \
         <code>compare</code> names (+ how many more), or why the file was refused. \
         A name or a cell opens the student's page.</p>",
    );
    body.push_str(&class_table::table(class));
    body.push_str("</section>");
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
        // One histogram per scene, one row per student.
        assert_eq!(index.matches("<svg class=\"histogram\"").count(), 2);
        assert_eq!(index.matches("<tr><th scope=\"row\"").count(), 3);
    }

    #[test]
    fn a_hostile_name_is_text_everywhere() {
        let name = "<script>alert(\"x\")</script> & 'co' \u{7}\u{fffd}";
        let escaped =
            "&lt;script&gt;alert(&quot;x&quot;)&lt;/script&gt; &amp; &#39;co&#39; \u{2407}\u{fffd}";
        let class = class(&[(name, vec![matched()])]);
        for (path, page) in pages(&class) {
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
    fn the_pages_fetch_nothing_and_run_nothing() {
        let class = class(&[("ada", vec![compared(&["gamma"])])]);
        for (path, page) in pages(&class) {
            // The SVG's namespace is a name, not a fetch.
            let page = page.replace("xmlns=\"http://www.w3.org/2000/svg\"", "");
            for forbidden in ["<script", "http://", "https://", "@import", "<link", "url("] {
                assert!(!page.contains(forbidden), "{path} has {forbidden}");
            }
        }
    }
}
