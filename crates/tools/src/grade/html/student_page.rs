//! students/<slug>.html: one student's grades, scene by scene, with the
//! three images at a readable size, the points and how they were scored,
//! the refusal or `compare`'s report, and the mistakes it named.

use std::fmt::Write;

use super::class_table::{overridden, verdict};
use super::escape::{escape, escape_block};
use super::images::{image, readable_size};
use super::{notes_line, scene_anchor};
use crate::grade::model::{ClassGrades, SceneGrade, SceneSheet, StudentGrades};
use crate::grade::points_text as points;

/// The page's body; images and links reach REPORT/ through `../`.
pub(super) fn body(class: &ClassGrades, student: &StudentGrades) -> String {
    let mut html = format!(
        "<nav class=\"back\"><a href=\"../index.html\">← Class report</a></nav>\
         <header><h1 class=\"name\"><bdi>{}</bdi></h1><p class=\"summary\">{} · total <b>{}</b> of {} points</p></header>",
        escape(&student.student),
        escape(&class.title),
        points(student.total),
        points(class.max_total),
    );
    if let Some(notes) = notes_line(student) {
        let _ = write!(html, "<p class=\"notes\">Note: {notes}.</p>");
    }
    html.push_str(&contents(class, student));
    for (index, scene) in class.scenes.iter().enumerate() {
        if let Some(grade) = student.scenes.get(index) {
            html.push_str(&section(index, scene, grade));
        }
    }
    html.push_str("<nav class=\"back\"><a href=\"../index.html\">← Class report</a></nav>");
    html
}

/// A line per scene at the top, linking to its section.
fn contents(class: &ClassGrades, student: &StudentGrades) -> String {
    let mut html = String::from("<ul class=\"contents\">");
    for (index, (scene, grade)) in class.scenes.iter().zip(&student.scenes).enumerate() {
        let _ = write!(
            html,
            "<li><a href=\"#{}\">{}</a> <span class=\"pts\"><b>{}</b>/{}</span> {} {}</li>",
            scene_anchor(index),
            escape(&scene.file),
            points(grade.points),
            points(grade.max_points),
            verdict(grade),
            overridden(grade, "span"),
        );
    }
    html.push_str("</ul>");
    html
}

fn section(index: usize, scene: &SceneSheet, grade: &SceneGrade) -> String {
    let mut html = format!(
        "<section class=\"scene\" id=\"{}\"><h2>{} <span class=\"sub\">hand in {}, {}x{}</span></h2>\
         <p class=\"result\"><span class=\"pts\"><b>{}</b> of {} points</span> {}</p>{}<p class=\"rule\">{}</p>",
        scene_anchor(index),
        escape(&scene.file),
        escape(&scene.submit),
        scene.width,
        scene.height,
        points(grade.points),
        points(grade.max_points),
        verdict(grade),
        overridden(grade, "p"),
        escape(&scoring(scene, grade)),
    );
    if let Some(reason) = &grade.refused {
        let _ = write!(html, "<p class=\"reason\">Refused: {}</p>", escape(reason));
    }
    let size = readable_size(scene.width, scene.height);
    let figures = [
        (grade.yours_image.as_deref(), "yours"),
        (Some(scene.reference_image.as_str()), "reference"),
        (grade.error_map_image.as_deref(), "error map (FLIP)"),
    ];
    html.push_str("<div class=\"images\">");
    for (path, caption) in figures {
        let _ = write!(
            html,
            "<figure>{}<figcaption>{caption}</figcaption></figure>",
            image(path, "../", caption, size, "no image")
        );
    }
    html.push_str("</div>");
    if !grade.mistakes.is_empty() {
        html.push_str("<p class=\"named\">Mistakes <code>compare</code> named, best first: ");
        for mistake in &grade.mistakes {
            let _ = write!(
                html,
                "<span class=\"tag mistake\">{}</span>",
                escape(mistake)
            );
        }
        html.push_str("</p>");
    }
    if let Some(report) = &grade.report_text {
        let _ = write!(html, "<pre class=\"report\">{}</pre>", escape_block(report));
    }
    html.push_str("</section>");
    html
}

/// How the points were reckoned, with this submission's numbers.
fn scoring(scene: &SceneSheet, grade: &SceneGrade) -> String {
    let max = points(grade.max_points);
    match (scene.partial, scene.max_flip, grade.flip_mean) {
        (true, Some(max_flip), Some(mean)) if grade.refused.is_none() && !grade.matches => format!(
            "Partial credit: {max} × max(0, 1 − FLIP {mean:.4} / {max_flip}) = {}.",
            points(grade.points)
        ),
        (true, Some(max_flip), _) => format!(
            "Partial credit: full points on a match, else {max} × max(0, 1 − FLIP mean / {max_flip})."
        ),
        _ => "Full points on a match, else 0.".to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grade::html::sample_class::{class, compared, refused};

    #[test]
    fn a_page_shows_the_name_escaped_each_scene_and_the_report() {
        let class = class(&[(
            "<b>ada</b>",
            vec![
                compared(&["opaque-shadows", "no-ambient"]),
                refused("not a PNG"),
            ],
        )]);
        let page = body(&class, &class.students[0]);
        assert!(
            page.contains("<h1 class=\"name\"><bdi>&lt;b&gt;ada&lt;/b&gt;</bdi></h1>"),
            "{page}"
        );
        assert!(
            page.contains("id=\"scene-1\"") && page.contains("id=\"scene-2\""),
            "{page}"
        );
        assert!(
            page.contains("best first: <span class=\"tag mistake\">opaque-shadows</span><span class=\"tag mistake\">no-ambient</span></p>")
        );
        // The report keeps its lines; images come from one folder up.
        assert!(page.contains(
            "<pre class=\"report\">yours.png against scene.toml: they differ.\n  FLIP 0.1566</pre>"
        ));
        assert!(
            page.contains("src=\"../yours/x.png\"")
                && page.contains("src=\"../reference/scene1.png\"")
        );
        assert!(page.contains("<p class=\"reason\">Refused: not a PNG</p>"));
        assert_eq!(page.matches("href=\"../index.html\"").count(), 2);
    }

    #[test]
    fn partial_credit_is_reckoned_with_the_numbers() {
        // 10 × max(0, 1 − 0.157 / 0.2) = 10 × 0.215 = 2.15 (the model holds
        // the points; the line shows how they came).
        let mut sheet = class(&[("a", vec![compared(&[])])]).scenes[0].clone();
        sheet.partial = true;
        sheet.max_flip = Some(0.2);
        let grade = SceneGrade {
            flip_mean: Some(0.157),
            points: 2.15,
            ..compared(&[])
        };
        assert_eq!(
            scoring(&sheet, &grade),
            "Partial credit: 10 × max(0, 1 − FLIP 0.1570 / 0.2) = 2.15."
        );
    }
}
