//! Gradescope's results.json for one submission, as its autograder
//! specification defines it (gradescope-autograders.readthedocs.io,
//! "Autograder Specifications", "Output format"): the submission's `score`
//! and `output`, and one entry of `tests` per scene with its `name`,
//! `score`, `max_score`, `output` and `visibility`. The container's
//! `run_autograder` writes it to /autograder/results/results.json.

use serde_json::{Value, json};

use super::model::{ClassGrades, SceneGrade, SceneSheet, StudentGrades};

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
                "visibility": "visible",
            })
        })
        .collect();
    json!({
        "score": student.total,
        "output": format!(
            "{}: {} of {} points.",
            grades.title,
            super::csv_table::number(student.total),
            super::csv_table::number(grades.max_total)
        ),
        "tests": tests,
    })
}

/// What a scene's test says: the verdict and how it scored, then
/// `compare`'s report (or why the file was refused).
pub(crate) fn output(sheet: &SceneSheet, grade: &SceneGrade) -> String {
    let points = format!(
        "{} of {} points",
        super::csv_table::number(grade.points),
        super::csv_table::number(grade.max_points)
    );
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
        return format!("{points}{by_hand}: not graded, {reason}.\n");
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
    format!("{points}{by_hand}: {how}.\n\n{report}")
}
