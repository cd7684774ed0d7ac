//! A hand-made class for the report's unit tests: students by name, each
//! with one grade per scene, made by `matched`, `compared` or `refused`.

use crate::grade::model::{ClassGrades, SceneGrade, SceneSheet, StudentGrades};

/// A class of `students`; scene `i` is `scene{i}.toml` (hand in
/// `scene{i}.png`, 160x120, 10 points), student `i`'s slug is `s{i}`.
pub(super) fn class(students: &[(&str, Vec<SceneGrade>)]) -> ClassGrades {
    let scene_count = students.iter().map(|(_, s)| s.len()).max().unwrap_or(0);
    let scenes: Vec<SceneSheet> = (0..scene_count)
        .map(|i| SceneSheet {
            file: format!("scene{i}.toml"),
            submit: format!("scene{i}.png"),
            points: 10.0,
            width: 160,
            height: 120,
            partial: false,
            max_flip: None,
            reference_image: format!("reference/scene{i}.png"),
            visibility: Default::default(),
            tolerance: 3,
            far_off_allowed: 0,
            antialiasing: true,
            hot_pixels_allowed: None,
        })
        .collect();
    let students = students
        .iter()
        .enumerate()
        .map(|(i, (name, grades))| StudentGrades {
            student: name.to_string(),
            slug: format!("s{i}"),
            total: grades.iter().map(|g| g.points).sum(),
            scenes: grades.clone(),
            notes: Vec::new(),
        })
        .collect();
    ClassGrades {
        title: "A5: Whitted ray tracing".into(),
        max_total: 10.0 * scene_count as f64,
        scenes,
        students,
        ignored: Vec::new(),
        visibility: Default::default(),
    }
}

pub(super) fn matched() -> SceneGrade {
    SceneGrade {
        points: 10.0,
        matches: true,
        flip_mean: Some(0.0),
        mistakes: Vec::new(),
        report_text: Some("yours.png against scene.toml: they match.".into()),
        ..compared(&[])
    }
}

/// Compared, no match, with `mistakes` named (best first): 0 points.
pub(super) fn compared(mistakes: &[&str]) -> SceneGrade {
    SceneGrade {
        points: 0.0,
        max_points: 10.0,
        refused: None,
        matches: false,
        flip_mean: Some(0.1566),
        mistakes: mistakes.iter().map(|m| m.to_string()).collect(),
        compare: None,
        report_text: Some("yours.png against scene.toml: they differ.\n  FLIP 0.1566".into()),
        yours_image: Some("yours/x.png".into()),
        error_map_image: Some("error/x.png".into()),
        note: None,
        anti_aliased: false,
        overridden: None,
    }
}

/// Compared, no match, no mistake named, at FLIP `flip_mean`: 0 points.
pub(super) fn near(flip_mean: f64) -> SceneGrade {
    SceneGrade {
        flip_mean: Some(flip_mean),
        ..compared(&[])
    }
}

pub(super) fn refused(reason: &str) -> SceneGrade {
    SceneGrade {
        refused: Some(reason.into()),
        flip_mean: None,
        report_text: None,
        yours_image: None,
        error_map_image: None,
        ..compared(&[])
    }
}
