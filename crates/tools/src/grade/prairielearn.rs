//! PrairieLearn's results.json for one submission, as its external
//! grading documentation defines it
//! (<https://prairielearn.readthedocs.io/en/latest/externalGrading/>,
//! "Grading results"): `gradable`, `score` from 0 to 1, `message`, and
//! `tests` with `name`, `description`, `points`, `max_points`, `message`,
//! `output` and `images`, each image a `label` and a `url` holding a base64
//! data URL. The file must stay under 1 MB: when the images would take it
//! past that, the error maps and references are dropped first, then the
//! students' own images, and the message says so. The container writes it
//! to /grade/results/results.json.
//!
//! When not one file could be compared (each missing or refused), nothing
//! was handed in to grade: `gradable` is false, which PrairieLearn shows as
//! "invalid, not gradable" and does not count as an attempt, and
//! `format_errors` says why for each file.

use base64::Engine;
use serde_json::{Value, json};

use super::Graded;
use super::gradescope::output;
use super::model::StudentGrades;

/// PrairieLearn's limit on the file, 1 MB, with room to spare.
pub(crate) const MAX_BYTES: usize = 1_000_000;

/// Which images each test carries.
#[derive(Clone, Copy, PartialEq)]
enum Images {
    All,
    YoursOnly,
    None,
}

/// The results of `student` (one of `graded`'s students), as JSON text.
pub fn results(graded: &Graded, student: &StudentGrades) -> String {
    for images in [Images::All, Images::YoursOnly, Images::None] {
        let text = text(graded, student, images);
        if text.len() <= MAX_BYTES || images == Images::None {
            return text;
        }
    }
    unreachable!("the last try is returned")
}

fn text(graded: &Graded, student: &StudentGrades, images: Images) -> String {
    let grades = &graded.grades;
    let tests: Vec<Value> = grades
        .scenes
        .iter()
        .zip(&student.scenes)
        .map(|(sheet, grade)| {
            let mut shown = Vec::new();
            let mut add = |label: &str, path: Option<&String>| {
                if let Some(bytes) = path.and_then(|p| graded.image(p)) {
                    shown.push(json!({ "label": label, "url": data_url(bytes) }));
                }
            };
            if images != Images::None {
                add("your image", grade.yours_image.as_ref());
            }
            if images == Images::All {
                add("raystep's render", Some(&sheet.reference_image));
                add("FLIP error map", grade.error_map_image.as_ref());
            }
            let mut verdict = match (&grade.refused, grade.matches) {
                (Some(reason), _) => format!("not graded: {reason}"),
                (None, true) if grade.anti_aliased => "matches (anti-aliased)".to_string(),
                (None, true) => "matches".to_string(),
                (None, false) => match grade.mistakes.first() {
                    Some(mistake) => format!("differs: likely {mistake}"),
                    None => "differs".to_string(),
                },
            };
            if let Some(note) = &grade.note {
                verdict.push_str(&format!(" ({note})"));
            }
            if let Some(o) = &grade.overridden {
                verdict.push_str(&format!("; overridden by hand: {}", o.reason));
            }
            json!({
                "name": sheet.submit,
                "description": format!("{} rendered at {}x{}", sheet.file, sheet.width, sheet.height),
                "points": grade.points,
                "max_points": grade.max_points,
                "message": verdict,
                "output": output(sheet, grade),
                "images": shown,
            })
        })
        .collect();
    let score = if grades.max_total > 0.0 {
        (student.total / grades.max_total).clamp(0.0, 1.0)
    } else {
        // Nothing to lose: full marks.
        1.0
    };
    let mut message = format!(
        "{}: {} of {} points.",
        grades.title,
        super::csv_table::number(student.total),
        super::csv_table::number(grades.max_total)
    );
    for note in &student.notes {
        message.push_str(&format!(" Note: {note}."));
    }
    // Nothing compared: nothing was handed in to grade.
    let gradable = student.scenes.iter().any(|g| g.refused.is_none());
    if !gradable {
        message.push_str(
            " Nothing could be graded: none of the files asked for could be read (each test \
             says why). This submission is not counted as an attempt.",
        );
    }
    match images {
        Images::All => {}
        Images::YoursOnly => message.push_str(
            " raystep's renders and the error maps are left out to keep this file under \
             PrairieLearn's 1 MB.",
        ),
        Images::None => message
            .push_str(" The images are left out to keep this file under PrairieLearn's 1 MB."),
    }
    let mut value = json!({
        "gradable": gradable,
        "score": score,
        "message": message,
        "tests": tests,
    });
    if !gradable {
        let errors: Vec<String> = (grades.scenes.iter().zip(&student.scenes))
            .filter_map(|(sheet, g)| Some(format!("{}: {}", sheet.submit, g.refused.as_ref()?)))
            .collect();
        value["format_errors"] = json!(errors);
    }
    serde_json::to_string(&value).expect("JSON values serialise") + "\n"
}

