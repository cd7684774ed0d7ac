//! index.html's table: one row per student, one column per scene. A cell
//! shows the three thumbnails (yours, the reference, the error map), the
//! points, and match, near match, the top mistake or the refusal's reason;
//! each links to that scene on the student's page. Rows come by name
//! (`sorting`); each heading, row and cell carries what the page's script
//! sorts by (`data-sort`, `data-points`).

use std::fmt::Write;

use super::escape::{escape, url};
use super::images::{image, thumbnail_size};
use super::sorting::{by_name, row_anchor};
use super::{notes_line, scene_anchor, student_page_path};
use crate::grade::model::{ClassGrades, SceneGrade, SceneSheet, StudentGrades};
use crate::grade::points_text as points;

/// An image that differs, with no mistake named, and a FLIP mean below
/// this is a "near match": a few pixels off, worth the teacher's look, not
/// a wrong tracer. At 160 x 120 a handful of stray pixels gives 0.0003 to
/// 0.004 and a 2 x 2 supersampled render 0.005 to 0.05, while a channel
/// swap gives 0.11 to 0.64 (0.11 on attenuation.toml: under the 0.2 of
/// `max_flip`, which is why that is not the bar). A catalogue mistake is
/// named before this is asked, however faint (byte-wrap on glass.toml is
/// 0.0012).
pub(super) const NEAR_MATCH_FLIP: f64 = 0.01;

/// Whether `grade` is a near match (`NEAR_MATCH_FLIP`).
pub(super) fn near_match(grade: &SceneGrade) -> bool {
    grade.refused.is_none()
        && !grade.matches
        && grade.mistakes.is_empty()
        && grade.flip_mean.is_some_and(|f| f < NEAR_MATCH_FLIP)
}

pub(super) fn table(class: &ClassGrades) -> String {
    // A refusal's reason is as wide as the widest cell's thumbnails.
    let thumbnails = class
        .scenes
        .iter()
        .map(|s| thumbnail_size(s.width, s.height, class.scenes.len()).0 * 3 + 6)
        .max()
        .unwrap_or(0);
    let mut html = format!(
        "<table class=\"grades\" style=\"--cell:{thumbnails}px\"><thead><tr><th scope=\"col\" class=\"student\" data-sort=\"name\">Student</th>\
         <th scope=\"col\" class=\"total\" data-sort=\"total\">Total<span class=\"sub\">of {}</span></th>",
        points(class.max_total)
    );
    for (index, scene) in class.scenes.iter().enumerate() {
        html.push_str(&scene_heading(class, index, scene));
    }
    html.push_str("</tr></thead><tbody>");
    for student in by_name(&class.students) {
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
        "<th scope=\"col\" class=\"scene\" data-sort=\"{}\">{}<span class=\"sub\">{} · {} points</span><span class=\"sub\">{matched} of {} match</span><span class=\"sub\">yours · reference · error map</span></th>",
        scene_anchor(index),
        escape(&scene.file),
        escape(&scene.submit),
        points(scene.points),
        class.students.len(),
    )
}

fn row(class: &ClassGrades, student: &StudentGrades) -> String {
    let page = url(&student_page_path(student));
    let name = escape(&student.student);
    let notes = notes_line(student).map_or(String::new(), |notes| {
        format!("<div class=\"notes\" title=\"{notes}\">{notes}</div>")
    });
    let mut html = format!(
        "<tr id=\"{}\"><th scope=\"row\" class=\"student\"><a href=\"{page}\" title=\"{name}\"><bdi>{name}</bdi></a>{notes}</th><td class=\"total\" data-points=\"{}\"><b>{}</b></td>",
        row_anchor(student),
        student.total,
        points(student.total)
    );
    let scenes = class.scenes.len();
    for (index, scene) in class.scenes.iter().enumerate() {
        match student.scenes.get(index) {
            Some(grade) => html.push_str(&cell(
                scene,
                scenes,
                grade,
                &format!("{page}#{}", scene_anchor(index)),
            )),
            None => html.push_str("<td class=\"cell\"></td>"),
        }
    }
    html.push_str("</tr>");
    html
}

/// One student's cell for `scene` (one of `scenes`), its thumbnails
/// linking to `link`.
fn cell(scene: &SceneSheet, scenes: usize, grade: &SceneGrade, link: &str) -> String {
    let size = thumbnail_size(scene.width, scene.height, scenes);
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
        "<td class=\"cell\" data-points=\"{}\"><a class=\"thumbs\" href=\"{link}\">{}</a><div class=\"result\"><span class=\"pts\"><b>{}</b>/{}</span> {}</div>",
        grade.points,
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
/// named), near match, differs, or refused.
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
        None if near_match(grade) => format!(
            "<span class=\"tag near\" title=\"FLIP {:.4}, under {NEAR_MATCH_FLIP}, and no mistake named: a few pixels apart; see the error map\">near match</span>",
            grade.flip_mean.unwrap_or_default()
        ),
        None => "<span class=\"tag unexplained\">differs</span>".into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grade::html::sample_class::{class, compared, matched, near, refused};

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
        let cell = &table[table.find("<td class=\"cell\"").unwrap()..];
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
    fn a_faint_unexplained_difference_is_a_near_match_not_differs() {
        // Six stray pixels on shadows.toml at 160x120: FLIP 0.0014, nothing
        // named. A channel swap there: 0.277. The bar is 0.01.
        let six_pixels = verdict(&near(0.0014));
        assert!(
            six_pixels.starts_with("<span class=\"tag near\" title=\"FLIP 0.0014, under 0.01"),
            "{six_pixels}"
        );
        assert!(six_pixels.ends_with(">near match</span>"), "{six_pixels}");
        assert_eq!(
            verdict(&near(0.277)),
            "<span class=\"tag unexplained\">differs</span>"
        );
        // A named mistake is told, however faint; a match is a match.
        assert!(
            verdict(&SceneGrade {
                flip_mean: Some(0.0012),
                ..compared(&["byte-wrap"])
            })
            .contains(">byte-wrap<")
        );
        assert!(!near_match(&matched()));
        assert!(!near_match(&refused("missing")));
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
