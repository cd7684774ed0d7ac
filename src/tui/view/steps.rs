//! The step-through list: the execution-ordered events, one line per event,
//! indented by the depth of the ray it belongs to, the current one centred.

use ratatui::style::{Color as TermColor, Style};
use ratatui::text::{Line, Span};

use raystep_engine::record::{RayTree, describe_event};
use raystep_engine::scene::Scene;

use super::tree::swatch;

/// The first event shown when `height` lines centre `current`.
pub(crate) fn first_line(current: usize, count: usize, height: usize) -> usize {
    current
        .saturating_sub(height / 2)
        .min(count.saturating_sub(height))
}

/// The lines of events around `current`, `height` of them, current marked.
pub(crate) fn lines(
    tree: &RayTree,
    scene: &Scene,
    current: usize,
    height: usize,
) -> Vec<Line<'static>> {
    let count = tree.events.len();
    let first = first_line(current, count, height);
    (first..count.min(first + height))
        .map(|i| {
            let event = &tree.events[i];
            let (text, swatch_color) = describe_event(tree, scene, event);
            let indent = "  ".repeat(tree.nodes[event.node].depth.saturating_sub(1) as usize);
            let marker = if i == current { "▶" } else { " " };
            let mut spans = vec![Span::raw(format!("{marker}{:>3} {indent}{text}", i + 1))];
            if let Some(c) = swatch_color {
                spans.push(Span::raw(" "));
                spans.push(swatch(c));
            }
            let line = Line::from(spans);
            if i == current {
                line.style(Style::new().bold().fg(TermColor::Yellow))
            } else {
                line
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use raystep_engine::test_scenes::ball;

    #[test]
    fn the_current_event_is_centred_until_an_end_is_reached() {
        // 10 events in 4 lines: centred means 2 lines above the current one.
        assert_eq!(first_line(0, 10, 4), 0, "nothing above the first");
        assert_eq!(first_line(5, 10, 4), 3);
        assert_eq!(first_line(9, 10, 4), 6, "the last 4: events 6..=9");
        assert_eq!(first_line(3, 2, 10), 0, "all fit");
    }

    #[test]
    fn lines_number_and_mark_the_events_shown() {
        let (scene, tree) = ball();
        let text = |l: &Line| {
            l.spans
                .iter()
                .map(|s| s.content.as_ref())
                .collect::<String>()
        };
        let lines = lines(&tree, &scene, 5, 4);
        // Events 3..=6, numbered from 1; r1 (depth 2) indented once; the
        // current one, event 5, marked.
        let first: Vec<String> = lines.iter().map(text).collect();
        assert_eq!(first.len(), 4);
        assert_eq!(first[0], "   4 r0: shadow ray to light lamp");
        assert_eq!(
            first[2],
            "▶  6   r1: cast reflected ray, depth 2, weight 0.5"
        );
        assert!(first[3].starts_with("   7   r1: missed everything: background ██"));
    }
}
