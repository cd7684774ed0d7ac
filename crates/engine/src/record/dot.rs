//! A pixel's ray tree for Graphviz (`inspect --format dot`): one box per ray,
//! filled with the colour it brings back; one ellipse per light at each hit,
//! joined by its shadow ray when one was cast; total internal reflection and
//! blocked lights named on their edges, so the figure tells the story alone.

use std::fmt::Write;

use super::fate::LightFate;
use super::numbers::{color, num};
use super::ray_tree::{LightRecord, Node, NodeId, RayTree};
use super::shared_words::{kind_name, not_cast_reason};
use crate::trace::{PruneRule, RayKind};
use raystep_model::math::{Color, to_rgb8};

/// The one font of every label.
const FONT: &str = "fontname=\"Helvetica\", fontsize=10";

pub fn dot(tree: &RayTree) -> String {
    let mut out = format!(
        "digraph raytree {{\n  rankdir=TB;\n  graph [{FONT}];\n  node [{FONT}];\n  edge [{FONT}];\n"
    );
    let _ = writeln!(out, "  eye [shape=point, label=\"\"];");
    for (id, node) in tree.nodes.iter().enumerate() {
        write_ray(&mut out, tree, id, node);
        for (i, light) in node.lights.iter().enumerate() {
            write_light(&mut out, id, i, light);
        }
        for (i, ray) in node.not_cast.iter().enumerate() {
            let rule = match ray.rule {
                PruneRule::MinWeight { .. } => "min_weight",
                PruneRule::MaxRays { .. } => "max_rays",
            };
            let why = format!("not cast: {rule}\\n{}", not_cast_reason(ray));
            write_not_cast(&mut out, &format!("n{id}p{i}"), id, ray.kind, &why);
        }
        for (i, (kind, weight)) in node.depth_cut().enumerate() {
            let why = format!(
                "not cast: max_depth\\nweight {}, max_depth = {}",
                num(weight),
                tree.max_depth
            );
            write_not_cast(&mut out, &format!("n{id}d{i}"), id, kind, &why);
        }
    }
    out.push_str("}\n");
    out
}

/// A secondary ray a rule or the depth limit kept from being cast: a grey
/// dashed box under the ray it would have come from.
fn write_not_cast(out: &mut String, name: &str, parent: NodeId, kind: RayKind, why: &str) {
    let _ = writeln!(
        out,
        "  {name} [shape=box, style=dashed, color=\"grey\", fontcolor=\"grey40\", \
         label=\"{} ray\\n{why}\"];",
        kind_name(kind)
    );
    let _ = writeln!(out, "  n{parent} -> {name} [style=dashed, color=\"grey\"];");
}

/// A ray's box, filled with its colour, and the edge from its parent.
fn write_ray(out: &mut String, tree: &RayTree, id: NodeId, node: &Node) {
    let what = match &node.hit {
        Some(hit) => format!("hit {} at t={}", escape(&hit.object), num(hit.t)),
        None => "miss".into(),
    };
    let _ = writeln!(
        out,
        "  n{id} [shape=box, style=filled, fillcolor=\"{}\", fontcolor=\"{}\", \
         label=\"{} ray (depth {})\\n{what}\\ncolour {}\"];",
        hex(node.color),
        text_colour(node.color),
        kind_name(node.kind),
        node.depth,
        color(node.color)
    );
    let Some(parent) = node.parent else {
        let _ = writeln!(out, "  eye -> n{id} [label=\"primary\"];");
        return;
    };
    // A reflected ray whose parent met total internal reflection carries
    // k_t too: say so on the edge.
    let tir = node.kind == RayKind::Reflected && tree.nodes[parent].tir();
    let (label, style) = if tir {
        (
            format!("reflected (TIR) x{}", num(node.weight)),
            ", color=\"red\", fontcolor=\"red\"",
        )
    } else {
        (
            format!("{} x{}", kind_name(node.kind), num(node.weight)),
            "",
        )
    };
    let _ = writeln!(out, "  n{parent} -> n{id} [label=\"{label}\"{style}];");
}

/// A light at a hit: the shadow ray to it when one was cast (dashed, naming
/// what blocked it), else a plain dotted line saying why none was.
fn write_light(out: &mut String, id: NodeId, i: usize, light: &LightRecord) {
    let fate = match LightFate::of(light) {
        LightFate::AtPoint => "at the point".to_string(),
        LightFate::FacesAway => format!("faces away (N·L = {})", num(light.n_dot_l)),
        LightFate::NotCast => "shadows off".to_string(),
        LightFate::Lit(_) => "S = 1, nothing in the way".to_string(),
        LightFate::Blocked(s) => {
            let names = s.blockers.iter().map(|b| escape(&b.object));
            format!("S = 0, blocked by {}", first_few(names, s.blockers.len()))
        }
        LightFate::Crossed(s) | LightFate::PartlyBlocked(s) => {
            let names =
                (s.blockers.iter()).map(|b| format!("{} (k_t = {})", escape(&b.object), num(b.kt)));
            let names = first_few(names, s.blockers.len());
            format!("S = {}, partly blocked by {names}", num(s.s))
        }
    };
    // A directional light has no place: say what it is instead.
    let kind = if light.directional {
        "\\ndirectional, not attenuated"
    } else {
        ""
    };
    let _ = writeln!(
        out,
        "  n{id}l{i} [shape=ellipse, label=\"{}{kind}\\n{fate}\"];",
        escape(&light.light)
    );
    let edge = if light.shadow.is_some() {
        "style=dashed, label=\"shadow\""
    } else {
        "style=dotted, arrowhead=none, label=\"no shadow ray\""
    };
    let _ = writeln!(out, "  n{id} -> n{id}l{i} [{edge}];");
}

