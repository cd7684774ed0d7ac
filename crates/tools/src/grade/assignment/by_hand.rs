//! Grades set by hand in the assignment file (issue 40): the teacher who
//! decides an edge case writes it down, with the reason, and every output
//! shows the grade as overridden, with that reason.
//!
//! ```toml
//! [[override]]
//! student = "ada"          # the student's folder name
//! scene = "glass.png"      # the scene, by the file handed in for it
//! points = 10              # from 0 to the scene's points
//! reason = "a correct render; the silhouette moved by rounding"
//! ```
//!
//! The scene and the points are checked as the file is read; the student
//! when the class is known (`check_students`), before anything is graded.

use std::collections::HashSet;
use std::ops::Range;
use std::path::Path;

use serde::Deserialize;
use toml::Spanned;

use super::AssignedScene;
use raystep_engine::scene::SceneError;

/// One `[[override]]` as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct OverrideDef {
    student: Spanned<String>,
    scene: Spanned<String>,
    points: Spanned<f64>,
    reason: Spanned<String>,
}

/// A grade set by hand.
pub struct Override {
    /// The student's folder name, as the grades write it.
    pub(crate) student: String,
    /// The index of the scene in the assignment.
    pub(crate) scene: usize,
    pub(crate) points: f64,
    pub(crate) reason: String,
    /// What to say when no student of the class has this name.
    unknown: SceneError,
}

/// The overrides of `defs`, each checked against the assignment's
/// `scenes`; `path` and `text` name the assignment in messages.
pub(super) fn read(
    path: &Path,
    text: &str,
    defs: Vec<OverrideDef>,
    scenes: &[AssignedScene],
) -> Result<Vec<Override>, SceneError> {
    let error = |span: Range<usize>, message: String| SceneError::at(path, text, span, message);
    let mut seen = HashSet::new();
    let mut overrides = Vec::with_capacity(defs.len());
    for def in defs {
        let wanted = def.scene.get_ref();
        let Some(scene) = scenes.iter().position(|s| &s.submit == wanted) else {
            let names: Vec<String> = scenes.iter().map(|s| format!("{:?}", s.submit)).collect();
            return Err(error(
                def.scene.span(),
                format!(
                    "no scene hands in {wanted:?}: an override names its scene by the file handed in for it ({})",
                    names.join(", ")
                ),
            ));
        };
        let student = def.student.get_ref();
        if student.is_empty() {
            return Err(error(
                def.student.span(),
                "student must be a student's folder name, got an empty name".into(),
            ));
        }
        if !seen.insert((student.clone(), scene)) {
            return Err(error(
                def.student.span(),
                format!(
                    "{student:?} already has an override for {wanted:?}: one per student and scene"
                ),
            ));
        }
        let points = *def.points.get_ref();
        let max = scenes[scene].points;
        if !(points.is_finite() && (0.0..=max).contains(&points)) {
            return Err(error(
                def.points.span(),
                format!("points must be a number from 0 to the scene's {max}, got {points}"),
            ));
        }
        if def.reason.get_ref().trim().is_empty() {
            return Err(error(
                def.reason.span(),
                "reason must say why the grade is set by hand: every output shows it".into(),
            ));
        }
        let unknown = error(
            def.student.span(),
            format!(
                "no student folder named {student:?} in the class: an override names a student by their folder's name"
            ),
        );
        overrides.push(Override {
            student: def.student.into_inner(),
            scene,
            points,
            reason: def.reason.into_inner(),
            unknown,
        });
    }
    Ok(overrides)
}

