//! Gradescope's results.json for one submission, as its autograder
//! specification defines it
//! (<https://gradescope-autograders.readthedocs.io/en/latest/specs/>,
//! "Output format"): the submission's `score`, `output`, `output_format` and
//! `visibility`, and one entry of `tests` per scene with its `name`,
//! `score`, `max_score`, `output`, `output_format` and `visibility`. The
//! container's `run_autograder` writes it to
//! /autograder/results/results.json.
//!
//! Every `output` is plain text: its `output_format` is `"text"` ("Output
//! String Formatting": `text`, `simple_format`, `html`, `md` or `ansi`; the
//! top-level output's default, `simple_format`, renders HTML, so a title
//! holding `<meshes>` would lose it). `visibility` is one of `visible` (the
//! default), `hidden`, `after_due_date` and `after_published`
//! ("Controlling Test Case Visibility"), set in the assignment file.

use serde_json::{Value, json};

use super::model::{ClassGrades, SceneGrade, SceneSheet, StudentGrades};

/// How every `output` is rendered: as written, no markup.
const OUTPUT_FORMAT: &str = "text";

/// The results of `student` (one of `grades`' students).
pub fn results(grades: &ClassGrades, student: &StudentGrades) -> Value {
    let tests: Vec<Value> = grades
        .scenes
        .iter()
        .zip(&student.scenes)
        .map(|(sheet, grade)| {
            json!({
                "name": format!("{} ({})", sheet.submit, sheet.file),
                "score": grade.points,
                "max_score": grade.max_points,
                "output": output(sheet, grade),
                "output_format": OUTPUT_FORMAT,
                "visibility": sheet.visibility,
            })
        })
        .collect();
    let mut output = format!(
        "{}: {} of {} points.",
        grades.title,
        super::csv_table::number(student.total),
        super::csv_table::number(grades.max_total)
    );
    for note in &student.notes {
        output.push_str(&format!("\nNote: {note}."));
    }
    json!({
        "score": student.total,
        "output": output,
        "output_format": OUTPUT_FORMAT,
        "visibility": grades.visibility,
        "tests": tests,
    })
}

/// What a scene's test says: the verdict and how it scored, which file was
/// taken when it is not the name asked for, then `compare`'s report (or why
/// the file was refused).
pub(crate) fn output(sheet: &SceneSheet, grade: &SceneGrade) -> String {
    let points = format!(
        "{} of {} points",
        super::csv_table::number(grade.points),
        super::csv_table::number(grade.max_points)
    );
    let note = grade
        .note
        .as_ref()
        .map_or(String::new(), |note| format!("Note: {note}.\n"));
    // Set by hand: the teacher's points and reason first, then what
    // grading found.
    let by_hand = grade.overridden.as_ref().map_or(String::new(), |o| {
        format!(
            ", overridden by hand: {} (graded {} of {} points)",
            o.reason,
            super::csv_table::number(o.graded_points),
            super::csv_table::number(grade.max_points)
        )
    });
    if let Some(reason) = &grade.refused {
        return format!("{points}{by_hand}: not graded, {reason}.\n{note}");
    }
    let how = match (grade.matches, sheet.max_flip, grade.flip_mean) {
        (true, _, _) if grade.anti_aliased => {
            "your image matches raystep's (anti-aliased)".to_string()
        }
        (true, _, _) => "your image matches raystep's".to_string(),
        (false, Some(max), Some(flip)) => format!(
            "your image differs; partial credit, the points × (1 − FLIP {flip:.4} / max_flip {max})"
        ),
        _ => "your image differs (a match scores the points, a difference 0)".to_string(),
    };
    let report = grade.report_text.as_deref().unwrap_or_default();
    format!("{points}{by_hand}: {how}.\n{note}\n{report}")
}
