//! Typed lines: what `inspect` prints and the debugger shows about a ray, each
//! line tagged with the step it is about and made of text and colours. The
//! text form flattens them; the debugger highlights by the tag and draws a
//! swatch after each colour, so neither ever reads the words back.

use std::fmt;

use super::text::color;
use super::tree::{Event, EventKind, NodeId, RayTree};
use crate::math::Color;
use crate::trace::RayKind;

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
pub enum Piece {
    Text(String),
    Color(Color),
}

/// One line, and what it is about (`None` for context such as near misses).
#[derive(Clone, Debug, PartialEq)]
pub struct Line {
    pub about: Option<About>,
    pub pieces: Vec<Piece>,
}

impl Line {
    pub fn new(about: Option<About>) -> Line {
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
    pub fn then(mut self, text: impl Into<String>) -> Line {
        self.pieces.push(Piece::Text(text.into()));
        self
    }

    /// The line with a colour appended.
    pub fn color(mut self, c: Color) -> Line {
        self.pieces.push(Piece::Color(c));
        self
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
}