/// Refuses an override whose student is not one of `names` (the class's
/// folder names, as the grades write them), at the override's line and
/// column.
pub fn check_students<'a>(
    overrides: &[Override],
    names: impl IntoIterator<Item = &'a str>,
) -> Result<(), SceneError> {
    let names: HashSet<&str> = names.into_iter().collect();
    match overrides
        .iter()
        .find(|o| !names.contains(o.student.as_str()))
    {
        Some(unknown) => Err(unknown.unknown.clone()),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::check_students;
    use crate::grade::assignment::{Assignment, test_parsed as parsed, test_path as here};

    /// Two scenes (glass.png 10 points, shadows.png 5) and `overrides`,
    /// from line 9 on.
    fn with(overrides: &str) -> Result<Assignment, String> {
        parsed(&format!(
            "[[scene]]\nfile = \"glass.toml\"\nsubmit = \"glass.png\"\npoints = 10\n\
             [[scene]]\nfile = \"shadows.toml\"\nsubmit = \"shadows.png\"\npoints = 5\n{overrides}"
        ))
    }

    fn refused(overrides: &str) -> String {
        match with(overrides) {
            Ok(_) => panic!("accepted: {overrides}"),
            Err(message) => message,
        }
    }

    fn block(student: &str, scene: &str, points: &str, reason: &str) -> String {
        format!(
            "[[override]]\nstudent = {student:?}\nscene = {scene:?}\npoints = {points}\nreason = {reason:?}\n"
        )
    }

    #[test]
    fn an_override_names_a_student_a_scene_its_points_and_why() {
        let assignment = with(&block("ada", "shadows.png", "4.5", "rounding")).unwrap();
        let [o] = &assignment.overrides[..] else {
            panic!("one override")
        };
        assert_eq!((o.student.as_str(), o.scene, o.points), ("ada", 1, 4.5));
        assert_eq!(o.reason, "rounding");
        // The student is checked against the class.
        assert!(check_students(&assignment.overrides, ["ada", "bo"]).is_ok());
        let message = check_students(&assignment.overrides, ["bo"])
            .unwrap_err()
            .to_string();
        // `student = "ada"` is line 10, the value from column 11.
        assert!(
            message.starts_with(&format!("{}:10:11: ", here().display())),
            "{message}"
        );
        assert!(
            message.contains("no student folder named \"ada\""),
            "{message}"
        );
    }

    #[test]
    fn teachers_md_s_knobs_and_override_parse() {
        // Its knobs block and its override block, after a scene of its own:
        // what the guide shows is what the loader reads.
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
        let guide = std::fs::read_to_string(root.join("docs/TEACHERS.md")).unwrap();
        let block = |start: &str| {
            let from = guide
                .find(start)
                .unwrap_or_else(|| panic!("TEACHERS.md's {start}"));
            let to = from + guide[from..].find("```").unwrap();
            guide[from..to].to_string()
        };
        let knobs = block("tolerance = 3 ");
        let overrides = block("[[override]]\nstudent = ");
        let text = format!(
            "{knobs}[[scene]]\nfile = \"glass.toml\"\nsubmit = \"glass.png\"\npoints = 10\n{overrides}"
        );
        let assignment = parsed(&text).unwrap_or_else(|m| panic!("{m}"));
        assert_eq!(
            assignment.scenes[0].rule,
            crate::compare::MatchRule::default()
        );
        assert_eq!(assignment.overrides[0].student, "ada");
        assert_eq!(assignment.overrides[0].points, 10.0);
    }

    #[test]
    fn bad_overrides_are_told_at_their_line_and_column() {
        let at = |line_col: &str| format!("{}:{line_col}: ", here().display());
        // Line 9 is [[override]]; student line 10, scene 11, points 12,
        // reason 13.
        let cases = [
            (
                block("ada", "glass.toml", "1", "r"),
                "11:9",
                "no scene hands in \"glass.toml\"",
            ),
            (
                block("ada", "shadows.png", "5.5", "r"),
                "12:10",
                "from 0 to the scene's 5, got 5.5",
            ),
            (block("ada", "shadows.png", "-1", "r"), "12:10", "got -1"),
            (block("ada", "glass.png", "nan", "r"), "12:10", "got NaN"),
            (
                block("ada", "glass.png", "1", " "),
                "13:10",
                "reason must say why",
            ),
            (block("", "glass.png", "1", "r"), "10:11", "an empty name"),
        ];
        for (text, line_col, words) in cases {
            let message = refused(&text);
            assert!(message.starts_with(&at(line_col)), "{message}");
            assert!(message.contains(words), "{message}");
        }
        // The same student and scene twice: at the second's student, line 15.
        let twice = block("ada", "glass.png", "1", "r") + &block("ada", "glass.png", "2", "s");
        let message = refused(&twice);
        assert!(message.starts_with(&at("15:11")), "{message}");
        assert!(message.contains("already has an override"), "{message}");
        // A missing reason and an unknown key: TOML's own words, line 9/13.
        let message =
            refused("[[override]]\nstudent = \"ada\"\nscene = \"glass.png\"\npoints = 1\n");
        assert!(message.starts_with(&at("9:1")), "{message}");
        assert!(message.contains("missing field `reason`"), "{message}");
        let message = refused(&(block("ada", "glass.png", "1", "r") + "note = 1\n"));
        assert!(message.starts_with(&at("14:1")), "{message}");
        assert!(message.contains("unknown field `note`"), "{message}");
    }
}
