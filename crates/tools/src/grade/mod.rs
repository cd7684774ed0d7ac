//! `raystep grade`: a whole class's renders graded against an assignment's
//! scenes in one run. Each scene's renders are made once and shared by every
//! student (`compare::SceneRenders`); students are graded in parallel; one
//! student's bad file scores 0 for that scene with the reason, and never
//! stops the class.
//!
//! Everything found goes into one value, `model::ClassGrades`, that every
//! output is written from: grades.csv (`csv_table`), grades.json, the
//! autograder files (`gradescope`, `prairielearn`) and the HTML report
//! (`html`).
//! REPORT/ is written as a whole or not at all (`report_dir`).

pub mod assignment;
mod csv_table;
mod gradescope;
pub(crate) mod html;
mod locate;
pub mod model;
mod prairielearn;
mod report_dir;
mod scoring;
mod slug;
mod submission;

use std::ffi::OsString;
use std::fs;
use std::io::Cursor;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use image::RgbImage;
use rayon::prelude::*;

pub use assignment::Assignment;
pub(crate) use csv_table::csv;
pub use csv_table::number as points_text;
pub use gradescope::results as gradescope_results;
pub use model::{ClassGrades, Overridden, SceneGrade, SceneSheet, StudentGrades, Visibility};
pub use prairielearn::results as prairielearn_results;
pub use report_dir::ReportDir;

use crate::compare::{self, SceneRenders};

/// One student's folder.
pub struct Student {
    /// Its name as read (invalid UTF-8 replaced by U+FFFD).
    pub(crate) name: String,
    pub folder: PathBuf,
}

impl Student {
    /// The folder's name as the grades write it.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The files this student hands in for `assignment`, where they are
    /// found (the names asked for, and the near misses taken for them).
    pub fn submitted_files(&self, assignment: &Assignment) -> Vec<PathBuf> {
        let mut files: Vec<PathBuf> = assignment
            .scenes
            .iter()
            .map(|s| self.folder.join(&s.submit))
            .collect();
        if let Ok(root) = fs::canonicalize(&self.folder)
            && let Ok(found) = locate::locate(
                &root,
                &submits(assignment),
                assignment.handing_in.strict_names,
            )
        {
            files
                .extend((found.files.iter().flatten()).map(|taken| found.folder.join(&taken.name)));
        }
        files
    }
}

/// The students to grade, and what lay beside them.
pub struct Submissions {
    pub students: Vec<Student>,
    /// What SUBMISSIONS/ holds that is not a student (`ClassGrades::ignored`).
    pub ignored: Vec<String>,
}

impl Submissions {
    /// A folder given by itself (`--submission DIR`), named after its last part.
    pub fn alone(folder: &Path) -> Result<Submissions> {
        let meta = fs::metadata(folder)
            .with_context(|| format!("cannot read the submission folder {}", folder.display()))?;
        if !meta.is_dir() {
            bail!(
                "cannot read the submission folder {}: it is not a folder",
                folder.display()
            );
        }
        let real = fs::canonicalize(folder)
            .with_context(|| format!("cannot read the submission folder {}", folder.display()))?;
        let name = real
            .file_name()
            .map_or("submission".into(), |n| n.to_string_lossy().into_owned());
        Ok(Submissions {
            students: vec![Student {
                name,
                folder: folder.to_owned(),
            }],
            ignored: Vec::new(),
        })
    }
}

/// The student folders in `submissions`, sorted by their names' bytes
/// (as `StudentGrades::student` holds them), and what lies beside them.
/// What a system or an archiver leaves (`locate::is_junk`: `__MACOSX`, dot
/// names, `Thumbs.db`, `desktop.ini`) and files beside the folders (a
/// platform's metadata file) are not students; a folder that holds none is
/// refused.
pub fn student_folders(submissions: &Path) -> Result<Submissions> {
    let shown = submissions.display();
    let entries = fs::read_dir(submissions)
        .with_context(|| format!("cannot read the submissions folder {shown}"))?;
    let mut found: Vec<(OsString, PathBuf)> = Vec::new();
    let mut ignored = Vec::new();
    for entry in entries {
        let entry = entry.with_context(|| format!("cannot read the submissions folder {shown}"))?;
        let name = entry.file_name();
        // A link to a folder counts as that folder.
        if !locate::is_junk(&name) && fs::metadata(entry.path()).is_ok_and(|m| m.is_dir()) {
            found.push((name, entry.path()));
        } else {
            ignored.push(name.to_string_lossy().into_owned());
        }
    }
    if found.is_empty() {
        bail!(
            "no student folder in {shown}: it must hold one folder per student, each with \
             the files the assignment names ({shown}/<student>/<file>.png)"
        );
    }
    ignored.sort();
    let mut students: Vec<(Student, OsString)> = found
        .into_iter()
        .map(|(raw, folder)| {
            let name = raw.to_string_lossy().into_owned();
            (Student { name, folder }, raw)
        })
        .collect();
    // By the name as written in the grades; two names that read the same
    // there (different bytes that are not UTF-8) by their own bytes.
    students.sort_by(|(a, a_raw), (b, b_raw)| {
        (a.name.as_bytes(), a_raw.as_encoded_bytes())
            .cmp(&(b.name.as_bytes(), b_raw.as_encoded_bytes()))
    });
    Ok(Submissions {
        students: students.into_iter().map(|(student, _)| student).collect(),
        ignored,
    })
}

