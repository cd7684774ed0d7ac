//! The class's mistakes per scene: how many students each named mistake
//! fits, beside how many matched (or nearly) and how many were refused, as
//! an inline SVG bar chart (no script, no fonts to fetch), each bar's
//! students in its tooltip and in a list under the chart that links to
//! their rows. A student may fit up to three mistakes, so the bars may add
//! up to more than the class.

use std::collections::BTreeMap;
use std::fmt::Write;

use super::class_table::near_match;
use super::escape::escape;
use super::sorting::{by_name, row_anchor};
use crate::grade::model::{ClassGrades, StudentGrades};

/// What a bar counts; its colour comes from the page's style.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kind {
    Match,
    /// Compared, no match, no mistake named, and a faint FLIP mean
    /// (`class_table::near_match`).
    NearMatch,
    Mistake,
    /// Compared, no match, no mistake named, and not a near match.
    Unexplained,
    Refused,
}

/// A bar: what it counts, and the students it counts, by name.
#[derive(Clone, Debug)]
pub(super) struct Bar<'a> {
    pub(super) label: String,
    pub(super) kind: Kind,
    pub(super) who: Vec<&'a StudentGrades>,
}

/// Scene `scene`'s bars: "match" first, "near match" when any, the named
/// mistakes by how many students they fit (most first, then by name), "no
/// mistake named" when any student's image differs unexplained, "refused"
/// last. "match" and "refused" are always there, at 0 too. Each bar's
/// students come in the table's order (`sorting::by_name`).
pub(super) fn bars(class: &ClassGrades, scene: usize) -> Vec<Bar<'_>> {
    let (mut matched, mut near, mut unexplained, mut refused) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut mistakes: BTreeMap<&str, Vec<&StudentGrades>> = BTreeMap::new();
    for student in by_name(&class.students) {
        let Some(grade) = student.scenes.get(scene) else {
            continue;
        };
        if grade.refused.is_some() {
            refused.push(student);
        } else if grade.matches {
            matched.push(student);
        } else if near_match(grade) {
            near.push(student);
        } else if grade.mistakes.is_empty() {
            unexplained.push(student);
        }
        // A name listed twice still fits the student once.
        let mut names: Vec<&str> = grade.mistakes.iter().map(String::as_str).collect();
        names.sort_unstable();
        names.dedup();
        for name in names {
            mistakes.entry(name).or_default().push(student);
        }
    }
    let bar = |label: &str, kind, who| Bar {
        label: label.to_string(),
        kind,
        who,
    };
    let mut named: Vec<_> = mistakes.into_iter().collect();
    named.sort_by(|a, b| b.1.len().cmp(&a.1.len()).then(a.0.cmp(b.0)));
    let mut bars = vec![bar("match", Kind::Match, matched)];
    if !near.is_empty() {
        bars.push(bar("near match", Kind::NearMatch, near));
    }
    bars.extend(
        named
            .into_iter()
            .map(|(name, who)| bar(name, Kind::Mistake, who)),
    );
    if !unexplained.is_empty() {
        bars.push(bar("no mistake named", Kind::Unexplained, unexplained));
    }
    bars.push(bar("refused", Kind::Refused, refused));
    bars
}

/// A bar's tooltip names at most this many students, then counts the rest
/// (the list under the chart holds them all).
const NAMED_IN_TOOLTIP: usize = 12;

/// "opaque-shadows, 2 students: ada, bob" for a bar's tooltip.
fn tooltip(bar: &Bar) -> String {
    let count = bar.who.len();
    let mut text = format!(
        "{}, {count} {}",
        bar.label,
        if count == 1 { "student" } else { "students" }
    );
    if count > 0 {
        let named: Vec<&str> = bar
            .who
            .iter()
            .take(NAMED_IN_TOOLTIP)
            .map(|s| s.student.as_str())
            .collect();
        text.push_str(": ");
        text.push_str(&named.join(", "));
        if count > NAMED_IN_TOOLTIP {
            let _ = write!(text, " and {} more", count - NAMED_IN_TOOLTIP);
        }
    }
    text
}

