//! What `grade` found for one class: the one value that grades.csv,
//! grades.json, the autograder files and the HTML report are all written
//! from, so no two of them can disagree.
//!
//! Paths in it are relative to REPORT/ and use `/`, as HTML links need.

use serde::{Deserialize, Serialize};

/// A whole class's grades.
#[derive(Clone, Debug, Serialize)]
pub struct ClassGrades {
    /// The assignment's title.
    pub title: String,
    /// The assignment's scenes, in its order.
    pub scenes: Vec<SceneSheet>,
    /// One entry per student folder, sorted by `student` (byte order).
    pub students: Vec<StudentGrades>,
    /// The points the whole assignment is worth: the sum of the scenes'.
    pub max_total: f64,
    /// What SUBMISSIONS/ holds beside the students, not graded (as read,
    /// sorted, a folder without `/`): what a system or an archiver leaves
    /// (`__MACOSX`, dot names, `Thumbs.db`, `desktop.ini`) and files.
    /// Empty for one submission. Untrusted, as `student` is.
    pub ignored: Vec<String>,
    /// Gradescope's visibility of the whole results (the assignment's).
    pub visibility: Visibility,
}

/// One scene of the assignment, as it was graded.
#[derive(Clone, Debug, Serialize)]
pub struct SceneSheet {
    /// The scene file as the assignment names it (`glass.toml`).
    pub file: String,
    /// The file name each student hands in for it (`glass.png`).
    pub submit: String,
    pub points: f64,
    /// The size every submission must have.
    pub width: u32,
    pub height: u32,
    /// Partial credit from FLIP, and the FLIP mean that scores 0.
    pub partial: bool,
    pub max_flip: Option<f64>,
    /// raystep's render of the scene at that size (a PNG in REPORT/).
    pub reference_image: String,
    /// Gradescope's visibility of this scene's test.
    pub visibility: Visibility,
    /// The match rule's knobs for this scene (issue 40): the tolerance in
    /// steps of 255, the far-off pixels a match allows, and whether
    /// anti-aliased edges match.
    pub tolerance: u8,
    pub far_off_allowed: usize,
    pub antialiasing: bool,
    /// CSE 167's pass rule, when the assignment asks for it (issue 42): at
    /// most this many hot pixels, in place of the three knobs above but the
    /// tolerance.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hot_pixels_allowed: Option<usize>,
}

/// One student's grades, scene by scene.
#[derive(Clone, Debug, Serialize)]
pub struct StudentGrades {
    /// The student's folder name as read (invalid UTF-8 replaced by U+FFFD).
    /// Untrusted: escape it wherever it is written.
    pub student: String,
    /// A name for this student's files in REPORT/: only `[a-z0-9_-]`,
    /// unique over the class, never empty.
    pub slug: String,
    /// One per scene, in the order of `ClassGrades::scenes`.
    pub scenes: Vec<SceneGrade>,
    /// The sum of the scenes' points.
    pub total: f64,
    /// What the student should know about how their files were found (read
    /// from the one folder in theirs); each scene's own note is its `note`.
    pub notes: Vec<String>,
}

/// One student's submission for one scene.
#[derive(Clone, Debug, Serialize)]
pub struct SceneGrade {
    pub points: f64,
    pub max_points: f64,
    /// Why the submission could not be compared (missing, not a PNG, the
    /// wrong size, a link out of the folder, ...): it scores 0.
    pub refused: Option<String>,
    /// `compare`'s verdict; false when refused.
    pub matches: bool,
    /// FLIP's mean error, when compared.
    pub flip_mean: Option<f64>,
    /// The names of the mistakes `compare` ranked, best first (empty on a
    /// match or a refusal): the class histogram counts these.
    pub mistakes: Vec<String>,
    /// `compare --format json`'s value for this image, when compared.
    pub compare: Option<serde_json::Value>,
    /// `compare`'s text report, when compared.
    pub report_text: Option<String>,
    /// The student's image and FLIP's error map as PNGs in REPORT/, when
    /// compared.
    pub yours_image: Option<String>,
    pub error_map_image: Option<String>,
    /// Which file was taken when it is not the name asked for ("took
    /// Shadows.PNG for shadows.png").
    pub note: Option<String>,
    /// A match thanks to anti-aliased edges (issue 40).
    pub anti_aliased: bool,
    /// Set by hand in the assignment's `[[override]]`: `points` are the
    /// teacher's, for this reason.
    #[serde(rename = "override")]
    pub overridden: Option<Overridden>,
}

/// A grade set by hand.
#[derive(Clone, Debug, Serialize)]
pub struct Overridden {
    /// Why, as the assignment says.
    pub reason: String,
    /// The points grading gave before the override.
    pub graded_points: f64,
}

/// When Gradescope shows students a test (or the whole results): the
/// assignment's `visibility`, as its autograder specification names it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Visibility {
    /// Always.
    #[default]
    Visible,
    /// Never.
    Hidden,
    /// Once the due date (the late due date, if any) has passed.
    AfterDueDate,
    /// Once the grades are published.
    AfterPublished,
}
