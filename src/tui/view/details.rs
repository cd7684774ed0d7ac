//! The details pane's text: the lines `raystep inspect` prints for the selected ray
//! (the intersection working and every term), a swatch after every colour,
//! and the lines of the current event highlighted. The lines come typed from
//! `record`: the highlight follows their `About`, the swatches their colour
//! pieces; no text is read back.

use ratatui::style::{Color as TermColor, Modifier, Style};
use ratatui::text::{Line, Span};

use crate::math::Color;
use crate::record::{self, About, Children, NodeId, Piece, RayTree, color, node_lines};

use super::tree::swatch;

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

/// Words, keeping a parenthesised group such as a vector in one piece; a
/// word holding a colour piece carries that colour, for a swatch after it.
fn tokens(line: &record::Line) -> Vec<(String, Option<Color>)> {
    let mut tokens = vec![(String::new(), None)];
    let mut open = 0;
    for piece in &line.pieces {
        let text = match piece {
            Piece::Text(text) => text,
            Piece::Color(c) => {
                let last = tokens.last_mut().expect("never empty");
                last.0.push_str(&color(*c));
                last.1 = Some(*c);
                continue;
            }
        };
        for ch in text.chars() {
            if ch == ' ' && open <= 0 {
                tokens.push((String::new(), None));
                open = 0;
                continue;
            }
            open += i32::from(ch == '(') - i32::from(ch == ')');
            let last = tokens.last_mut().expect("never empty");
            last.0.push(ch);
        }
    }
    tokens
}

/// One line wrapped to `width`, with swatches, continuation indented.
fn wrap(line: &record::Line, width: usize, style: Style) -> Vec<Line<'static>> {
    let text = line.to_string();
    let indent = text.len() - text.trim_start().len() + 4;
    let mut lines = Vec::new();
    let mut spans: Vec<Span<'static>> = Vec::new();
    let mut used = 0;
    for (i, (token, swatch_color)) in tokens(line).into_iter().enumerate() {
        let len = token.chars().count() + if swatch_color.is_some() { 3 } else { 0 };
        if i > 0 && used + 1 + len > width && used > indent {
            lines.push(Line::from(std::mem::take(&mut spans)).style(style));
            spans.push(Span::raw(" ".repeat(indent)));
            used = indent;
        } else if i > 0 {
            spans.push(Span::raw(" "));
            used += 1;
        }
        spans.push(Span::raw(token));
        if let Some(c) = swatch_color {
            spans.push(Span::raw(" "));
            spans.push(swatch(c));
        }
        used += len;
    }
    lines.push(Line::from(spans).style(style));
    lines
}

/// The pane's lines wrapped to `width`, and the first line of the marked part.
pub fn lines(
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
        out.extend(wrap(line, width.max(20), style));
    }
    (out, first_marked)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_colour_pieces_get_swatches() {
        // A vector with three decimals a number reads like a colour, but it
        // is text: only the colour piece carries a colour.
        let c = Color::new(0.5, 0.25, 1.0);
        let line = record::Line::text(None, "from (0.125, 0.375, 0.625) adds ")
            .color(c)
            .then(" = x");
        let words = |w: &[&str]| w.iter().map(|w| (w.to_string(), None)).collect::<Vec<_>>();
        let mut expected = words(&["from", "(0.125, 0.375, 0.625)", "adds"]);
        expected.push(("(0.500, 0.250, 1.000)".into(), Some(c)));
        expected.extend(words(&["=", "x"]));
        assert_eq!(tokens(&line), expected);
    }
}
