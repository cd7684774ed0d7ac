//! The step-through pane: the execution-ordered event list, one line per
//! event, indented by the depth of the ray it belongs to.

use ratatui::style::{Color as TermColor, Style};
use ratatui::text::{Line, Span};

use crate::math::Color;
use crate::record::{Event, EventKind, RayTree, color, kind_name, not_cast_line, num};
use crate::scene::Scene;

use super::app::App;
use super::layout::Pane;
use super::tree_view::{light_label, swatch};
use super::ui::pane_block;
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::widgets::Paragraph;

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
                "{ray}: blocked by {} at t = {}, kt = {}",
                scene.object_name(*object),
                num(*t),
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
pub fn first_line(current: usize, count: usize, height: usize) -> usize {
    current
        .saturating_sub(height / 2)
        .min(count.saturating_sub(height))
}

/// The lines of events around `current`, `height` of them, current marked.
pub fn lines(tree: &RayTree, scene: &Scene, current: usize, height: usize) -> Vec<Line<'static>> {
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

pub fn draw(frame: &mut Frame, app: &App, area: Rect) {
    let count = app.tree().events.len();
    let mut title = format!(" Step-through · event {} of {count} ", app.current() + 1);
    if let Some(object) = app.break_object().and_then(|o| app.scene().objects.get(o)) {
        title.push_str(&format!("· x stops at hits on {} ", object.name));
    }
    let block = pane_block(app, Pane::Steps, title);
    let height = block.inner(area).height as usize;
    let lines = lines(app.tree(), app.scene(), app.current(), height);
    frame.render_widget(Paragraph::new(lines).block(block), area);
}
