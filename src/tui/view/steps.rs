//! The step-through list: the execution-ordered events, one line per event,
//! indented by the depth of the ray it belongs to, the current one centred.

use ratatui::style::{Color as TermColor, Style};
use ratatui::text::{Line, Span};

use raystep_engine::record::{
    Event, EventKind, RayTree, color, kind_name, not_cast_line, num, root,
};
use raystep_engine::scene::Scene;
use raystep_model::math::Color;

use super::tree::{light_label, swatch};

fn light_name(scene: &Scene, light: usize) -> String {
    light_label(scene.lights.get(light).map_or("?", |l| l.name.as_str()))
}

/// An event in words, and the colour it carries, if any.
pub fn describe(tree: &RayTree, scene: &Scene, event: &Event) -> (String, Option<Color>) {
    let node = &tree.nodes[event.node];
    let ray = format!("r{}", event.node);
    match &event.kind {
        EventKind::RayCast { kind, depth } => {
            let weight = if node.parent.is_some() {
                format!(", weight {}", num(node.weight))
            } else {
                String::new()
            };
            (
                format!(
                    "{ray}: cast {} ray, depth {depth}{weight}",
                    kind_name(*kind)
                ),
                None,
            )
        }
        EventKind::Hit { object, t, tested } => (
            format!(
                "{ray}: hit {} at t = {} ({} primitives tested)",
                scene.object_name(*object),
                num(*t),
                tested.primitives
            ),
            None,
        ),
        EventKind::Miss { .. } => (
            format!("{ray}: missed everything: background"),
            Some(node.color),
        ),
        EventKind::Ambient { term } => (format!("{ray}: ambient {}", color(*term)), Some(*term)),
        EventKind::ShadowCast { light } => (
            format!("{ray}: shadow ray to {}", light_name(scene, *light)),
            None,
        ),
        EventKind::Blocker { object, t, kt, .. } => (
            format!(
                "{ray}: blocked by {} at {}, kt = {}",
                scene.object_name(*object),
                root("t", *t),
                num(*kt)
            ),
            None,
        ),
        EventKind::Light {
            light,
            at_point: true,
            ..
        } => (
            format!(
                "{ray}: {} is at the point: adds nothing",
                light_name(scene, *light)
            ),
            None,
        ),
        EventKind::Light {
            light,
            faces_away: true,
            ..
        } => (
            format!(
                "{ray}: {} faces away: adds nothing",
                light_name(scene, *light)
            ),
            None,
        ),
        EventKind::Light {
            light,
            s,
            diffuse,
            specular,
            ..
        } => {
            let s = s.map_or("shadows off".to_string(), |s| format!("S = {}", num(s)));
            let term = *diffuse + *specular;
            (
                format!(
                    "{ray}: {}: {s}, adds {}",
                    light_name(scene, *light),
                    color(term)
                ),
                Some(term),
            )
        }
        EventKind::Refraction { tir: true } => (
            format!("{ray}: total internal reflection: no transmitted ray"),
            None,
        ),
        EventKind::Refraction { tir: false } => (
            format!("{ray}: refraction: a transmitted ray will be cast"),
            None,
        ),
        EventKind::ChildReturned {
            child,
            kind,
            contribution,
        } => (
            format!(
                "{ray}: {} ray r{child} returns, adds {}",
                kind_name(*kind),
                color(*contribution)
            ),
            Some(*contribution),
        ),
        EventKind::NotCast(not_cast) => (format!("{ray}: {}", not_cast_line(not_cast)), None),
        EventKind::RayDone { color: c } => (format!("{ray}: done, colour {}", color(*c)), Some(*c)),
    }
}

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
            let (text, swatch_color) = describe(tree, scene, event);
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
    fn events_read_as_what_happened() {
        let (scene, tree) = ball();
        let text = |i: usize| describe(&tree, &scene, &tree.events[i]);
        assert_eq!(text(3), ("r0: shadow ray to light lamp".into(), None));
        // r1 misses: its colour is the background.
        let background = Color::new(0.1, 0.2, 0.3);
        assert_eq!(
            text(6),
            ("r1: missed everything: background".into(), Some(background))
        );
        // r1 adds ks x background = 0.5 x (0.1, 0.2, 0.3).
        let (words, carried) = text(8);
        assert_eq!(
            words,
            "r0: reflected ray r1 returns, adds (0.050, 0.100, 0.150)"
        );
        assert!((carried.unwrap() - background * 0.5).abs().max_element() < 1e-12);
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
