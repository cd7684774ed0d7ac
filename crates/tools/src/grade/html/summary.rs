//! The class in one line at the top of index.html: how many students, the
//! mean and median total, how many matched every scene, how many students
//! had a file refused (and how many files: one student may have several).

use super::escape::escape;
use crate::grade::model::ClassGrades;
use crate::grade::points_text as points;

pub(super) fn summary(class: &ClassGrades) -> String {
    let students = class.students.len();
    if students == 0 {
        return "<p class=\"summary\">No student folders were found.</p>".into();
    }
    let mut totals: Vec<f64> = class.students.iter().map(|s| s.total).collect();
    totals.sort_by(f64::total_cmp);
    let mean = totals.iter().sum::<f64>() / students as f64;
    let median = if students % 2 == 1 {
        totals[students / 2]
    } else {
        (totals[students / 2 - 1] + totals[students / 2]) / 2.0
    };
    let all_matched = class
        .students
        .iter()
        .filter(|s| !s.scenes.is_empty() && s.scenes.iter().all(|g| g.matches))
        .count();
    let refused_files: Vec<usize> = class
        .students
        .iter()
        .map(|s| s.scenes.iter().filter(|g| g.refused.is_some()).count())
        .filter(|&files| files > 0)
        .collect();
    let plural =
        |n: usize, one: &str, many: &str| format!("{n} {}", if n == 1 { one } else { many });
    let refused = match refused_files.len() {
        0 => "no file refused".to_string(),
        n => format!(
            "{} had a file refused ({})",
            plural(n, "student", "students"),
            plural(refused_files.iter().sum(), "file", "files"),
        ),
    };
    format!(
        "<p class=\"summary\"><b>{}</b> · total out of {}: mean <b>{}</b>, median <b>{}</b> · <b>{all_matched}</b> matched every scene · {refused}</p>",
        plural(students, "student", "students"),
        points(class.max_total),
        points(mean),
        points(median),
    )
}

/// What SUBMISSIONS/ held that was not graded as a student, named once;
/// nothing when it held only students.
pub(super) fn ignored(class: &ClassGrades) -> String {
    if class.ignored.is_empty() {
        return String::new();
    }
    let names: Vec<String> = class
        .ignored
        .iter()
        .map(|name| format!("<bdi>{}</bdi>", escape(name)))
        .collect();
    format!(
        "<p class=\"note ignored\">Not students, not graded: {} (what a system or an archiver \
         leaves, and files beside the folders).</p>",
        names.join(", ")
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grade::html::sample_class::{class, compared, matched, refused};

    #[test]
    fn mean_median_and_counts_by_hand() {
        // Totals 20, 10, 0, 10: mean 40 / 4 = 10, median of 0 10 10 20 is
        // (10 + 10) / 2 = 10. Only ada matched both scenes; cy had one file
        // refused.
        let class = class(&[
            ("ada", vec![matched(), matched()]),
            ("bob", vec![matched(), compared(&["no-ambient"])]),
            ("cy", vec![refused("missing"), compared(&[])]),
            ("dee", vec![compared(&[]), matched()]),
        ]);
        assert_eq!(
            summary(&class),
            "<p class=\"summary\"><b>4 students</b> · total out of 20: mean <b>10</b>, median <b>10</b> · <b>1</b> matched every scene · 1 student had a file refused (1 file)</p>"
        );
        // Three students, totals 0, 10, 10: the median is the middle one, 10;
        // the mean 20 / 3 = 6.67.
        let three = crate::grade::html::sample_class::class(&[
            ("a", vec![compared(&[])]),
            ("b", vec![matched()]),
            ("c", vec![matched()]),
        ]);
        assert!(summary(&three).contains("mean <b>6.67</b>, median <b>10</b>"));
        assert!(summary(&three).ends_with(" · no file refused</p>"));
    }

    #[test]
    fn refusals_are_counted_in_students_then_files() {
        // ada had both files refused, bob one, cy none: 2 students, 3 files.
        let class = class(&[
            ("ada", vec![refused("missing"), refused("not a PNG")]),
            ("bob", vec![matched(), refused("missing")]),
            ("cy", vec![matched(), matched()]),
        ]);
        assert!(
            summary(&class).ends_with(" · 2 students had a file refused (3 files)</p>"),
            "{}",
            summary(&class)
        );
    }

    #[test]
    fn what_is_not_a_student_is_named_once() {
        let mut class = class(&[("ada", vec![matched()])]);
        assert_eq!(ignored(&class), "");
        class.ignored = vec![".DS_Store".into(), "<b>".into(), "__MACOSX".into()];
        assert_eq!(
            ignored(&class),
            "<p class=\"note ignored\">Not students, not graded: <bdi>.DS_Store</bdi>, \
             <bdi>&lt;b&gt;</bdi>, <bdi>__MACOSX</bdi> (what a system or an archiver leaves, \
             and files beside the folders).</p>"
        );
    }

    #[test]
    fn an_empty_class_says_so() {
        assert!(summary(&class(&[])).contains("No student folders"));
    }
}
