//! What the panes show of a student's ray log (`--rays`) for the pixel
//! traced: each tree row's mark (the ray matches yours, differs, is not in
//! your log), the rays only in yours, the event where the first divergence
//! happens, and the details' lines that set your numbers beside ours.

use std::collections::HashMap;

use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};

use raystep_engine::record::{self, EventKind, NodeId, RayTree};
use raystep_engine::scene::Scene;
use raystep_tools::divergence::{
    Check, Divergence, Field, PixelReport, RayStatus, Value, value_text,
};
use raystep_tools::raylog::{Hit, RayPath, Step, rays_with_nodes};

use super::tree::RowKind;
use raystep_engine::record::stepping::{cast_event, light_event};

/// A ray's mark in the tree pane and its colour.
pub(crate) fn mark(status: RayStatus) -> (&'static str, Color) {
    match status {
        RayStatus::Matches => ("✓", Color::Green),
        RayStatus::Differs => ("≠", Color::Red),
        RayStatus::OnlyOurs => ("−", Color::Yellow),
        RayStatus::OnlyYours => ("+", Color::Magenta),
    }
}

/// The tree pane's legend of the marks, for its bottom border: the
/// longest that fits `width` columns.
pub(crate) fn legend(width: usize) -> &'static str {
    const LONG: &str =
        " your log: ✓ same  ≠ differs  − not in your log  + only in yours  · D: first divergence ";
    const SHORT: &str = " ✓ same ≠ differs − not in your log + only yours · D ";
    if LONG.chars().count() + 2 <= width {
        LONG
    } else {
        SHORT
    }
}

/// Where each of our rays of the pixel shows in the tree: a shading ray
/// on its node's row, a shadow ray on its light's row.
fn row_of(tree: &RayTree, path: &RayPath, node: NodeId) -> Option<RowKind> {
    match path.steps.last() {
        Some(Step::Shadow(light)) => tree.nodes[node]
            .lights
            .iter()
            .position(|l| l.light_index == *light)
            .map(|light| RowKind::Light { node, light }),
        _ => Some(RowKind::Ray(node)),
    }
}

/// The tree pane's marks for the pixel traced, compared with your log.
pub(crate) struct RowMarks {
    status: HashMap<RowKind, RayStatus>,
    paths: HashMap<RowKind, RayPath>,
    /// The row of the first divergence, when that ray is in our tree.
    first: Option<RowKind>,
}

impl RowMarks {
    pub(crate) fn new(tree: &RayTree, report: &PixelReport) -> RowMarks {
        let by_path: HashMap<&RayPath, RayStatus> = report
            .aligned
            .iter()
            .map(|a| (&a.path, a.status()))
            .collect();
        let mut status = HashMap::new();
        let mut paths = HashMap::new();
        for (ray, node) in rays_with_nodes(tree) {
            let Some(row) = row_of(tree, &ray.path, node) else {
                continue;
            };
            if let Some(&s) = by_path.get(&ray.path) {
                status.insert(row, s);
            }
            paths.insert(row, ray.path);
        }
        let first = report.first_divergence.as_ref().and_then(|d| {
            paths
                .iter()
                .find(|(_, path)| **path == d.path)
                .map(|(row, _)| *row)
        });
        RowMarks {
            status,
            paths,
            first,
        }
    }

    /// How the row's ray compares with yours; `None` for a row with no ray
    /// (a light facing away, shadows off).
    pub(crate) fn status(&self, row: RowKind) -> Option<RayStatus> {
        self.status.get(&row).copied()
    }

    /// The row's ray as your log names it.
    pub(crate) fn path(&self, row: RowKind) -> Option<&RayPath> {
        self.paths.get(&row)
    }

    pub(crate) fn is_first(&self, row: RowKind) -> bool {
        self.first == Some(row)
    }
}

/// The lines under the tree: the rays only in your log, each with the
/// rule of MODEL that keeps ours from casting it.
pub(crate) fn only_yours_lines(report: &PixelReport) -> Vec<(String, bool)> {
    let first = report.first_divergence.as_ref().map(|d| &d.path);
    report
        .only_yours
        .iter()
        .map(|ray| {
            let is_first = first == Some(&ray.path);
            let flag = if is_first {
                " ◀ first divergence"
            } else {
                ""
            };
            (
                format!("{} only in yours{flag}: {}", ray.path, ray.rule),
                is_first,
            )
        })
        .collect()
}

/// The ray of our tree the current event is about: a shadow ray when the
/// event is about a light its node cast one to, else the event's node.
pub(crate) fn selected_path(tree: &RayTree, current: usize) -> Option<RayPath> {
    let event = tree.events.get(current)?;
    let light = event.kind.light();
    let rays = rays_with_nodes(tree);
    let shadow = rays.iter().find(|(ray, node)| {
        *node == event.node
            && light.is_some()
            && ray.path.steps.last() == light.map(Step::Shadow).as_ref()
    });
    let own = || {
        rays.iter()
            .find(|(ray, node)| *node == event.node && !ray.path.is_shadow())
    };
    shadow.or_else(own).map(|(ray, _)| ray.path.clone())
}

