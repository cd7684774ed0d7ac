//! Typed lines: what `inspect` prints and the debugger shows about a ray, each
//! line tagged with the step it is about and made of text and colours. The
//! text form flattens them; the debugger highlights by the tag and draws a
//! swatch after each colour, so neither ever reads the words back.

use std::fmt;

use super::numbers::color;
use super::ray_tree::{Event, EventKind, NodeId, RayTree};
use crate::trace::RayKind;
use raystep_model::math::Color;

/// A part of a ray's lines, named by the event or object it explains. The
/// ray itself is implied: a node's lines are all about that node.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum About {
    /// Where the ray starts and goes: its `ray_cast` event.
    Cast,
    /// The hit and how it was found.
    Hit,
    /// The miss, which also gives the ray's colour (the background).
    Miss,
    Ambient,
    Emission,
    /// A light by its index in the scene: its shadow ray, blockers and terms.
    Light(usize),
    Refraction,
    /// A child ray returning its contribution.
    Child(NodeId),
    /// A secondary ray of this kind that a rule kept from being cast.
    NotCast(RayKind),
    /// The ray's colour, the sum of its terms: its `ray_done` event.
    Colour,
}

impl About {
    /// The part of its ray's lines an event is about.
    pub fn of(tree: &RayTree, event: &Event) -> About {
        match &event.kind {
            EventKind::RayCast { .. } => About::Cast,
            EventKind::Hit { .. } => About::Hit,
            EventKind::Miss { .. } => About::Miss,
            EventKind::Ambient { .. } => About::Ambient,
            EventKind::Emission { .. } => About::Emission,
            EventKind::ShadowCast { light }
            | EventKind::Blocker { light, .. }
            | EventKind::Light { light, .. } => About::Light(*light),
            EventKind::Refraction { .. } => About::Refraction,
            EventKind::ChildReturned { child, .. } => About::Child(*child),
            EventKind::NotCast(ray) => About::NotCast(ray.kind),
            // A missed ray's colour is on its miss line.
            EventKind::RayDone { .. } if tree.nodes[event.node].hit.is_none() => About::Miss,
            EventKind::RayDone { .. } => About::Colour,
        }
    }
}

/// One piece of a line: words, or a colour written as `color` writes it.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Piece {
    Text(String),
    Color(Color),
}

/// One line, and what it is about (`None` for context such as near misses).
#[derive(Clone, Debug)]
pub struct Line {
    pub about: Option<About>,
    pub(crate) pieces: Vec<Piece>,
}

impl Line {
    pub(crate) fn new(about: Option<About>) -> Line {
        Line {
            about,
            pieces: Vec::new(),
        }
    }

    /// A line of words only.
    pub fn text(about: Option<About>, text: impl Into<String>) -> Line {
        Line::new(about).then(text)
    }

    /// The line with `text` appended.
    pub(crate) fn then(mut self, text: impl Into<String>) -> Line {
        self.pieces.push(Piece::Text(text.into()));
        self
    }

    /// The line with a colour appended.
    pub fn color(mut self, c: Color) -> Line {
        self.pieces.push(Piece::Color(c));
        self
    }
}

/// A word of a wrapped line: a colour's word carries the colour, for a
/// swatch after it.
#[derive(Clone, Debug, PartialEq)]
pub struct Word {
    pub text: String,
    pub color: Option<Color>,
}

/// One row of a wrapped line: its indentation in spaces, then its words,
/// one space apart.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    pub indent: usize,
    pub words: Vec<Word>,
}

impl Row {
    /// The row as text, without swatches.
    pub fn text(&self) -> String {
        let words: Vec<&str> = self.words.iter().map(|w| w.text.as_str()).collect();
        format!("{}{}", " ".repeat(self.indent), words.join(" "))
    }
}

impl Line {
    /// The line broken at spaces into rows of at most `room` characters
    /// (never fewer than 24 past the indentation), counting `swatch` more
    /// after each colour. A parenthesised group, such as a vector or a
    /// colour, is never broken, nor a word longer than a row. Continuations
    /// are indented four past the line's own indentation. `inspect` wraps
    /// with no swatch; the details pane with its swatch's width.
    pub fn wrap(&self, room: usize, swatch: usize) -> Vec<Row> {
        self.wrap_hanging(room, swatch, 4)
    }

    /// Like `wrap`, with continuations indented `hang` past the line's own
    /// indentation (`explain` hangs them under the text after a number).
    pub(crate) fn wrap_hanging(&self, room: usize, swatch: usize, hang: usize) -> Vec<Row> {
        let mut words = self.words();
        // A line of spaces keeps its last (empty) word.
        let lead = (words.iter().take_while(|w| w.text.is_empty()).count()).min(words.len() - 1);
        words.drain(..lead);
        let room = room.max(lead + 24);
        let width = |w: &Word| w.text.chars().count() + if w.color.is_some() { swatch } else { 0 };
        let mut rows = vec![Row {
            indent: lead,
            words: Vec::new(),
        }];
        let mut used = lead;
        for word in words {
            let row = rows.last_mut().expect("never empty");
            let len = width(&word);
            if row.words.is_empty() {
                used += len;
            } else if used + 1 + len > room {
                rows.push(Row {
                    indent: lead + hang,
                    words: Vec::new(),
                });
                used = lead + hang + len;
            } else {
                used += 1 + len;
            }
            rows.last_mut().expect("never empty").words.push(word);
        }
        rows
    }

