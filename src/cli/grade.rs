//! `raystep grade`: a class's folders into REPORT/, or one submission for
//! an autograder's container, with its summary on stdout and the results
//! files Gradescope and PrairieLearn read. Everything that can be refused
//! (the assignment, its scenes, the folders, where the outputs go) is
//! refused before grading starts, so nothing is written then.

use std::fmt::Write as _;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{Context, Result};

use super::{GradeArgs, emit};
use raystep_engine::render::with_threads;
use raystep_tools::grade::{self, Assignment, Graded, ReportDir, Submissions};
use raystep_tools::output::{self, Target};

pub(super) fn run(args: &GradeArgs) -> Result<ExitCode> {
    let assignment = grade::assignment::load(&args.assignment)?;
    let class = match (&args.submissions, &args.submission) {
        (Some(folder), _) => grade::student_folders(folder)?,
        (None, Some(folder)) => Submissions::alone(folder)?,
        (None, None) => unreachable!("clap requires SUBMISSIONS or --submission"),
    };
    // A class must hold every student an override names; one submission
    // (an autograder's) takes the overrides that name it and no others.
    if args.submissions.is_some() {
        grade::assignment::check_students(
            &assignment.overrides,
            class.students.iter().map(|s| s.name()),
        )?;
    }
    let folders = args.submissions.as_ref().or(args.submission.as_ref());
    let report = args
        .output
        .as_deref()
        .map(|dir| ReportDir::check(dir, &inputs(args, &assignment, folders)))
        .transpose()?;
    for warning in report.iter().flat_map(ReportDir::warnings) {
        warn(warning);
    }
    let results = ResultsFiles::check(args, &assignment, &class, report.as_ref())?;
    let progress = progress_bar(class.students.len() * assignment.scenes.len());
    let tick = || progress.inc(1);
    let graded = with_threads(args.jobs.map(usize::from), || {
        grade::grade(&assignment, &class, &tick)
    })?;
    progress.finish_and_clear();
    if let Some(report) = &report {
        for warning in report.write(&graded.report_files()?)? {
            warn(&warning);
        }
    }
    results.write(&graded)?;
    let summary = match (&args.submission, &args.output) {
        (Some(_), _) => one_summary(&graded),
        (None, Some(dir)) => class_summary(&graded, dir),
        (None, None) => String::new(),
    };
    // It names REPORT/ as argv spelt it, and the assignment's titles and
    // file names: spelt as names are (`raystep_engine::printable`).
    emit(&raystep_engine::printable::printable_text(&summary))?;
    Ok(ExitCode::SUCCESS)
}

fn warn(warning: &str) {
    eprintln!(
        "warning: {}",
        raystep_engine::printable::printable_text(warning)
    );
}

/// What REPORT/ may neither be, hold nor lie in.
fn inputs<'a>(
    args: &'a GradeArgs,
    assignment: &'a Assignment,
    folders: Option<&'a PathBuf>,
) -> Vec<(&'a Path, String)> {
    let mut inputs = vec![(args.assignment.as_path(), "the assignment".to_string())];
    for scene in &assignment.scenes {
        inputs.push((scene.path.as_path(), "the scene file".to_string()));
        // Its meshes and MTL files.
        inputs.extend(
            (scene.scene.files.iter().skip(1))
                .map(|f| (f.as_path(), "a file a scene reads,".to_string())),
        );
    }
    inputs.extend(folders.map(|f| (f.as_path(), "the submissions folder".to_string())));
    inputs
}

/// The autograders' results files of `--submission`, checked before grading.
struct ResultsFiles {
    gradescope: Option<Target>,
    prairielearn: Option<Target>,
}

impl ResultsFiles {
    /// Checks the results files: against REPORT/ before a folder is made
    /// for them, then against each other and every input. A refused run
    /// leaves no folder it made.
    fn check(
        args: &GradeArgs,
        assignment: &Assignment,
        class: &Submissions,
        report: Option<&ReportDir>,
    ) -> Result<Self> {
        if let Some(report) = report {
            for (path, flag) in [
                (&args.gradescope, "--gradescope"),
                (&args.prairielearn, "--prairielearn"),
            ] {
                if let Some(path) = path {
                    report.refuse_overlap(path, flag)?;
                }
            }
        }
        let mut made = Vec::new();
        let checked = Self::check_made(args, assignment, class, &mut made);
        if checked.is_err() {
            // Deepest first, and only if still empty.
            for folder in made.iter().rev() {
                let _ = std::fs::remove_dir(folder);
            }
        }
        checked
    }