/// The file names `assignment` asks for, in its order.
fn submits(assignment: &Assignment) -> Vec<&str> {
    assignment
        .scenes
        .iter()
        .map(|s| s.submit.as_str())
        .collect()
}

/// Files of REPORT/: each one's path in it (with `/`) and its bytes.
pub(crate) type Files = Vec<(String, Vec<u8>)>;

/// What grading found: the grades, and the PNGs they name.
pub struct Graded {
    pub grades: ClassGrades,
    /// Each image the grades name: its path in REPORT/ and its PNG bytes.
    pub(crate) images: Files,
}

impl Graded {
    /// The PNG at `path` (a path the grades name).
    pub(crate) fn image(&self, path: &str) -> Option<&[u8]> {
        self.images
            .iter()
            .find(|(p, _)| p == path)
            .map(|(_, bytes)| bytes.as_slice())
    }

    /// Every file of REPORT/: the table, the JSON and the images.
    pub fn report_files(&self) -> Result<Files> {
        let mut files = vec![
            ("grades.csv".to_string(), csv(&self.grades).into_bytes()),
            (
                "grades.json".to_string(),
                (serde_json::to_string_pretty(&self.grades)? + "\n").into_bytes(),
            ),
        ];
        files.extend(self.images.iter().cloned());
        files.extend(
            html::pages(&self.grades)
                .into_iter()
                .map(|(path, page)| (path, page.into_bytes())),
        );
        Ok(files)
    }
}

/// Grades every student of `students` on every scene of `assignment`;
/// `done` is called once per student and scene graded (from any thread).
pub fn grade(
    assignment: &Assignment,
    submissions: &Submissions,
    done: &(dyn Fn() + Sync),
) -> Graded {
    let students = &submissions.students;
    let scene_slugs = slug::slugs(assignment.scenes.iter().map(|s| stem(&s.submit)), "scene");
    let shared: Vec<SceneRenders> = assignment
        .scenes
        .iter()
        .map(|s| SceneRenders::new(&s.scene))
        .collect();
    if students.len() > 1 {
        // What every student who differs needs, rendered once up front,
        // not by every thread at once.
        shared.iter().for_each(compare::prepare);
    }
    let sheets: Vec<SceneSheet> = assignment
        .scenes
        .iter()
        .zip(&scene_slugs)
        .map(|(s, slug)| SceneSheet {
            file: s.file.clone(),
            submit: s.submit.clone(),
            points: s.points,
            width: s.scene.width,
            height: s.scene.height,
            partial: s.max_flip.is_some(),
            max_flip: s.max_flip,
            reference_image: format!("reference/{slug}.png"),
            visibility: s.visibility,
            tolerance: s.rule.tolerance_steps,
            far_off_allowed: s.rule.far_off_allowed,
            antialiasing: s.rule.antialiasing,
            hot_pixels_allowed: s.rule.hot_pixels_allowed,
        })
        .collect();
    let mut images: Files = sheets
        .iter()
        .zip(&shared)
        .map(|(sheet, renders)| {
            (
                sheet.reference_image.clone(),
                png(&renders.reference().image),
            )
        })
        .collect();
    let student_slugs = slug::slugs(students.iter().map(|s| s.name.as_str()), "student");
    let graded: Vec<(StudentGrades, Files)> = students
        .par_iter()
        .zip(&student_slugs)
        .map(|(student, slug)| {
            let work = Work {
                assignment,
                shared: &shared,
                scene_slugs: &scene_slugs,
                done,
            };
            work.student(student, slug)
        })
        .collect();
    let mut grades = Vec::with_capacity(graded.len());
    for (mut student, files) in graded {
        set_by_hand(&mut student, &assignment.overrides);
        grades.push(student);
        images.extend(files);
    }
    Graded {
        grades: ClassGrades {
            title: assignment.title.clone(),
            max_total: scoring::total(assignment.scenes.iter().map(|s| s.points)),
            scenes: sheets,
            students: grades,
            ignored: submissions.ignored.clone(),
            visibility: assignment.handing_in.visibility,
        },
        images,
    }
}

/// What grading one student needs.
struct Work<'a> {
    assignment: &'a Assignment,
    shared: &'a [SceneRenders<'a>],
    scene_slugs: &'a [String],
    done: &'a (dyn Fn() + Sync),
}