fn data_url(png: &[u8]) -> String {
    format!(
        "data:image/png;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(png)
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grade::model::{ClassGrades, SceneGrade, SceneSheet};

    /// A class of one student and `scenes` scenes, each image `image_bytes`
    /// long (not a real PNG: only its size matters here).
    fn graded(scenes: usize, image_bytes: usize) -> Graded {
        let mut images = Vec::new();
        let mut sheets = Vec::new();
        let mut grades = Vec::new();
        for i in 0..scenes {
            let (reference, yours, map) = (
                format!("reference/{i}.png"),
                format!("images/a/{i}.yours.png"),
                format!("images/a/{i}.flip.png"),
            );
            for path in [&reference, &yours, &map] {
                images.push((path.clone(), vec![7u8; image_bytes]));
            }
            sheets.push(SceneSheet {
                file: format!("{i}.toml"),
                submit: format!("{i}.png"),
                points: 10.0,
                width: 160,
                height: 120,
                partial: false,
                max_flip: None,
                reference_image: reference,
                visibility: Default::default(),
                tolerance: 3,
                far_off_allowed: 0,
                antialiasing: true,
                hot_pixels_allowed: None,
            });
            grades.push(SceneGrade {
                points: 10.0,
                max_points: 10.0,
                refused: None,
                matches: true,
                flip_mean: Some(0.0),
                mistakes: Vec::new(),
                compare: None,
                report_text: Some("they match.\n".into()),
                yours_image: Some(yours),
                error_map_image: Some(map),
                note: None,
                anti_aliased: false,
                overridden: None,
            });
        }
        let student = StudentGrades {
            student: "a".into(),
            slug: "a".into(),
            scenes: grades,
            total: 10.0 * scenes as f64,
            notes: Vec::new(),
        };
        Graded {
            grades: ClassGrades {
                title: "T".into(),
                scenes: sheets,
                students: vec![student],
                max_total: 10.0 * scenes as f64,
                ignored: Vec::new(),
                visibility: Default::default(),
            },
            images,
        }
    }

    fn images_per_test(text: &str) -> Vec<usize> {
        let value: Value = serde_json::from_str(text).unwrap();
        value["tests"]
            .as_array()
            .unwrap()
            .iter()
            .map(|t| t["images"].as_array().unwrap().len())
            .collect()
    }

    #[test]
    fn images_are_dropped_to_stay_under_a_megabyte_and_the_message_says_so() {
        // A 100 KB image is 136 KB in base64 (4 characters per 3 bytes):
        // two scenes' three images each are 820 KB, under the limit.
        let small = graded(2, 100_000);
        let text = results(&small, &small.grades.students[0]);
        assert_eq!(images_per_test(&text), [3, 3]);
        assert!(
            text.len() < MAX_BYTES && text.len() > 800_000,
            "{}",
            text.len()
        );
        assert!(!text.contains("left out"));
        // 200 KB images: all six are 1.6 MB; the two students' own, 546 KB.
        let large = graded(2, 200_000);
        let text = results(&large, &large.grades.students[0]);
        assert_eq!(images_per_test(&text), [1, 1]);
        assert!(text.len() < MAX_BYTES, "{}", text.len());
        assert!(
            text.contains("error maps are left out to keep this file under PrairieLearn's 1 MB")
        );
        // 400 KB: even the students' own are 1.07 MB: none.
        let huge = graded(2, 400_000);
        let text = results(&huge, &huge.grades.students[0]);
        assert_eq!(images_per_test(&text), [0, 0]);
        assert!(text.contains("The images are left out"));
        let value: Value = serde_json::from_str(&text).unwrap();
        assert_eq!(value["score"], 1.0);
        assert_eq!(value["gradable"], true);
    }
}