/// Scene `scene`'s bars as a list, closed at first: each bar's label and
/// count, then its students, each a link to the student's row.
pub(super) fn who(class: &ClassGrades, scene: usize) -> String {
    let mut html = String::from("<details class=\"who\"><summary>Who is in each bar</summary><dl>");
    for bar in bars(class, scene) {
        if bar.who.is_empty() {
            continue;
        }
        let _ = write!(
            html,
            "<dt>{} ({})</dt><dd>",
            escape(&bar.label),
            bar.who.len()
        );
        let links: Vec<String> = bar
            .who
            .iter()
            .map(|s| {
                format!(
                    "<a href=\"#{}\"><bdi>{}</bdi></a>",
                    row_anchor(s),
                    escape(&s.student)
                )
            })
            .collect();
        html.push_str(&links.join(", "));
        html.push_str("</dd>");
    }
    html.push_str("</dl></details>");
    html
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
        .map(|b| format!("{} {}", b.label, b.who.len()))
        .collect();
    let mut svg = format!(
        "<svg class=\"histogram\" xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" viewBox=\"0 0 {width} {height}\" role=\"img\"><title>{}</title>",
        escape(&said.join(", "))
    );
    for (row, (bar, label)) in bars.iter().zip(&labels).enumerate() {
        let top = ROW * row as u32 + 4;
        let middle = top + ROW / 2;
        let length = (LONGEST as f64 * bar.who.len() as f64 / class_size as f64).round() as u32;
        let kind = match bar.kind {
            Kind::Match => "match",
            Kind::NearMatch => "near",
            Kind::Mistake => "mistake",
            Kind::Unexplained => "unexplained",
            Kind::Refused => "refused",
        };
        let _ = write!(
            svg,
            "<g class=\"bar {kind}\"><title>{}</title><text class=\"label\" x=\"{}\" y=\"{middle}\" text-anchor=\"end\" dominant-baseline=\"central\">{}</text>\
             <rect x=\"{label_width}\" y=\"{}\" width=\"{length}\" height=\"{THICK}\" rx=\"2\"/>\
             <text class=\"count\" x=\"{}\" y=\"{middle}\" dominant-baseline=\"central\">{}</text></g>",
            escape(&tooltip(bar)),
            label_width - 6,
            escape(label),
            middle - THICK / 2,
            label_width + length + 5,
            bar.who.len(),
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
    use crate::grade::html::sample_class::{class, compared, matched, near, refused};
    use crate::grade::model::SceneGrade;

    /// Each bar as (label, kind, its students' names).
    fn named(class: &ClassGrades, scene: usize) -> Vec<(String, Kind, Vec<String>)> {
        bars(class, scene)
            .into_iter()
            .map(|b| {
                let who = b.who.iter().map(|s| s.student.clone()).collect();
                (b.label, b.kind, who)
            })
            .collect()
    }

    fn want(bars: &[(&str, Kind, &[&str])]) -> Vec<(String, Kind, Vec<String>)> {
        bars.iter()
            .map(|(l, k, who)| {
                (
                    l.to_string(),
                    *k,
                    who.iter().map(|w| w.to_string()).collect(),
                )
            })
            .collect()
    }

    #[test]
    fn bars_count_students_per_mistake_match_and_refusal() {
        // Scene 0 of eight students: fay and gus match; hal nearly (FLIP
        // 0.0014, nothing named); ada fits opaque-shadows and
        // phong-not-blinn, bob opaque-shadows (listed twice: counted
        // once), cy no-ambient; dee differs with no mistake named; eve was
        // refused. So match 2, near match 1, opaque-shadows 2, no-ambient 1
        // and phong-not-blinn 1 (1 each: by name), no mistake named 1,
        // refused 1; each bar's students by name.
        let class = class(&[
            (
                "ada",
                vec![compared(&["opaque-shadows", "phong-not-blinn"])],
            ),
            ("bob", vec![compared(&["opaque-shadows", "opaque-shadows"])]),
            ("cy", vec![compared(&["no-ambient"])]),
            ("dee", vec![compared(&[])]),
            ("eve", vec![refused("not a PNG")]),
            ("gus", vec![matched()]),
            ("Fay", vec![matched()]),
            ("hal", vec![near(0.0014)]),
        ]);
        assert_eq!(
            named(&class, 0),
            want(&[
                ("match", Kind::Match, &["Fay", "gus"]),
                ("near match", Kind::NearMatch, &["hal"]),
                ("opaque-shadows", Kind::Mistake, &["ada", "bob"]),
                ("no-ambient", Kind::Mistake, &["cy"]),
                ("phong-not-blinn", Kind::Mistake, &["ada"]),
                ("no mistake named", Kind::Unexplained, &["dee"]),
                ("refused", Kind::Refused, &["eve"]),
            ])
        );
    }

    #[test]
    fn match_and_refused_are_there_at_zero_and_the_others_only_when_some() {
        let class = class(&[("ada", vec![matched()])]);
        assert_eq!(
            named(&class, 0),
            want(&[
                ("match", Kind::Match, &["ada"]),
                ("refused", Kind::Refused, &[])
            ])
        );
    }

    #[test]
    fn a_faint_difference_named_or_past_the_bar_is_not_near() {
        // FLIP 0.0012 with byte-wrap named is that mistake; 0.01 itself is
        // not under the bar, so it differs.
        let byte_wrap = SceneGrade {
            flip_mean: Some(0.0012),
            ..compared(&["byte-wrap"])
        };
        let class = class(&[("a", vec![byte_wrap]), ("b", vec![near(0.01)])]);
        let kinds: Vec<Kind> = bars(&class, 0).iter().map(|b| b.kind).collect();
        assert_eq!(
            kinds,
            [Kind::Match, Kind::Mistake, Kind::Unexplained, Kind::Refused]
        );
    }

    #[test]
    fn the_svg_draws_each_bar_to_scale_with_its_count_and_students() {
        // Four students, three refused and one matching: the refused bar is
        // 160 × 3/4 = 120 long, the match bar 40, each with its count and a
        // tooltip naming its students.
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
        assert_eq!(
            texts,
            [
                "match 1, refused 3",
                "match, 1 student: d",
                "match",
                "1",
                "refused, 3 students: a, b, c",
                "refused",
                "3"
            ]
        );
    }

    #[test]
    fn a_long_bar_names_twelve_in_its_tooltip_and_all_in_the_list() {
        // 14 students match: s00 to s13 (zero-padded: name order is this
        // order); the tooltip names s00..s11 and says "and 2 more".
        let names: Vec<String> = (0..14).map(|i| format!("s{i:02}")).collect();
        let class = class(
            &names
                .iter()
                .map(|n| (n.as_str(), vec![matched()]))
                .collect::<Vec<_>>(),
        );
        let svg = svg(&class, 0);
        assert!(
            svg.contains(&format!(
                "<title>match, 14 students: {} and 2 more</title>",
                names[..12].join(", ")
            )),
            "{svg}"
        );
        let list = who(&class, 0);
        // Every student's link, to the row anchor of their slug (student i
        // is slug s{i}); the empty refused bar is left out.
        assert!(
            list.starts_with("<details class=\"who\"><summary>"),
            "{list}"
        );
        assert!(list.contains("<dt>match (14)</dt><dd><a href=\"#row-s0\"><bdi>s00</bdi></a>, "));
        assert!(list.contains(", <a href=\"#row-s13\"><bdi>s13</bdi></a></dd></dl>"));
        assert_eq!(list.matches("<a href=").count(), 14);
        assert!(!list.contains("refused"), "{list}");
    }

    #[test]
    fn names_in_the_list_and_tooltips_are_text() {
        let class = class(&[("<b>x</b> & y", vec![refused("missing")])]);
        let list = who(&class, 0);
        assert!(
            list.contains("<bdi>&lt;b&gt;x&lt;/b&gt; &amp; y</bdi>"),
            "{list}"
        );
        let svg = svg(&class, 0);
        assert!(
            svg.contains("<title>refused, 1 student: &lt;b&gt;x&lt;/b&gt; &amp; y</title>"),
            "{svg}"
        );
    }
}