impl Work<'_> {
    /// One student's grades, and the PNGs they name.
    fn student(&self, student: &Student, slug: &str) -> (StudentGrades, Files) {
        // Every file must lie in the folder as it really is.
        let found = fs::canonicalize(&student.folder)
            .map_err(|e| format!("cannot read the student's folder: {e}"))
            .and_then(|root| {
                let submits = submits(self.assignment);
                let strict = self.assignment.handing_in.strict_names;
                locate::locate(&root, &submits, strict).map(|found| (root, found))
            });
        let mut images = Vec::new();
        let mut scenes = Vec::with_capacity(self.assignment.scenes.len());
        for (i, scene) in self.assignment.scenes.iter().enumerate() {
            let size = (scene.scene.width, scene.scene.height);
            let taken = found
                .as_ref()
                .map_err(Clone::clone)
                .and_then(|(root, found)| Ok((root, found, found.files[i].as_ref()?)));
            let note = taken.as_ref().ok().and_then(|(_, _, t)| t.note.clone());
            let read = taken.and_then(|(root, found, taken)| {
                submission::read(root, &found.folder, &taken.name, size)
            });
            let compared = read.and_then(|image| {
                let yours_png = png(&image.image);
                compare::compare_with(&self.shared[i], image, &scene.rule)
                    .map(|comparison| (yours_png, comparison))
                    .map_err(|e| format!("{e:#}"))
            });
            let grade = match compared {
                Err(reason) => refused(scene.points, reason),
                Ok((yours_png, comparison)) => {
                    let base = format!("images/{slug}/{}", self.scene_slugs[i]);
                    let (yours, error_map) =
                        (format!("{base}.yours.png"), format!("{base}.flip.png"));
                    images.push((yours.clone(), yours_png));
                    let (Some(map), Some(flip)) =
                        (&comparison.error_map, comparison.metrics.flip_mean)
                    else {
                        unreachable!("grade is built with FLIP (the flip feature)")
                    };
                    images.push((error_map.clone(), png(map)));
                    SceneGrade {
                        points: scoring::points(
                            scene.points,
                            comparison.matches,
                            flip,
                            scene.max_flip,
                        ),
                        max_points: scene.points,
                        refused: None,
                        matches: comparison.matches,
                        flip_mean: Some(flip),
                        mistakes: comparison
                            .mistakes
                            .iter()
                            .map(|r| r.mistake.name().to_string())
                            .collect(),
                        compare: serde_json::to_value(&comparison).ok(),
                        report_text: Some(compare::text(&comparison, &scene.submit, &scene.file)),
                        yours_image: Some(yours),
                        error_map_image: Some(error_map),
                        note: None,
                        anti_aliased: comparison.matches
                            && comparison.metrics.anti_aliased_pixels > 0,
                        overridden: None,
                    }
                }
            };
            let grade = SceneGrade { note, ..grade };
            scenes.push(grade);
            (self.done)();
        }
        let total = scoring::total(scenes.iter().map(|s| s.points));
        let grades = StudentGrades {
            student: student.name.clone(),
            slug: slug.to_string(),
            scenes,
            total,
            notes: found.map(|(_, found)| found.notes).unwrap_or_default(),
        };
        (grades, images)
    }
}

/// A submission that could not be compared: 0 points, and why.
fn refused(max_points: f64, reason: String) -> SceneGrade {
    SceneGrade {
        points: 0.0,
        max_points,
        refused: Some(reason),
        matches: false,
        flip_mean: None,
        mistakes: Vec::new(),
        compare: None,
        report_text: None,
        yours_image: None,
        error_map_image: None,
        note: None,
        anti_aliased: false,
        overridden: None,
    }
}

/// The student's grades with the assignment's `[[override]]`s for them
/// applied: the points set, the graded ones kept beside the reason, the
/// total summed again.
fn set_by_hand(student: &mut StudentGrades, overrides: &[assignment::Override]) {
    let mine = overrides.iter().filter(|o| o.student == student.student);
    let mut any = false;
    for o in mine {
        let grade = &mut student.scenes[o.scene];
        grade.overridden = Some(Overridden {
            reason: o.reason.clone(),
            graded_points: grade.points,
        });
        grade.points = scoring::hundredths(o.points);
        any = true;
    }
    if any {
        student.total = scoring::total(student.scenes.iter().map(|s| s.points));
    }
}

/// A file name without its extension (`glass.png` -> `glass`).
fn stem(name: &str) -> &str {
    Path::new(name)
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or(name)
}

/// `image` as PNG bytes.
fn png(image: &RgbImage) -> Vec<u8> {
    let mut bytes = Cursor::new(Vec::new());
    image
        .write_to(&mut bytes, image::ImageFormat::Png)
        .expect("a PNG is written to memory");
    bytes.into_inner()
}