/// `#rrggbb` of a colour as the image stores it.
fn hex(c: Color) -> String {
    let [r, g, b] = to_rgb8(c);
    format!("#{r:02x}{g:02x}{b:02x}")
}

/// Black on light fills, white on dark ones (Rec. 601 luma at half).
fn text_colour(c: Color) -> &'static str {
    let [r, g, b] = to_rgb8(c);
    if 299 * r as u32 + 587 * g as u32 + 114 * b as u32 >= 128_000 {
        "black"
    } else {
        "white"
    }
}

/// The most characters of a name in a label: a 150-character name would
/// stretch its box across the whole tree (MODEL §10).
const MAX_NAME_CHARS: usize = 100;

/// The most blockers a shadow ray's label names; the rest are counted.
const MAX_BLOCKERS: usize = 10;

/// The first `MAX_BLOCKERS` of `names` (of `count`), then "and N more".
fn first_few(names: impl Iterator<Item = String>, count: usize) -> String {
    let mut shown: Vec<String> = names.take(MAX_BLOCKERS).collect();
    if count > MAX_BLOCKERS {
        shown.push(format!("and {} more", count - MAX_BLOCKERS));
    }
    shown.join(", ")
}

/// A name inside a quoted dot string: control characters (NUL ends
/// Graphviz's string, others break its layout) spelled out as
/// `crate::printable` does and the whole cut to `MAX_NAME_CHARS` with `…`,
/// then `&` written `&amp;` (Graphviz reads `&lt;` in any label as `<`:
/// a name holding one would show another name), backslashes and quotes
/// escaped.
fn escape(text: &str) -> String {
    let spelt = crate::printable::printable(text);
    let cut = if spelt.chars().count() > MAX_NAME_CHARS {
        let mut cut: String = spelt.chars().take(MAX_NAME_CHARS - 1).collect();
        cut.push('…');
        std::borrow::Cow::Owned(cut)
    } else {
        spelt
    };
    cut.replace('&', "&amp;")
        .replace('\\', "\\\\")
        .replace('"', "\\\"")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fills_and_their_text_colours() {
        // (1, 0.5, 0) stores as (255, 128, 0): luma 299*255 + 587*128 =
        // 151,381 >= 128,000, so black text; (0.1, 0.1, 0.1) -> 26s: white.
        assert_eq!(hex(Color::new(1.0, 0.5, 0.0)), "#ff8000");
        assert_eq!(text_colour(Color::new(1.0, 0.5, 0.0)), "black");
        assert_eq!(text_colour(Color::splat(0.1)), "white");
    }

    #[test]
    fn names_are_spelt_cut_and_escaped_for_a_dot_string() {
        // `&` first (so the `&` of `&amp;` is not doubled), then `\` and `"`;
        // ESC spelt `\u{1b}`, whose backslash is then doubled.
        assert_eq!(escape("a&lt;\"b\"\\\u{1b}"), r#"a&amp;lt;\"b\"\\\\u{1b}"#);
        // 150 letters: the first 99 and `…`; 100 stay whole.
        let long = "x".repeat(150);
        assert_eq!(escape(&long), format!("{}…", "x".repeat(99)));
        assert_eq!(escape(&long[..100]), long[..100]);
        // Cut after spelling: 30 ESCs are 180 characters spelt (`\u{1b}` is
        // 6), so 16 whole spellings (96) and 3 of the 17th, then `…`.
        let escs = escape(&"\u{1b}".repeat(30));
        assert_eq!(escs, format!("{}\\\\u{{…", r"\\u{1b}".repeat(16)));
    }

    #[test]
    fn a_shadow_names_ten_blockers_then_counts_the_rest() {
        let names = |n: usize| (0..n).map(|i| format!("b{i}"));
        assert_eq!(first_few(names(2), 2), "b0, b1");
        assert_eq!(
            first_few(names(10), 10),
            (0..10)
                .map(|i| format!("b{i}"))
                .collect::<Vec<_>>()
                .join(", ")
        );
        // 13 blockers: b0..b9, then the 3 others counted.
        let thirteen = first_few(names(13), 13);
        assert!(thirteen.starts_with("b0, b1, "), "{thirteen}");
        assert!(thirteen.ends_with("b8, b9, and 3 more"), "{thirteen}");
    }
}
