//! The class's mistakes per scene: how many students each named mistake
//! fits, beside how many matched and how many were refused, as an inline
//! SVG bar chart (no script, no fonts to fetch). A student may fit up to
//! three mistakes, so the bars may add up to more than the class.

use std::collections::BTreeMap;
use std::fmt::Write;

use super::escape::escape;
use crate::grade::model::ClassGrades;

/// What a bar counts; its colour comes from the page's style.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kind {
    Match,
    Mistake,
    /// Compared, no match, and no mistake named.
    Unexplained,
    Refused,
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub(super) struct Bar {
    pub(super) label: String,
    pub(super) kind: Kind,
    pub(super) students: usize,
}

/// Scene `scene`'s bars: "match" first, the named mistakes by how many
/// students they fit (most first, then by name), "no mistake named" when
/// any student's image differs unexplained, "refused" last. "match" and
/// "refused" are always there, at 0 too.
pub(super) fn bars(class: &ClassGrades, scene: usize) -> Vec<Bar> {
    let (mut matched, mut unexplained, mut refused) = (0, 0, 0);
    let mut mistakes: BTreeMap<&str, usize> = BTreeMap::new();
    for grade in class.students.iter().filter_map(|s| s.scenes.get(scene)) {
        if grade.refused.is_some() {
            refused += 1;
        } else if grade.matches {
            matched += 1;
        } else if grade.mistakes.is_empty() {
            unexplained += 1;
        }
        // A name listed twice still fits the student once.
        let mut names: Vec<&str> = grade.mistakes.iter().map(String::as_str).collect();
        names.sort_unstable();
        names.dedup();
        for name in names {
            *mistakes.entry(name).or_default() += 1;
        }
    }
    let bar = |label: &str, kind, students| Bar {
        label: label.to_string(),
        kind,
        students,
    };
    let mut named: Vec<_> = mistakes.into_iter().collect();
    named.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(b.0)));
    let mut bars = vec![bar("match", Kind::Match, matched)];
    bars.extend(
        named
            .into_iter()
            .map(|(name, n)| bar(name, Kind::Mistake, n)),
    );
    if unexplained > 0 {
        bars.push(bar("no mistake named", Kind::Unexplained, unexplained));
    }
    bars.push(bar("refused", Kind::Refused, refused));
    bars
}

/// Row height, bar thickness and the longest bar, in SVG units (pixels).
const ROW: u32 = 20;
const THICK: u32 = 14;
const LONGEST: u32 = 160;
/// Labels are monospaced at 12 px, about 7.3 px a character, so their
/// column can be as wide as the longest needs; longer labels are cut.
const CHAR: f64 = 7.3;
const MOST_CHARS: usize = 32;

/// Scene `scene`'s bars as an `<svg>`, bars scaled to the class's size so
/// that scenes compare at a glance; its `<title>` says every count.
pub(super) fn svg(class: &ClassGrades, scene: usize) -> String {
    let bars = bars(class, scene);
    let labels: Vec<String> = bars.iter().map(|b| shortened(&b.label)).collect();
    let longest_label = labels.iter().map(|l| l.chars().count()).max().unwrap_or(0);
    let label_width = (longest_label as f64 * CHAR).ceil() as u32 + 8;
    let width = label_width + LONGEST + 48;
    let height = ROW * bars.len() as u32 + 4;
    let class_size = class.students.len().max(1);
    let said: Vec<String> = bars
        .iter()
        .map(|b| format!("{} {}", b.label, b.students))
        .collect();
    let mut svg = format!(
        "<svg class=\"histogram\" xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" viewBox=\"0 0 {width} {height}\" role=\"img\"><title>{}</title>",
        escape(&said.join(", "))
    );
    for (row, (bar, label)) in bars.iter().zip(&labels).enumerate() {
        let top = ROW * row as u32 + 4;
        let middle = top + ROW / 2;
        let length = (LONGEST as f64 * bar.students as f64 / class_size as f64).round() as u32;
        let kind = match bar.kind {
            Kind::Match => "match",
            Kind::Mistake => "mistake",
            Kind::Unexplained => "unexplained",
            Kind::Refused => "refused",
        };
        let _ = write!(
            svg,
            "<g class=\"bar {kind}\"><text class=\"label\" x=\"{}\" y=\"{middle}\" text-anchor=\"end\" dominant-baseline=\"central\">{}</text>\
             <rect x=\"{label_width}\" y=\"{}\" width=\"{length}\" height=\"{THICK}\" rx=\"2\"/>\
             <text class=\"count\" x=\"{}\" y=\"{middle}\" dominant-baseline=\"central\">{}</text></g>",
            label_width - 6,
            escape(label),
            middle - THICK / 2,
            label_width + length + 5,
            bar.students,
        );
    }
    svg.push_str("</svg>");
    svg
}

