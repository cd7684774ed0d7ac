//! A recording's events in words, one line each, as the debugger's step
//! list and the web page show them.

use raystep_model::math::Color;

use super::shared_words::weight_words;
use super::{Event, EventKind, RayTree, color, kind_name, light_label, not_cast_line, num, root};
use crate::scene::Scene;

fn light_name(scene: &Scene, light: usize) -> String {
    light_label(scene.lights.get(light).map_or("?", |l| l.name.as_str()))
}

/// An event in words, and the colour it carries, if any.
pub fn describe_event(tree: &RayTree, scene: &Scene, event: &Event) -> (String, Option<Color>) {
    let node = &tree.nodes[event.node];
    let ray = format!("r{}", event.node);
    match &event.kind {
        EventKind::RayCast { kind, depth } => {
            let weight = if node.parent.is_some() {
                format!(", weight {}", weight_words(node))
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
        EventKind::Emission { term } => (
            format!("{ray}: emission {}, added as it is", color(*term)),
            Some(*term),
        ),
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_scenes::ball;

    #[test]
    fn events_read_as_what_happened() {
        let (scene, tree) = ball();
        let text = |i: usize| describe_event(&tree, &scene, &tree.events[i]);
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
}
