//! The assignment file: the scenes a class renders, the file each student
//! hands in for each, and what each is worth. TOML, read as scene files are
//! read: unknown keys are refused and every error points at its file, line
//! and column. Each scene is loaded as `raystep render` loads it, at the
//! size the assignment asks for.
//!
//! ```toml
//! title = "A5: Whitted ray tracing"
//!
//! [[scene]]
//! file = "glass.toml"   # relative to this file; TOML or NFF
//! submit = "glass.png"  # the file each student hands in for it
//! points = 10
//! size = [160, 120]     # optional: default, the scene's own size
//! partial = true        # optional: partial credit from FLIP (default false)
//! max_flip = 0.2        # optional, with partial: the FLIP mean that scores 0
//! ```
//!
//! How students hand in, and what Gradescope shows them (each optional):
//!
//! ```toml
//! strict_names = true         # take only files named exactly as `submit` says
//! visibility = "after_due_date"   # Gradescope's, for every scene's test
//!
//! [[scene]]
//! # ...
//! visibility = "hidden"       # this scene's test alone
//! ```
//!
//! The match rule's knobs (`match_rule`) and grades set by hand
//! (`[[override]]`, `overrides`) have modules of their own.

use std::collections::HashSet;
use std::ops::Range;
use std::path::{Path, PathBuf};

use serde::Deserialize;
use toml::Spanned;

use super::model::Visibility;
use crate::compare::MatchRule;
use crate::compare::student::check_compared_size;
use raystep_engine::input_file::{self, Cap};
use raystep_engine::scene::{self, Scene, SceneError, check_image_size};

mod by_hand;
mod match_rule;
pub use by_hand::{Override, check_students};

/// With `partial` and no `max_flip`: the FLIP mean that scores 0. Every
/// classic mistake of the catalogue that changes much of the image scores
/// FLIP means of a few hundredths to a few tenths on the example scenes.
pub(crate) const DEFAULT_MAX_FLIP: f64 = 0.2;

/// The largest assignment file read: a few lines a scene.
pub(crate) const ASSIGNMENT_CAP: Cap = Cap {
    bytes: 16 << 20,
    of: "an assignment file",
};

/// An assignment, its scenes loaded.
/// The most points one scene may give: a million, so that totals and
/// hundredths stay finite whatever the number of scenes.
pub(crate) const MAX_POINTS: f64 = 1e6;

pub struct Assignment {
    pub(crate) title: String,
    pub scenes: Vec<AssignedScene>,
    /// How students hand in, and what Gradescope shows them.
    pub(crate) handing_in: HandingIn,
    /// Grades set by hand (`[[override]]`).
    pub overrides: Vec<Override>,
}

/// The assignment's top-level keys on handing in and the autograders.
#[derive(Clone, Copy, Default)]
pub(crate) struct HandingIn {
    /// Take only files named exactly as `submit` says: a near miss
    /// (`Shadows.PNG`) is refused, naming it.
    pub strict_names: bool,
    /// Gradescope's visibility of the results, and of every scene's test
    /// that does not set its own.
    pub visibility: Visibility,
}

