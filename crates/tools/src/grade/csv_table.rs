//! grades.csv: one row per student, for a spreadsheet. Per scene the
//! points, whether it matches, FLIP's mean, the top mistake and why it was
//! refused (blank where it was compared); then the total. Fields are quoted
//! as RFC 4180 says, and one that a spreadsheet would run as a formula
//! (starting with `=`, `+`, `-`, `@`, a tab or a carriage return) gets a
//! leading `'`, as OWASP's advice on CSV injection has it: a student's
//! folder name is data, never a formula. The file opens with UTF-8's
//! byte-order mark, without which Excel reads a CSV in the system's code
//! page and garbles accented names (`CafÃ©`); LibreOffice and Python's
//! `utf-8-sig` skip it.
//!
//! When the assignment sets grades by hand (`[[override]]`), one more
//! column per scene follows the total, `SCENE override`: the points
//! grading gave and the reason (blank where none); the points column holds
//! the teacher's points. Without overrides the table is as it always was.

use super::model::{ClassGrades, SceneGrade};

/// UTF-8's byte-order mark, U+FEFF (EF BB BF).
const BYTE_ORDER_MARK: char = '\u{feff}';

/// The whole table after the byte-order mark, header first, each line
/// ending in CRLF (RFC 4180).
pub(crate) fn csv(grades: &ClassGrades) -> String {
    let mut header = vec!["student".to_string()];
    for scene in &grades.scenes {
        for column in ["points", "match", "flip", "mistake", "refused"] {
            header.push(format!("{} {column}", scene.submit));
        }
    }
    header.push("total".into());
    let overridden =
        (grades.students.iter()).any(|s| s.scenes.iter().any(|g| g.overridden.is_some()));
    if overridden {
        header.extend(
            grades
                .scenes
                .iter()
                .map(|s| format!("{} override", s.submit)),
        );
    }
    let mut out = String::from(BYTE_ORDER_MARK);
    out += &line(&header);
    for student in &grades.students {
        let mut row = vec![student.student.clone()];
        for scene in &student.scenes {
            row.extend(cells(scene));
        }
        row.push(number(student.total));
        if overridden {
            row.extend(student.scenes.iter().map(|g| {
                g.overridden.as_ref().map_or(String::new(), |o| {
                    format!("graded {}: {}", number(o.graded_points), o.reason)
                })
            }));
        }
        out += &line(&row);
    }
    out
}

/// One scene's five cells.
fn cells(scene: &SceneGrade) -> [String; 5] {
    let compared = scene.refused.is_none();
    [
        number(scene.points),
        match (compared, scene.matches) {
            (false, _) => String::new(),
            (true, true) => "yes".into(),
            (true, false) => "no".into(),
        },
        scene
            .flip_mean
            .map(|f| format!("{f:.4}"))
            .unwrap_or_default(),
        scene.mistakes.first().cloned().unwrap_or_default(),
        scene.refused.clone().unwrap_or_default(),
    ]
}

/// Points as written by hand: 10, 7.5, 3.85.
pub fn number(x: f64) -> String {
    let text = format!("{x:.2}");
    text.trim_end_matches('0').trim_end_matches('.').to_string()
}

fn line(fields: &[String]) -> String {
    let mut out = fields
        .iter()
        .map(|f| field(f))
        .collect::<Vec<_>>()
        .join(",");
    out.push_str("\r\n");
    out
}

/// One field: defused if a spreadsheet would read it as a formula, then
/// quoted when it holds a comma, a quote, a line break or a leading or
/// trailing space (quotes doubled).
fn field(text: &str) -> String {
    let text = if text.starts_with(['=', '+', '-', '@', '\t', '\r']) {
        format!("'{text}")
    } else {
        text.to_string()
    };
    let quote =
        text.contains([',', '"', '\n', '\r']) || text.starts_with(' ') || text.ends_with(' ');
    if quote {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_are_quoted_and_formulas_defused() {
        assert_eq!(field("ada"), "ada");
        assert_eq!(field("Lovelace, Ada"), "\"Lovelace, Ada\"");
        assert_eq!(field("say \"hi\""), "\"say \"\"hi\"\"\"");
        assert_eq!(field("two\nlines"), "\"two\nlines\"");
        assert_eq!(field("=HYPERLINK(\"x\")"), "\"'=HYPERLINK(\"\"x\"\")\"");
        assert_eq!(field("+1"), "'+1");
        assert_eq!(field("-2"), "'-2");
        assert_eq!(field("@SUM(A1)"), "'@SUM(A1)");
        assert_eq!(field(" padded"), "\" padded\"");
        assert_eq!(number(10.0), "10");
        assert_eq!(number(7.5), "7.5");
        assert_eq!(number(3.85), "3.85");
        assert_eq!(number(0.0), "0");
    }

    #[test]
    fn the_file_opens_with_the_byte_order_mark_then_the_header() {
        let class = ClassGrades {
            title: "A5".into(),
            scenes: Vec::new(),
            students: vec![crate::grade::model::StudentGrades {
                student: "Zoë".into(),
                slug: "zoe".into(),
                scenes: Vec::new(),
                total: 0.0,
                notes: Vec::new(),
            }],
            max_total: 0.0,
            ignored: Vec::new(),
            visibility: Default::default(),
        };
        // EF BB BF, then "student,total", then the row; ë is C3 AB.
        assert_eq!(
            csv(&class).as_bytes(),
            b"\xef\xbb\xbfstudent,total\r\nZo\xc3\xab,0\r\n"
        );
    }
}