/// The deepest ray of our tree on `path`: the ray itself when ours cast
/// it, else the ancestor whose hit decided not to (with the step it did
/// not take).
fn anchor(tree: &RayTree, path: &RayPath) -> Option<(RayPath, NodeId, Option<Step>)> {
    let rays = rays_with_nodes(tree);
    let mut at = path.clone();
    let mut missing = None;
    loop {
        if let Some((ray, node)) = rays.iter().find(|(ray, _)| ray.path == at) {
            return Some((ray.path.clone(), *node, missing));
        }
        let (parent, step) = at.parent()?;
        (at, missing) = (parent, Some(step));
    }
}

/// The first event of `node` that `test` accepts.
fn event_of(tree: &RayTree, node: NodeId, test: impl Fn(&EventKind) -> bool) -> Option<usize> {
    tree.events
        .iter()
        .position(|e| e.node == node && test(&e.kind))
}

/// The event where the trace makes the divergence's number: the cast for
/// the ray's origin and direction, its hit, its ambient term, the light's
/// terms, its colour when done; for a ray ours never cast, the event of
/// the ray that would have cast it where ours decides not to.
pub(crate) fn divergence_event(tree: &RayTree, divergence: &Divergence) -> Option<usize> {
    let (path, node, missing) = anchor(tree, &divergence.path)?;
    if let Some(Step::Shadow(light)) = path.steps.last() {
        let terms = |k: &EventKind| matches!(k, EventKind::Light { light: l, .. } if l == light);
        return match divergence.field {
            Field::S => event_of(tree, node, terms),
            _ => None,
        }
        .or_else(|| light_event(tree, node, *light));
    }
    let found = match (missing, divergence.field) {
        (Some(Step::Shadow(light)), _) => light_event(tree, node, light),
        (Some(_), _) => event_of(tree, node, |k| matches!(k, EventKind::NotCast(_)))
            .or_else(|| event_of(tree, node, |k| matches!(k, EventKind::RayDone { .. }))),
        (None, Field::Hit | Field::T | Field::Point | Field::Normal) => event_of(tree, node, |k| {
            matches!(k, EventKind::Hit { .. } | EventKind::Miss { .. })
        }),
        (None, Field::Ambient) => event_of(tree, node, |k| matches!(k, EventKind::Ambient { .. })),
        (None, Field::Diffuse(i) | Field::Specular(i)) => event_of(
            tree,
            node,
            |k| matches!(k, EventKind::Light { light, .. } if *light == i),
        ),
        (None, Field::Color) => event_of(tree, node, |k| matches!(k, EventKind::RayDone { .. })),
        (None, _) => None,
    };
    found.or_else(|| cast_event(tree, node))
}

/// A logged value in the details: a hit by the object's name.
fn value_words(value: Option<Value>, scene: &Scene) -> String {
    match value {
        Some(Value::Hit(Hit::Object(i))) => format!("{} (object {i})", scene.object_name(i)),
        value => value_text(value),
    }
}

fn bold() -> Style {
    Style::new().add_modifier(Modifier::BOLD)
}

/// `text` wrapped to `width`, each row in `style`.
fn wrapped(text: &str, indent: usize, width: usize, style: Style) -> Vec<Line<'static>> {
    let line = record::Line::text(None, format!("{}{text}", " ".repeat(indent)));
    line.wrap(width, 0)
        .into_iter()
        .map(|row| Line::from(row.text()).style(style))
        .collect()
}

