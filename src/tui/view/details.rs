//! The details pane's text: the lines `raystep inspect` prints for the selected ray
//! (the intersection working and every term), a swatch after every colour,
//! and the lines of the current event highlighted. The lines come typed from
//! `record`: the highlight follows their `About`, the swatches their colour
//! pieces; no text is read back.

use ratatui::style::{Color as TermColor, Modifier, Style};
use ratatui::text::{Line, Span};

use raystep_engine::record::{self, About, Children, NodeId, RayTree, node_lines};

use super::tree::{rgb_swatch, swatch};

/// A ray's lines as the pane lists them: a header, then what `inspect`
/// prints, with the child rays listed before the colour they add to.
pub fn ray_lines(tree: &RayTree, id: NodeId) -> Vec<record::Line> {
    let header = format!("r{id}: {}", record::ray_header(&tree.nodes[id]));
    let mut lines = vec![record::Line::text(None, header)];
    lines.extend(node_lines(tree, id, Children::Listed));
    lines
}

/// What event `at` is about, when it is one of ray `id`'s events.
pub fn marked(tree: &RayTree, id: NodeId, at: Option<usize>) -> Option<About> {
    let event = at
        .and_then(|i| tree.events.get(i))
        .filter(|e| e.node == id)?;
    Some(About::of(tree, event))
}

/// One line wrapped to `width`, a swatch after each colour.
fn wrap(line: &record::Line, width: usize, style: Style) -> Vec<Line<'static>> {
    let rows = line.wrap(width, SWATCH_WIDTH);
    rows.into_iter()
        .map(|row| {
            let mut spans = vec![Span::raw(" ".repeat(row.indent))];
            for (i, word) in row.words.into_iter().enumerate() {
                if i > 0 {
                    spans.push(Span::raw(" "));
                }
                spans.push(Span::raw(word.text));
                if let Some(c) = word.color {
                    spans.push(Span::raw(" "));
                    spans.push(swatch(c));
                }
            }
            Line::from(spans).style(style)
        })
        .collect()
}

/// A space and the two-cell swatch after each colour.
const SWATCH_WIDTH: usize = 3;

/// The pane's lines wrapped to `width`, and the first line of the marked part.
pub(crate) fn lines(
    tree: &RayTree,
    id: NodeId,
    at: Option<usize>,
    width: usize,
) -> (Vec<Line<'static>>, Option<usize>) {
    let about = marked(tree, id, at);
    let mut out = Vec::new();
    let mut first_marked = None;
    for (i, line) in ray_lines(tree, id).iter().enumerate() {
        let style = if about.is_some() && line.about == about {
            first_marked.get_or_insert(out.len());
            Style::new()
                .fg(TermColor::Yellow)
                .add_modifier(Modifier::BOLD)
        } else if i == 0 {
            Style::new().add_modifier(Modifier::BOLD)
        } else {
            Style::new()
        };
        out.extend(wrap(line, width, style));
    }
    (out, first_marked)
}

/// With `--compare`: the student's pixel beside ours, each with a swatch.
pub(crate) fn compare_line(yours: [u8; 3], ours: Option<[u8; 3]>) -> Line<'static> {
    let rgb = |[r, g, b]: [u8; 3]| format!("({r}, {g}, {b})");
    let mut spans = vec![
        Span::raw(format!("yours {} ", rgb(yours))),
        rgb_swatch(yours),
    ];
    if let Some(ours) = ours {
        spans.push(Span::raw(format!(" · ours {} ", rgb(ours))));
        spans.push(rgb_swatch(ours));
    }
    Line::from(spans).style(Style::new().add_modifier(Modifier::BOLD))
}

/// The what-if section above the ray's lines: how the pixel changed with
/// the last toggle, wrapped to `width`, in italics, then a blank line.
pub(crate) fn what_if_lines(what_if: &str, width: usize) -> Vec<Line<'static>> {
    let style = Style::new().add_modifier(Modifier::ITALIC);
    let mut out = vec![
        Line::from("What changed with the last toggle:").style(style.add_modifier(Modifier::BOLD)),
    ];
    for line in what_if.lines() {
        for row in record::Line::text(None, line).wrap(width, 0) {
            out.push(Line::from(row.text()).style(style));
        }
    }
    out.push(Line::from(""));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_compare_line_puts_yours_beside_ours() {
        let line = compare_line([0, 0, 0], Some([12, 34, 255]));
        let text: String = line.spans.iter().map(|s| s.content.as_ref()).collect();
        assert_eq!(text, "yours (0, 0, 0) ██ · ours (12, 34, 255) ██");
        assert_eq!(line.spans[3].style.fg, Some(TermColor::Rgb(12, 34, 255)));
    }
}
