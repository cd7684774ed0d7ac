//! index.html's table: one row per student, one column per scene. A cell
//! shows the three thumbnails (yours, the reference, the error map), the
//! points, and match, the top mistake or the refusal's reason; each links
//! to that scene on the student's page.

use std::fmt::Write;

use super::escape::{escape, url};
use super::images::{image, thumbnail_size};
use super::{scene_anchor, student_page_path};
use crate::grade::model::{ClassGrades, SceneGrade, SceneSheet, StudentGrades};
use crate::grade::points_text as points;

pub(super) fn table(class: &ClassGrades) -> String {
    let mut html = String::from(
        "<table class=\"grades\"><thead><tr><th scope=\"col\" class=\"student\">Student</th>",
    );
    let _ = write!(
        html,
        "<th scope=\"col\" class=\"total\">Total<span class=\"sub\">of {}</span></th>",
        points(class.max_total)
    );
    for (index, scene) in class.scenes.iter().enumerate() {
        html.push_str(&scene_heading(class, index, scene));
    }
    html.push_str("</tr></thead><tbody>");
    for student in &class.students {
        html.push_str(&row(class, student));
    }
    html.push_str("</tbody></table>");
    html
}

fn scene_heading(class: &ClassGrades, index: usize, scene: &SceneSheet) -> String {
    let matched = class
        .students
        .iter()
        .filter(|s| s.scenes.get(index).is_some_and(|g| g.matches))
        .count();
    format!(
        "<th scope=\"col\" class=\"scene\">{}<span class=\"sub\">{} · {} points</span><span class=\"sub\">{matched} of {} match</span><span class=\"sub\">yours · reference · error map</span></th>",
        escape(&scene.file),
        escape(&scene.submit),
        points(scene.points),
        class.students.len(),
    )
}

fn row(class: &ClassGrades, student: &StudentGrades) -> String {
    let page = url(&student_page_path(student));
    let name = escape(&student.student);
    let mut html = format!(
        "<tr><th scope=\"row\" class=\"student\"><a href=\"{page}\" title=\"{name}\"><bdi>{name}</bdi></a></th><td class=\"total\"><b>{}</b></td>",
        points(student.total)
    );
    for (index, scene) in class.scenes.iter().enumerate() {
        match student.scenes.get(index) {
            Some(grade) => html.push_str(&cell(
                scene,
                grade,
                &format!("{page}#{}", scene_anchor(index)),
            )),
            None => html.push_str("<td class=\"cell\"></td>"),
        }
    }
    html.push_str("</tr>");
    html
}

/// One student's cell for `scene`, its thumbnails linking to `link`.
fn cell(scene: &SceneSheet, grade: &SceneGrade, link: &str) -> String {
    let size = thumbnail_size(scene.width, scene.height);
    let thumbnails = [
        image(grade.yours_image.as_deref(), "", "yours", size, "none"),
        image(Some(&scene.reference_image), "", "reference", size, "none"),
        image(
            grade.error_map_image.as_deref(),
            "",
            "error map",
            size,
            "none",
        ),
    ];
    let mut html = format!(
        "<td class=\"cell\"><a class=\"thumbs\" href=\"{link}\">{}</a><div class=\"result\"><span class=\"pts\"><b>{}</b>/{}</span> {}</div>",
        thumbnails.concat(),
        points(grade.points),
        points(grade.max_points),
        verdict(grade),
    );
    html.push_str(&overridden(grade, "div"));
    if grade.anti_aliased {
        html.push_str("<div class=\"flip\">anti-aliased</div>");
    }
    if let Some(reason) = &grade.refused {
        // Cut to three lines on screen; the title and the student's page
        // hold it whole.
        let reason = escape(reason);
        let _ = write!(
            html,
            "<div class=\"reason\" title=\"{reason}\">{reason}</div>"
        );
    } else if let Some(mean) = grade.flip_mean.filter(|_| !grade.matches) {
        let _ = write!(html, "<div class=\"flip\">FLIP {mean:.4}</div>");
    }
    html.push_str("</td>");
    html
}

/// "overridden: REASON (graded N)" in a `tag` element of class
/// `overridden`, where the grade was set by hand (issue 40); else nothing.
pub(super) fn overridden(grade: &SceneGrade, tag: &str) -> String {
    grade.overridden.as_ref().map_or(String::new(), |o| {
        format!(
            "<{tag} class=\"overridden\">overridden: {} (graded {})</{tag}>",
            escape(&o.reason),
            points(o.graded_points)
        )
    })
}

/// The cell's word: match, the top mistake (and how many more were
/// named), differs, or refused.
pub(super) fn verdict(grade: &SceneGrade) -> String {
    if grade.refused.is_some() {
        return "<span class=\"tag refused\">refused</span>".into();
    }
    if grade.matches {
        return "<span class=\"tag match\">match</span>".into();
    }
    match grade.mistakes.split_first() {
        Some((top, rest)) => {
            let more = if rest.is_empty() {
                String::new()
            } else {
                format!(" +{}", rest.len())
            };
            format!("<span class=\"tag mistake\">{}{more}</span>", escape(top))
        }
        None => "<span class=\"tag unexplained\">differs</span>".into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grade::html::sample_class::{class, compared, matched, refused};

    #[test]
    fn a_refused_cell_shows_its_reason_and_no_image_of_yours() {
        let class = class(&[(
            "ada",
            vec![
                refused("rendered at 320x240, the assignment asks for 160x120 <sic>"),
                matched(),
            ],
        )]);
        let table = table(&class);
        let cell = &table[table.find("<td class=\"cell\">").unwrap()..];
        let cell = &cell[..cell.find("</td>").unwrap()];
        assert!(
            cell.contains("<span class=\"tag refused\">refused</span>"),
            "{cell}"
        );
        assert!(
            cell.contains("assignment asks for 160x120 &lt;sic&gt;\">rendered at 320x240, the assignment asks for 160x120 &lt;sic&gt;</div>"),
            "{cell}"
        );
        // No image of yours nor an error map: two grey boxes, the reference alone.
        assert_eq!(cell.matches("<img ").count(), 1, "{cell}");
        assert!(cell.contains("src=\"reference/scene0.png\""), "{cell}");
        assert_eq!(cell.matches("class=\"noimg\"").count(), 2, "{cell}");
        assert!(cell.contains("<b>0</b>/10"), "{cell}");
    }

    #[test]
    fn a_cell_says_match_or_the_top_mistake() {
        assert!(verdict(&matched()).contains(">match<"));
        assert_eq!(
            verdict(&compared(&["opaque-shadows", "phong-not-blinn"])),
            "<span class=\"tag mistake\">opaque-shadows +1</span>"
        );
        assert!(verdict(&compared(&[])).contains(">differs<"));
    }

    #[test]
    fn the_heading_counts_matches_and_rows_link_to_pages() {
        // Two of three match scene 0; ada is s0, so her cell for the first
        // scene links to students/s0.html#scene-1.
        let class = class(&[
            ("ada", vec![matched()]),
            ("bob", vec![compared(&["no-ambient"])]),
            ("cy", vec![matched()]),
        ]);
        let table = table(&class);
        assert!(
            table.contains("scene0.png · 10 points</span><span class=\"sub\">2 of 3 match<"),
            "{table}"
        );
        assert!(
            table.contains("<a class=\"thumbs\" href=\"students/s0.html#scene-1\">"),
            "{table}"
        );
        assert!(
            table.contains("<a href=\"students/s1.html\" title=\"bob\"><bdi>bob</bdi></a>"),
            "{table}"
        );
    }
}