/// The checks of one ray: field, yours, ours; side by side when `width`
/// has room, else ours under yours.
fn check_lines(checks: &[Check], scene: &Scene, width: usize) -> Vec<Line<'static>> {
    let rows: Vec<(String, String, String, bool)> = checks
        .iter()
        .map(|c| {
            (
                c.field.to_string(),
                value_words(Some(c.yours), scene),
                value_words(c.ours, scene),
                c.agrees,
            )
        })
        .collect();
    let field_width = rows.iter().map(|r| r.0.chars().count()).max().unwrap_or(0) + 2;
    let yours_width = rows
        .iter()
        .map(|r| r.1.chars().count())
        .max()
        .unwrap_or(0)
        .max(5)
        + 2;
    let ours_width = rows.iter().map(|r| r.2.chars().count()).max().unwrap_or(0);
    let side_by_side = 2 + field_width + yours_width + ours_width <= width;
    let mut out = Vec::new();
    if side_by_side {
        out.push(
            Line::from(format!(
                "  {:field_width$}{:yours_width$}{}",
                "", "yours", "ours"
            ))
            .style(bold()),
        );
    }
    for (field, yours, ours, agrees) in rows {
        let status = if agrees {
            RayStatus::Matches
        } else {
            RayStatus::Differs
        };
        let (symbol, color) = mark(status);
        let style = if agrees {
            Style::new()
        } else {
            Style::new().fg(Color::Red).add_modifier(Modifier::BOLD)
        };
        let head = vec![
            Span::styled(symbol.to_string(), Style::new().fg(color)),
            Span::raw(" "),
        ];
        if side_by_side {
            let mut spans = head;
            spans.push(Span::styled(
                format!("{field:field_width$}{yours:yours_width$}{ours}"),
                style,
            ));
            out.push(Line::from(spans));
        } else if agrees {
            // Within the tolerance: one line, your value.
            let mut spans = head;
            spans.push(Span::styled(
                format!("{field:field_width$}both  {yours}"),
                style,
            ));
            out.push(Line::from(spans));
        } else {
            let mut spans = head;
            spans.push(Span::styled(
                format!("{field:field_width$}yours {yours}"),
                style,
            ));
            out.push(Line::from(spans));
            out.push(Line::from(Span::styled(
                format!("  {:field_width$}ours  {ours}", ""),
                style,
            )));
        }
    }
    out
}

/// The details' lines for ray `path` of a logged pixel: with the first
/// divergence, when it is this ray (or a ray of yours this one did not
/// cast), its kind in words and what ours is; then your numbers beside
/// ours, field by field; then a blank line. Empty when the pixel has no
/// such ray.
pub(crate) fn detail_lines(
    report: &PixelReport,
    path: &RayPath,
    tree: &RayTree,
    scene: &Scene,
    width: usize,
) -> Vec<Line<'static>> {
    let Some(aligned) = report.aligned.iter().find(|a| &a.path == path) else {
        return Vec::new();
    };
    let status = aligned.status();
    let (symbol, color) = mark(status);
    let checks = &aligned.checks;
    let differ = checks.iter().filter(|c| !c.agrees).count();
    let said = match status {
        RayStatus::OnlyOurs => format!("{path}: not in your log; ours casts it"),
        RayStatus::OnlyYours => format!("{path}: only in your log"),
        _ if checks.is_empty() => {
            format!("{path}: in your log, with none of the numbers raystep compares")
        }
        RayStatus::Matches if checks.len() == 1 => {
            format!("{path}, yours beside ours: its one number agrees")
        }
        RayStatus::Matches => format!(
            "{path}, yours beside ours: all {} numbers agree",
            checks.len()
        ),
        RayStatus::Differs => format!(
            "{path}, yours beside ours: {differ} of {} {}",
            record::count(checks.len() as u64, "number", "numbers"),
            if differ == 1 { "differs" } else { "differ" }
        ),
    };
    // The mark, then the words wrapped beside it.
    let rows = record::Line::text(None, said).wrap(width.saturating_sub(2), 0);
    let mut out: Vec<Line<'static>> = rows
        .into_iter()
        .enumerate()
        .map(|(i, row)| {
            let head = if i == 0 {
                Span::styled(
                    format!("{symbol} "),
                    Style::new().fg(color).add_modifier(Modifier::BOLD),
                )
            } else {
                Span::raw("  ")
            };
            Line::from(vec![head, Span::styled(row.text(), bold())])
        })
        .collect();
    let mut told = false;
    if let Some(first) = &report.first_divergence
        && anchor(tree, &first.path).is_some_and(|(p, _, _)| &p == path)
    {
        out.extend(divergence_lines(report, first, path, width));
        told = &first.path == path;
    }
    // The first divergence's "what ours is" already gave the rule that
    // casts a ray only ours has: no line twice.
    if status == RayStatus::OnlyOurs
        && !told
        && let Some(rule) = report.only_ours.iter().find(|u| &u.path == path)
    {
        out.extend(wrapped(&rule.rule, 2, width, Style::new()));
    }
    out.extend(check_lines(checks, scene, width));
    // Your rays this one would have cast and ours does not (the first
    // divergence, if one of them, is told above).
    let first = report.first_divergence.as_ref().map(|d| &d.path);
    let children: Vec<_> = (report.only_yours.iter())
        .filter(|u| Some(&u.path) != first)
        .filter(|u| anchor(tree, &u.path).is_some_and(|(p, _, _)| &p == path))
        .collect();
    if !children.is_empty() {
        out.push(Line::from("Only in your log, from this ray:").style(bold()));
        let (symbol, _) = mark(RayStatus::OnlyYours);
        for ray in children {
            let text = format!("{symbol} {}: {}", ray.path, ray.rule);
            out.extend(wrapped(&text, 0, width, Style::new()));
        }
    }
    let first = report.first_divergence.as_ref();
    if status == RayStatus::Differs
        && let Some(first) = first.filter(|d| &d.path != path)
    {
        out.extend(wrapped(
            &format!(
                "The first divergence of the pixel is at {} {} (D goes there); \
                 what differs later in the trace follows from it.",
                first.path, first.field
            ),
            0,
            width,
            Style::new().add_modifier(Modifier::ITALIC),
        ));
    }
    out.push(Line::from(""));
    out
}