/// `label` cut to `MOST_CHARS` characters with an ellipsis.
fn shortened(label: &str) -> String {
    if label.chars().count() <= MOST_CHARS {
        return label.to_string();
    }
    let kept: String = label.chars().take(MOST_CHARS - 1).collect();
    format!("{kept}…")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grade::html::sample_class::{class, compared, matched, refused};

    #[test]
    fn bars_count_students_per_mistake_match_and_refusal() {
        // Scene 0 of six students: two match; ada fits opaque-shadows and
        // phong-not-blinn, bob opaque-shadows (listed twice: counted once),
        // cy no-ambient; dee differs with no mistake named; eve was refused.
        // So match 2, opaque-shadows 2, no-ambient 1 and phong-not-blinn 1
        // (1 each: by name), no mistake named 1, refused 1.
        let class = class(&[
            (
                "ada",
                vec![compared(&["opaque-shadows", "phong-not-blinn"])],
            ),
            ("bob", vec![compared(&["opaque-shadows", "opaque-shadows"])]),
            ("cy", vec![compared(&["no-ambient"])]),
            ("dee", vec![compared(&[])]),
            ("eve", vec![refused("not a PNG")]),
            ("fay", vec![matched()]),
            ("gus", vec![matched()]),
        ]);
        let got: Vec<(String, Kind, usize)> = bars(&class, 0)
            .into_iter()
            .map(|b| (b.label, b.kind, b.students))
            .collect();
        let want = [
            ("match", Kind::Match, 2),
            ("opaque-shadows", Kind::Mistake, 2),
            ("no-ambient", Kind::Mistake, 1),
            ("phong-not-blinn", Kind::Mistake, 1),
            ("no mistake named", Kind::Unexplained, 1),
            ("refused", Kind::Refused, 1),
        ];
        let want: Vec<(String, Kind, usize)> = want
            .iter()
            .map(|(l, k, n)| (l.to_string(), *k, *n))
            .collect();
        assert_eq!(got, want);
    }

    #[test]
    fn match_and_refused_are_there_at_zero_and_unexplained_only_when_some() {
        let class = class(&[("ada", vec![matched()])]);
        let got: Vec<(String, usize)> = bars(&class, 0)
            .into_iter()
            .map(|b| (b.label, b.students))
            .collect();
        assert_eq!(got, [("match".to_string(), 1), ("refused".to_string(), 0)]);
    }

    #[test]
    fn the_svg_draws_each_bar_to_scale_with_its_count() {
        // Four students, three refused and one matching: the refused bar is
        // 160 × 3/4 = 120 long, the match bar 40, each with its count.
        let class = class(&[
            ("a", vec![refused("missing")]),
            ("b", vec![refused("missing")]),
            ("c", vec![refused("missing")]),
            ("d", vec![matched()]),
        ]);
        let svg = svg(&class, 0);
        let doc = roxmltree::Document::parse(&svg).expect("well-formed SVG");
        let rects: Vec<&str> = doc
            .descendants()
            .filter(|n| n.has_tag_name("rect"))
            .map(|n| n.attribute("width").unwrap())
            .collect();
        assert_eq!(rects, ["40", "120"]);
        let texts: Vec<&str> = doc
            .descendants()
            .filter(|n| n.is_text())
            .map(|n| n.text().unwrap())
            .collect();
        assert_eq!(texts, ["match 1, refused 3", "match", "1", "refused", "3"]);
    }
}