    /// The line split at spaces outside parentheses; a word holding a
    /// colour piece carries that colour. Each leading space gives an empty word.
    fn words(&self) -> Vec<Word> {
        let mut words = vec![Word {
            text: String::new(),
            color: None,
        }];
        let mut open = 0;
        for piece in &self.pieces {
            let text = match piece {
                Piece::Text(text) => text,
                Piece::Color(c) => {
                    let last = words.last_mut().expect("never empty");
                    last.text.push_str(&color(*c));
                    last.color = Some(*c);
                    continue;
                }
            };
            for ch in text.chars() {
                if ch == ' ' && open <= 0 {
                    words.push(Word {
                        text: String::new(),
                        color: None,
                    });
                    open = 0;
                    continue;
                }
                open += i32::from(ch == '(') - i32::from(ch == ')');
                words.last_mut().expect("never empty").text.push(ch);
            }
        }
        words
    }
}

/// The line as `inspect` prints it.
impl fmt::Display for Line {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for piece in &self.pieces {
            match piece {
                Piece::Text(text) => f.write_str(text)?,
                Piece::Color(c) => f.write_str(&color(*c))?,
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_flattens_colours_the_way_color_writes_them() {
        let line = Line::text(Some(About::Ambient), "ambient ")
            .color(Color::new(0.1, 0.25, 1.0))
            .then(" and more");
        assert_eq!(line.to_string(), "ambient (0.100, 0.250, 1.000) and more");
    }

    fn word(text: &str, color: Option<Color>) -> Word {
        Word {
            text: text.into(),
            color,
        }
    }

    #[test]
    fn only_colour_pieces_get_swatches() {
        // A vector with three decimals a number reads like a colour, but it
        // is text: only the colour piece carries a colour.
        let c = Color::new(0.5, 0.25, 1.0);
        let line = Line::text(None, "from (0.125, 0.375, 0.625) adds ")
            .color(c)
            .then(" = x");
        let expected = vec![
            word("from", None),
            word("(0.125, 0.375, 0.625)", None),
            word("adds", None),
            word("(0.500, 0.250, 1.000)", Some(c)),
            word("=", None),
            word("x", None),
        ];
        assert_eq!(line.words(), expected);
    }

    #[test]
    fn wrapping_keeps_groups_whole_and_indents_continuations() {
        // "  k_d (0.100, 0.200, 0.300) x" with room 30: the lead is 2; "k_d"
        // ends at 5; the colour (21 characters) + a swatch of 3 would end
        // at 5 + 1 + 24 = 30, which fits; "x" would end at 32 > 30, so it
        // starts a continuation indented 2 + 4 = 6.
        let c = Color::new(0.1, 0.2, 0.3);
        let line = Line::text(None, "  k_d ").color(c).then(" x");
        let rows = line.wrap(30, 3);
        assert_eq!(
            rows,
            vec![
                Row {
                    indent: 2,
                    words: vec![word("k_d", None), word("(0.100, 0.200, 0.300)", Some(c))],
                },
                Row {
                    indent: 6,
                    words: vec![word("x", None)],
                },
            ]
        );
        // Without the swatch the same line fits in 2 + 3 + 1 + 21 + 1 + 1 = 29.
        assert_eq!(line.wrap(30, 0).len(), 1);
        assert_eq!(line.wrap(30, 0)[0].text(), "  k_d (0.100, 0.200, 0.300) x");
    }

    #[test]
    fn a_hanging_indent_puts_continuations_under_the_text() {
        // "  0.5  aaaa bbbb cccc dddd eeee ffff" with room 30 and hang 5: the
        // lead is 2, "0.5  aaaa ... eeee" ends at 2 + 3 + 2 + 24 = 31 > 30,
        // so "eeee" starts a row indented 2 + 5 = 7, under "aaaa".
        let line = Line::text(None, "  0.5  aaaa bbbb cccc dddd eeee ffff");
        let rows: Vec<String> = line.wrap_hanging(30, 0, 5).iter().map(Row::text).collect();
        assert_eq!(rows, ["  0.5  aaaa bbbb cccc dddd", "       eeee ffff"]);
    }

    #[test]
    fn a_row_never_gets_narrower_than_24_past_the_indentation() {
        // Room 10 is raised to 0 + 24: "aaaa bbbb cccc dddd eeee" is 24 long.
        let line = Line::text(None, "aaaa bbbb cccc dddd eeee ffff");
        let rows: Vec<String> = line.wrap(10, 0).iter().map(Row::text).collect();
        assert_eq!(rows, ["aaaa bbbb cccc dddd eeee", "    ffff"]);
    }
}