/// The first divergence of the pixel in words, as `compare --rays` says it.
fn divergence_lines(
    report: &PixelReport,
    first: &Divergence,
    selected: &RayPath,
    width: usize,
) -> Vec<Line<'static>> {
    let red = Style::new().fg(Color::Red).add_modifier(Modifier::BOLD);
    let place = if &first.path == selected {
        format!("First divergence of the pixel: here, {}", first.field)
    } else {
        format!(
            "First divergence of the pixel: {} {}, a ray of yours this one did not cast",
            first.path, first.field
        )
    };
    let mut out = wrapped(&place, 0, width, red);
    let words = if first.words.is_empty() {
        first.kind.name().to_string()
    } else {
        format!("{}: {}", first.kind.name(), first.words)
    };
    out.extend(wrapped(&words, 2, width, Style::new().fg(Color::Red)));
    if !first.meaning.is_empty() {
        out.push(Line::from("What ours is:").style(bold()));
        for line in &first.meaning {
            out.extend(wrapped(line, 2, width, Style::new()));
        }
    }
    if report.later_differences > 0 {
        let n = report.later_differences;
        let later = record::count(n as u64, "difference", "differences");
        let follow = if n == 1 { "follows" } else { "follow" };
        out.extend(wrapped(
            &format!("{later} after it {follow} from the first."),
            0,
            width,
            Style::new(),
        ));
    }
    for line in raystep_tools::divergence::consistent_lines(report) {
        out.extend(wrapped(&format!("{line} M opens on it."), 0, width, bold()));
    }
    if !report.mistakes.is_empty() {
        let names: Vec<&str> = report.mistakes.iter().map(|m| m.name()).collect();
        out.extend(wrapped(
            &format!(
                "Your rays are raystep's under the catalogue's mistake: {} (M turns it on).",
                names.join(", ")
            ),
            0,
            width,
            bold(),
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use raystep_engine::test_scenes::ball;
    use raystep_tools::divergence::{OurRays, Tolerance, compare_pixel};
    use raystep_tools::raylog::rays_of;

    /// The ball's pixel logged as ours, with the reflected ray's direction
    /// negated: r1 (P/R) differs, r0 and the lamp's shadow ray match.
    fn negated_reflection() -> (Scene, RayTree, PixelReport) {
        let (scene, tree) = ball();
        let mut yours = rays_of(&tree);
        let reflected = yours
            .iter_mut()
            .find(|r| r.path.to_string() == "P/R")
            .expect("the ball's r1 is P/R");
        reflected.dir = reflected.dir.map(|d| -d);
        let ours = OurRays::of(tree.clone());
        let report = compare_pixel(&scene, yours, &ours, &Tolerance::default());
        (scene, tree, report)
    }

    #[test]
    fn rows_are_marked_by_their_rays() {
        let (_, tree, report) = negated_reflection();
        let marks = RowMarks::new(&tree, &report);
        let lamp = RowKind::Light { node: 0, light: 0 };
        assert_eq!(marks.status(RowKind::Ray(0)), Some(RayStatus::Matches));
        assert_eq!(marks.status(lamp), Some(RayStatus::Matches));
        assert_eq!(marks.status(RowKind::Ray(1)), Some(RayStatus::Differs));
        assert!(marks.is_first(RowKind::Ray(1)));
        assert_eq!(marks.path(lamp).map(|p| p.to_string()), Some("P/S0".into()));
    }

    #[test]
    fn the_jump_lands_on_the_cast_of_the_ray_whose_direction_differs() {
        // Events: 0-4 r0, 5 r1 cast (stepper's test): the direction is the cast's.
        let (_, tree, report) = negated_reflection();
        let first = report.first_divergence.as_ref().expect("a divergence");
        assert_eq!(
            (first.path.to_string(), first.field),
            ("P/R".into(), Field::Dir)
        );
        assert_eq!(divergence_event(&tree, first), Some(5));
        assert_eq!(
            selected_path(&tree, 5).map(|p| p.to_string()),
            Some("P/R".into())
        );
        // Event 3 is r0's shadow ray to the lamp.
        assert_eq!(
            selected_path(&tree, 3).map(|p| p.to_string()),
            Some("P/S0".into())
        );
    }
}