/// One scene of the assignment.
pub struct AssignedScene {
    /// The scene file as the assignment names it.
    pub(crate) file: String,
    /// Where it was read from: the assignment's folder joined to `file`.
    pub path: PathBuf,
    /// The file name each student hands in for it.
    pub submit: String,
    pub(crate) points: f64,
    /// With partial credit, the FLIP mean that scores 0.
    pub(crate) max_flip: Option<f64>,
    /// What a match allows.
    pub(crate) rule: MatchRule,
    /// Loaded at the size every submission must have.
    pub scene: Scene,
    /// Gradescope's visibility of this scene's test.
    pub(crate) visibility: Visibility,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileDef {
    title: Option<String>,
    #[serde(default)]
    scene: Vec<SceneDef>,
    // Handing in and the autograders.
    #[serde(default)]
    strict_names: bool,
    visibility: Option<Visibility>,
    // Issue 40: the match rule for every scene, and grades set by hand.
    tolerance: Option<Spanned<i64>>,
    far_off_allowed: Option<Spanned<i64>>,
    antialiasing: Option<Spanned<bool>>,
    // Issue 42: CSE 167's pass rule in place of the match rule.
    hot_pixels_allowed: Option<Spanned<i64>>,
    #[serde(default, rename = "override")]
    overrides: Vec<by_hand::OverrideDef>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneDef {
    file: Spanned<String>,
    submit: Spanned<String>,
    points: Spanned<f64>,
    size: Option<Spanned<[u32; 2]>>,
    #[serde(default)]
    partial: bool,
    max_flip: Option<Spanned<f64>>,
    // Handing in and the autograders.
    visibility: Option<Visibility>,
    // Issue 40: the match rule for this scene (the top's where not given).
    tolerance: Option<Spanned<i64>>,
    far_off_allowed: Option<Spanned<i64>>,
    antialiasing: Option<Spanned<bool>>,
    hot_pixels_allowed: Option<Spanned<i64>>,
}

/// Reads the assignment at `path` and loads its scenes.
pub fn load(path: &Path) -> Result<Assignment, SceneError> {
    let bytes = input_file::read(path, "the assignment", ASSIGNMENT_CAP)
        .map_err(|e| SceneError::plain(e.to_string()))?;
    let text = String::from_utf8(bytes).map_err(|e| {
        SceneError::plain(format!(
            "{} is not UTF-8 text (byte {} is 0x{:02X}): assignment files must be UTF-8",
            path.display(),
            e.utf8_error().valid_up_to(),
            e.as_bytes()[e.utf8_error().valid_up_to()]
        ))
    })?;
    parse(path, &text)
}

/// Parses assignment text; `path` names it in messages, and scene files
/// are found relative to its folder.
pub(crate) fn parse(path: &Path, text: &str) -> Result<Assignment, SceneError> {
    let error = |span: Range<usize>, message: String| SceneError::at(path, text, span, message);
    let file: FileDef = toml::from_str(text).map_err(|e| {
        let message = e.message().trim_end().to_string();
        match e.span() {
            Some(span) => error(span, message),
            None => SceneError::plain(format!("{}: {message}", path.display())),
        }
    })?;
    if file.scene.is_empty() {
        return Err(SceneError::plain(format!(
            "{}: an assignment needs at least one [[scene]], with file, submit and points",
            path.display()
        )));
    }
    let handing_in = HandingIn {
        strict_names: file.strict_names,
        visibility: file.visibility.unwrap_or_default(),
    };
    let folder = path.parent().unwrap_or(Path::new(""));
    let knobs = |tolerance, far_off_allowed, antialiasing, hot_pixels_allowed| match_rule::Knobs {
        tolerance,
        far_off_allowed,
        antialiasing,
        hot_pixels_allowed,
    };
    let every_scene = knobs(
        file.tolerance,
        file.far_off_allowed,
        file.antialiasing,
        file.hot_pixels_allowed,
    )
    .rule(MatchRule::default())
    .map_err(|(span, m)| error(span, m))?;
    let mut submits = HashSet::new();
    let mut scenes = Vec::with_capacity(file.scene.len());
    for def in file.scene {
        check_submit(def.submit.get_ref()).map_err(|m| error(def.submit.span(), m))?;
        if !submits.insert(def.submit.get_ref().clone()) {
            return Err(error(
                def.submit.span(),
                format!(
                    "two scenes ask for the same file {:?}: each scene needs its own",
                    def.submit.get_ref()
                ),
            ));
        }
        // At most MAX_POINTS, so that no total or hundredth overflows
        // (1e308 gave an infinite total, written `inf` and `null`); -0 is 0.
        let points = *def.points.get_ref() + 0.0;
        if !(points.is_finite() && (0.0..=MAX_POINTS).contains(&points)) {
            return Err(error(
                def.points.span(),
                format!(
                    "points must be a number from 0 to {MAX_POINTS}, got {}",
                    if points.abs() >= 1e9 {
                        format!("{points:e}")
                    } else {
                        points.to_string()
                    }
                ),
            ));
        }
        let max_flip = match (def.partial, &def.max_flip) {
            (false, Some(max)) => {
                return Err(error(
                    max.span(),
                    "max_flip counts only with partial = true: add it, or leave max_flip out"
                        .into(),
                ));
            }
            (false, None) => None,
            (true, None) => Some(DEFAULT_MAX_FLIP),
            (true, Some(max)) => {
                let value = *max.get_ref();
                if !(value.is_finite() && value > 0.0) {
                    return Err(error(
                        max.span(),
                        format!("max_flip must be a number above 0, got {value}"),
                    ));
                }
                Some(value)
            }
        };
        let rule = knobs(
            def.tolerance,
            def.far_off_allowed,
            def.antialiasing,
            def.hot_pixels_allowed,
        )
        .rule(every_scene)
        .map_err(|(span, m)| error(span, m))?;
        let scene_path = folder.join(def.file.get_ref());
        // A FIFO, a device or a folder is said to be one, as for every
        // other input (it was "no scene file").
        let exists = input_file::is_regular(&scene_path, "the scene file")
            .map_err(|e| error(def.file.span(), e.to_string()))?;
        if !exists {
            return Err(error(
                def.file.span(),
                format!(
                    "no scene file {} (scene files are found from the assignment's folder)",
                    scene_path.display()
                ),
            ));
        }
        let scene = scene::load(&scene_path)?;
        let scene = match &def.size {
            None => scene,
            Some(size) => {
                let [width, height] = *size.get_ref();
                check_image_size(width, height).map_err(|m| error(size.span(), m))?;
                scene
                    .with_size(width, height)
                    .map_err(|e| error(size.span(), e.message))?
            }
        };
        // Every student's image is compared at this size: refuse it once
        // here, not once per student.
        let size_span = def.size.as_ref().map_or(def.file.span(), |s| s.span());
        check_compared_size(scene.width, scene.height).map_err(|m| error(size_span, m))?;
        scenes.push(AssignedScene {
            file: def.file.into_inner(),
            path: scene_path,
            submit: def.submit.into_inner(),
            points,
            max_flip,
            rule,
            scene,
            visibility: def.visibility.unwrap_or(handing_in.visibility),
        });
    }
    let title = file.title.unwrap_or_else(|| {
        path.file_stem()
            .map_or("assignment".into(), |s| s.to_string_lossy().into_owned())
    });
    let overrides = by_hand::read(path, text, file.overrides, &scenes)?;
    Ok(Assignment {
        title,
        scenes,
        overrides,
        handing_in,
    })
}

/// A file name each student's folder can hold: one name, no folders.
fn check_submit(name: &str) -> Result<(), String> {
    let plain =
        !name.is_empty() && name != "." && name != ".." && !name.contains(['/', '\\', '\0']);
    if plain {
        Ok(())
    } else {
        Err(format!(
            "submit must be a file name in the student's folder, such as \"glass.png\", got {name:?}"
        ))
    }
}

/// An assignment file in scenes/, beside the scenes it names, for tests.
#[cfg(test)]
pub(crate) fn test_path() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/a.toml")
}

/// `parse` of `text` as `test_path()`; refused, the message's first line.
#[cfg(test)]
pub(crate) fn test_parsed(text: &str) -> Result<Assignment, String> {
    parse(&test_path(), text).map_err(|e| e.to_string().lines().next().unwrap().to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `parse` from a folder holding glass.toml, as scenes/ does.
    fn parse_here(text: &str) -> Result<Assignment, SceneError> {
        parse(&test_path(), text)
    }

    fn error(text: &str) -> String {
        let message = parse_here(text).err().expect("refused").to_string();
        message.lines().next().unwrap().to_string()
    }

    #[test]
    fn a_scene_takes_its_own_size_unless_the_assignment_gives_one() {
        let assignment = parse_here(
            "title = \"A5\"\n[[scene]]\nfile = \"glass.toml\"\nsubmit = \"glass.png\"\npoints = 10\n\
             [[scene]]\nfile = \"shadows.toml\"\nsubmit = \"s.png\"\npoints = 2.5\nsize = [32, 24]\n\
             partial = true\n",
        )
        .unwrap();
        assert_eq!(assignment.title, "A5");
        let [glass, shadows] = &assignment.scenes[..] else {
            panic!("two scenes")
        };
        // glass.toml says 160 x 120 in its [image].
        assert_eq!((glass.scene.width, glass.scene.height), (160, 120));
        assert_eq!((glass.points, glass.max_flip), (10.0, None));
        assert_eq!((shadows.scene.width, shadows.scene.height), (32, 24));
        // Partial credit without max_flip: the documented default.
        assert_eq!(shadows.max_flip, Some(DEFAULT_MAX_FLIP));
        assert!(glass.path.ends_with("scenes/glass.toml"));
    }

    #[test]
    fn mistakes_in_the_file_are_told_at_their_line_and_column() {
        let head = "[[scene]]\nfile = \"glass.toml\"\nsubmit = \"glass.png\"\n";
        let file = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../..")
            .join("scenes/a.toml");
        let at = |line_col: &str| format!("{}:{line_col}: ", file.display());
        // A misspelt key: line 5, column 1.
        let message = error(&format!("{head}points = 10\npartal = true\n"));
        assert!(message.starts_with(&at("5:1")), "{message}");
        assert!(message.contains("unknown field `partal`"), "{message}");
        // max_flip at or below 0, or not finite: at the value, line 6 col 12.
        for bad in ["0", "-0.1", "nan", "inf"] {
            let message = error(&format!(
                "{head}points = 10\npartial = true\nmax_flip = {bad}\n"
            ));
            assert!(message.starts_with(&at("6:12")), "{message}");
            assert!(message.contains("max_flip must be a number above 0"));
        }
        let message = error(&format!("{head}points = 10\nmax_flip = 0.1\n"));
        assert!(message.starts_with(&at("5:12")), "{message}");
        assert!(message.contains("only with partial = true"), "{message}");
        let message = error(&format!("{head}points = -1\n"));
        assert!(message.starts_with(&at("4:10")), "{message}");
        // 1e308 is finite, but 100 of it (hundredths) and any sum of two are
        // not: refused at its line and column.
        let message = error(&format!("{head}points = 1e308\n"));
        assert!(message.starts_with(&at("4:10")), "{message}");
        assert!(
            message.contains("from 0 to 1000000, got 1e308"),
            "{message}"
        );
        // -0 reads as 0, never printed "-0".
        let zero = parse_here(&format!("{head}points = -0.0\n")).unwrap();
        assert_eq!(zero.scenes[0].points.to_bits(), 0.0f64.to_bits());
        let message = error(&format!("{head}points = 1\nsize = [0, 10]\n"));
        assert!(message.starts_with(&at("5:8")), "{message}");
        assert!(message.contains("image size 0x10 is empty"), "{message}");
        // A size raystep renders but does not compare (2048 x 2048 pixels
        // at most): refused once here, not once per student.
        let message = error(&format!("{head}points = 1\nsize = [4096, 2048]\n"));
        assert!(message.starts_with(&at("5:8")), "{message}");
        assert!(
            message.contains("4096x2048 is too large to compare"),
            "{message}"
        );
        let message =
            error("[[scene]]\nfile = \"glass.toml\"\nsubmit = \"../x.png\"\npoints = 1\n");
        assert!(message.starts_with(&at("3:10")), "{message}");
        let message = error(&format!(
            "{head}points = 1\n[[scene]]\nfile = \"shadows.toml\"\nsubmit = \"glass.png\"\npoints = 1\n"
        ));
        assert!(message.starts_with(&at("7:10")), "{message}");
        assert!(message.contains("the same file \"glass.png\""), "{message}");
        let message = error("[[scene]]\nfile = \"nope.toml\"\nsubmit = \"x.png\"\npoints = 1\n");
        assert!(message.starts_with(&at("2:8")), "{message}");
        assert!(message.contains("no scene file"), "{message}");
        let message = error("title = \"empty\"\n");
        assert!(message.contains("at least one [[scene]]"), "{message}");
    }

    #[test]
    fn handing_in_and_gradescopes_visibility_are_read_and_checked() {
        let scene = |extra: &str| {
            format!("[[scene]]\nfile = \"glass.toml\"\nsubmit = \"glass.png\"\npoints = 1\n{extra}")
        };
        // The defaults: names near the one asked for are taken; visible.
        let plain = parse_here(&scene("")).unwrap();
        assert!(!plain.handing_in.strict_names);
        assert_eq!(plain.handing_in.visibility, Visibility::Visible);
        assert_eq!(plain.scenes[0].visibility, Visibility::Visible);
        // A scene's own visibility wins over the assignment's.
        let set = parse_here(&format!(
            "strict_names = true\nvisibility = \"after_due_date\"\n{}{}",
            scene(""),
            scene("visibility = \"hidden\"\n").replace("glass.png", "g2.png")
        ))
        .unwrap();
        assert!(set.handing_in.strict_names);
        assert_eq!(set.handing_in.visibility, Visibility::AfterDueDate);
        let scenes: Vec<Visibility> = set.scenes.iter().map(|s| s.visibility).collect();
        assert_eq!(scenes, [Visibility::AfterDueDate, Visibility::Hidden]);
        let published = parse_here(&scene("visibility = \"after_published\"\n")).unwrap();
        assert_eq!(published.scenes[0].visibility, Visibility::AfterPublished);
        // A value Gradescope does not know, at its line and column: 1:14,
        // and in a scene 5:14; strict_names must be true or false (1:16).
        let file = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../..")
            .join("scenes/a.toml");
        let at = |line_col: &str| format!("{}:{line_col}: ", file.display());
        let message = error(&format!("visibility = \"later\"\n{}", scene("")));
        assert!(message.starts_with(&at("1:14")), "{message}");
        assert!(
            message.contains(
                "unknown variant `later`, expected one of `visible`, `hidden`, \
                 `after_due_date`, `after_published`"
            ),
            "{message}"
        );
        let message = error(&scene("visibility = \"Visible\"\n"));
        assert!(message.starts_with(&at("5:14")), "{message}");
        let message = error(&format!("strict_names = \"yes\"\n{}", scene("")));
        assert!(message.starts_with(&at("1:16")), "{message}");
    }

    #[test]
    fn the_example_and_readmes_assignment_load() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
        let example = load(&root.join("scenes/assignments/a5.toml")).unwrap();
        assert_eq!(example.title, "A5: Whitted ray tracing");
        let submits: Vec<&str> = example.scenes.iter().map(|s| s.submit.as_str()).collect();
        assert_eq!(
            submits,
            [
                "shadows.png",
                "highlights.png",
                "mirrors.png",
                "glass.png",
                "attenuation.png"
            ]
        );
        for scene in &example.scenes {
            assert_eq!((scene.scene.width, scene.scene.height), (160, 120));
        }
        // 10 + 10 + 10 + 20 + 10; glass and attenuation with partial credit.
        assert_eq!(example.scenes.iter().map(|s| s.points).sum::<f64>(), 60.0);
        let partial: Vec<Option<f64>> = example.scenes.iter().map(|s| s.max_flip).collect();
        assert_eq!(
            partial,
            [None, None, None, Some(0.2), Some(DEFAULT_MAX_FLIP)]
        );
        // TEACHERS.md's block, its scene found beside the example scenes.
        let guide = std::fs::read_to_string(root.join("docs/TEACHERS.md")).unwrap();
        let start = guide
            .find("```toml\ntitle = ")
            .expect("TEACHERS.md's assignment")
            + 8;
        let end = start + guide[start..].find("```").unwrap();
        let block = parse_here(&guide[start..end]).unwrap();
        assert_eq!(block.scenes.len(), 1);
        assert_eq!(block.scenes[0].max_flip, Some(0.2));
    }
}
