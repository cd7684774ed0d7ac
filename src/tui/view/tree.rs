//! The ray tree's rows: one per shading ray and one per light it asked,
//! indented like the tree, each with a colour swatch and its share of the
//! pixel. A collapsed ray hides its lights and child rays.

use std::collections::BTreeSet;

use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};

use raystep_engine::record::{
    NodeId, RayTree, light_summary, path_factor, ray_summary, share_of_pixel,
};
use raystep_model::math::to_rgb8;

/// What a row shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum RowKind {
    Ray(NodeId),
    /// `light` indexes the node's `lights` (the scene's order).
    Light {
        node: NodeId,
        light: usize,
    },
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Row {
    pub(crate) kind: RowKind,
    pub(crate) indent: usize,
}

/// The visible rows, depth first: a ray, its lights, then its child rays.
pub fn rows(tree: &RayTree, collapsed: &BTreeSet<NodeId>) -> Vec<Row> {
    let mut rows = Vec::new();
    if !tree.nodes.is_empty() {
        push_rows(tree, collapsed, 0, 0, &mut rows);
    }
    rows
}

fn push_rows(
    tree: &RayTree,
    collapsed: &BTreeSet<NodeId>,
    id: NodeId,
    indent: usize,
    rows: &mut Vec<Row>,
) {
    rows.push(Row {
        kind: RowKind::Ray(id),
        indent,
    });
    if collapsed.contains(&id) {
        return;
    }
    for light in 0..tree.nodes[id].lights.len() {
        rows.push(Row {
            kind: RowKind::Light { node: id, light },
            indent: indent + 1,
        });
    }
    for child in tree.children(id) {
        push_rows(tree, collapsed, child, indent + 1, rows);
    }
}

/// The row that stands for event `at`: its light's row, else its ray's row,
/// else (when collapsed away) the nearest visible ancestor's.
pub(crate) fn selected_row(tree: &RayTree, rows: &[Row], at: usize) -> Option<usize> {
    let event = tree.events.get(at)?;
    let node = event.node;
    if let Some(light) = event.kind.light() {
        let index = tree.nodes[node]
            .lights
            .iter()
            .position(|l| l.light_index == light);
        let row = rows
            .iter()
            .position(|r| index.is_some_and(|i| r.kind == RowKind::Light { node, light: i }));
        if row.is_some() {
            return row;
        }
    }
    let mut id = Some(node);
    while let Some(n) = id {
        if let Some(row) = rows.iter().position(|r| r.kind == RowKind::Ray(n)) {
            return Some(row);
        }
        id = tree.nodes[n].parent;
    }
    None
}

/// The first row shown when `selected` must be visible in `height` rows.
pub(crate) fn scroll_offset(selected: usize, height: usize) -> usize {
    (selected + 1).saturating_sub(height.max(1))
}

/// A colour as the pixel shows it: two full blocks in its rgb8.
pub(crate) fn swatch(color: raystep_model::math::Color) -> Span<'static> {
    rgb_swatch(to_rgb8(color))
}

pub(crate) fn rgb_swatch([r, g, b]: [u8; 3]) -> Span<'static> {
    Span::styled("██", Style::new().fg(Color::Rgb(r, g, b)))
}

/// What a row says of a student's ray log: its ray's path in the log's
/// words, and a note after the description.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct LogLabel<'a> {
    pub(crate) path: Option<&'a str>,
    pub(crate) note: Option<&'a str>,
}

/// One row as text: marker, description, swatch and share, `width`
/// columns; with `label`, what it says of the student's ray log.
pub(crate) fn row_line(
    tree: &RayTree,
    collapsed: &BTreeSet<NodeId>,
    row: &Row,
    label: LogLabel,
    width: usize,
) -> Line<'static> {
    let pad = "  ".repeat(row.indent);
    let path = label.path.map_or(String::new(), |p| format!("{p} "));
    let (text, color, part) = match row.kind {
        RowKind::Ray(id) => {
            let node = &tree.nodes[id];
            let has_rows = !node.lights.is_empty() || tree.children(id).next().is_some();
            let marker = match (has_rows, collapsed.contains(&id)) {
                (false, _) => " ",
                (true, true) => "▸",
                (true, false) => "▾",
            };
            let text = format!("{pad}{marker} r{id} {path}{}", ray_summary(node));
            (text, node.color, node.color * path_factor(tree, id))
        }
        RowKind::Light { node, light } => {
            let record = &tree.nodes[node].lights[light];
            let color = record.diffuse + record.specular;
            (
                format!("{pad}  ☼ {path}{}", light_summary(record)),
                color,
                color * path_factor(tree, node),
            )
        }
    };
    let text = match label.note {
        Some(note) => format!("{text} {note}"),
        None => text,
    };
    let room = width.saturating_sub(8);
    let text: String = text.chars().take(room).collect();
    let fill = room.saturating_sub(text.chars().count());
    Line::from(vec![
        Span::raw(text),
        Span::raw(" ".repeat(fill + 1)),
        swatch(color),
        Span::raw(" "),
        Span::raw(share_of_pixel(tree, part)),
    ])
}

/// The style of the selected row.
pub(crate) fn selected_style(focused: bool) -> Style {
    let style = Style::new().add_modifier(Modifier::REVERSED);
    if focused {
        style.add_modifier(Modifier::BOLD)
    } else {
        style
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use raystep_engine::test_scenes::ball;

    #[test]
    fn rows_list_a_ray_its_lights_then_its_children() {
        let (_, tree) = ball();
        // r0, the lamp it asked (one deeper), r1 (one deeper).
        let expected = [
            Row {
                kind: RowKind::Ray(0),
                indent: 0,
            },
            Row {
                kind: RowKind::Light { node: 0, light: 0 },
                indent: 1,
            },
            Row {
                kind: RowKind::Ray(1),
                indent: 1,
            },
        ];
        assert_eq!(rows(&tree, &BTreeSet::new()), expected);
        // Collapsing r0 hides its lamp and r1.
        assert_eq!(rows(&tree, &BTreeSet::from([0])), expected[..1]);
    }

    #[test]
    fn an_event_selects_its_lights_row_else_its_rays() {
        let (_, tree) = ball();
        let open = rows(&tree, &BTreeSet::new());
        // 0: r0's cast; 3 and 4: the shadow ray to the lamp and its terms;
        // 6: r1's miss; 8: r0 again (r1 returning is r0's event).
        for (event, row) in [(0, 0), (3, 1), (4, 1), (6, 2), (8, 0)] {
            assert_eq!(selected_row(&tree, &open, event), Some(row), "{event}");
        }
        // With r0 collapsed, r1's miss falls back to r0, its visible parent.
        let folded = rows(&tree, &BTreeSet::from([0]));
        assert_eq!(selected_row(&tree, &folded, 6), Some(0));
        assert_eq!(selected_row(&tree, &open, 10), None, "no event 10");
    }

    #[test]
    fn the_scroll_keeps_the_selected_row_on_the_last_line() {
        // Rows 0..=4 fit 5 lines; row 9 needs rows 5..=9.
        assert_eq!(scroll_offset(4, 5), 0);
        assert_eq!(scroll_offset(9, 5), 5);
        assert_eq!(scroll_offset(3, 0), 3, "no room: the selected row first");
    }
}