    fn check_made(
        args: &GradeArgs,
        assignment: &Assignment,
        class: &Submissions,
        made: &mut Vec<PathBuf>,
    ) -> Result<Self> {
        let mut target = |path: &Option<PathBuf>| -> Result<Option<Target>> {
            let Some(path) = path else { return Ok(None) };
            // An autograder's results folder may not exist yet (PrairieLearn
            // leaves /grade/results to the grader).
            if let Some(folder) = path.parent().filter(|p| !p.as_os_str().is_empty())
                && !folder.exists()
            {
                let missing: Vec<PathBuf> = (folder.ancestors())
                    .take_while(|f| !f.as_os_str().is_empty() && !f.exists())
                    .map(Path::to_owned)
                    .collect();
                std::fs::create_dir_all(folder)
                    .with_context(|| format!("cannot create {}", folder.display()))?;
                made.extend(missing.into_iter().rev());
            }
            output::file(path).map(Some)
        };
        let files = ResultsFiles {
            gradescope: target(&args.gradescope)?,
            prairielearn: target(&args.prairielearn)?,
        };
        let named: Vec<(&Target, String)> = [
            (&files.gradescope, "--gradescope"),
            (&files.prairielearn, "--prairielearn"),
        ]
        .into_iter()
        .filter_map(|(t, what)| t.as_ref().map(|t| (t, format!("the results of {what}"))))
        .collect();
        let mut inputs = output::Inputs::default().with(&args.assignment, "the assignment");
        for scene in &assignment.scenes {
            inputs = inputs.with_scene(&scene.scene);
        }
        // The files as named, and those taken for them (`Shadows.PNG`).
        let submitted: Vec<_> = (class.students.iter())
            .flat_map(|student| student.submitted_files(assignment))
            .collect();
        for file in &submitted {
            inputs = inputs.with(file, "the submission");
        }
        output::refuse_clashes(&inputs, &named)?;
        Ok(files)
    }

    fn write(&self, graded: &Graded) -> Result<()> {
        let Some(student) = graded.grades.students.first() else {
            return Ok(());
        };
        if let Some(target) = &self.gradescope {
            let value = grade::gradescope_results(&graded.grades, student);
            output::write_text(target, &(serde_json::to_string_pretty(&value)? + "\n"))?;
        }
        if let Some(target) = &self.prairielearn {
            output::write_text(target, &grade::prairielearn_results(graded, student))?;
        }
        Ok(())
    }
}

/// One submission, scene by scene.
fn one_summary(graded: &Graded) -> String {
    let grades = &graded.grades;
    let mut out = String::new();
    for student in &grades.students {
        let _ = writeln!(
            out,
            "{}: {} of {} points",
            grades.title,
            grade::points_text(student.total),
            grade::points_text(grades.max_total)
        );
        let width = grades
            .scenes
            .iter()
            .map(|s| s.submit.chars().count())
            .max()
            .unwrap_or(0);
        for (sheet, scene) in grades.scenes.iter().zip(&student.scenes) {
            let verdict = match (&scene.refused, scene.matches, scene.flip_mean) {
                (Some(reason), _, _) => format!("not graded: {reason}"),
                (None, true, Some(flip)) => format!("matches (FLIP {flip:.4})"),
                (None, false, flip) => {
                    let likely = scene
                        .mistakes
                        .first()
                        .map_or(String::new(), |m| format!(", likely {m}"));
                    format!("differs{likely} (FLIP {:.4})", flip.unwrap_or(0.0))
                }
                (None, true, None) => "matches".to_string(),
            };
            let verdict = match &scene.overridden {
                Some(o) => format!(
                    "{verdict}; overridden by hand: {} (graded {})",
                    o.reason,
                    grade::points_text(o.graded_points)
                ),
                None => verdict,
            };
            let _ = writeln!(
                out,
                "  {:<width$}  {:>6} of {:<6}  {verdict}",
                sheet.submit,
                grade::points_text(scene.points),
                grade::points_text(scene.max_points),
            );
        }
        // How the files were found, when not as named.
        let scene_notes = student.scenes.iter().filter_map(|s| s.note.as_ref());
        for note in student.notes.iter().chain(scene_notes) {
            let _ = writeln!(out, "  note: {note}");
        }
    }
    out
}

/// The class in one line, and where the report is.
fn class_summary(graded: &Graded, dir: &Path) -> String {
    let grades = &graded.grades;
    let count = grades.students.len();
    let mean = grades.students.iter().map(|s| s.total).sum::<f64>() / count.max(1) as f64;
    format!(
        "graded {} on {}: mean {} of {} points; the report is in {}\n",
        raystep_engine::record::count(count as u64, "student", "students"),
        raystep_engine::record::count(grades.scenes.len() as u64, "scene", "scenes"),
        grade::points_text((mean * 100.0).round() / 100.0),
        grade::points_text(grades.max_total),
        dir.display()
    )
}

/// A progress bar on stderr when it is a terminal; hidden otherwise.
fn progress_bar(submissions: usize) -> indicatif::ProgressBar {
    if !std::io::stderr().is_terminal() {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(submissions as u64);
    if let Ok(style) = indicatif::ProgressStyle::with_template(
        "{spinner} grading {bar:40} {pos}/{len} images {elapsed}",
    ) {
        bar.set_style(style);
    }
    bar
}
