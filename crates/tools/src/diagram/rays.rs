//! A pixel's rays as projected segments, each with its kind (for its
//! colour) and how far the step-through has come; the blockers' points.

use std::collections::HashMap;

use glam::{DVec2, DVec3};

use super::projection::Projection;
use raystep_engine::record::{EventKind, NodeId, RayTree};
use raystep_engine::scene::{Light, LightKind, Scene};

/// What a drawn ray is, for its colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stroke {
    Primary,
    Reflected,
    Transmitted,
    ShadowLit,
    /// 0 < S < 1: only transparent blockers (MODEL §4's Kt product).
    ShadowPartial,
    ShadowBlocked,
    Normal,
    /// Not yet reached by the step-through.
    Later,
    Current,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Segment {
    pub from: DVec2,
    pub to: DVec2,
    /// Its stroke at the diagram's own progress (`stroke_at` for another).
    pub(crate) stroke: Stroke,
    /// For a shadow ray, the node from whose hit it is cast (to leave
    /// shadow rays out of a slide); none for a ray or a normal.
    pub(crate) shadow_of: Option<NodeId>,
    /// What it draws: a normal, or a ray cast by an event.
    pub(crate) drawn: Drawn,
}

/// What a segment draws, for its stroke at any point of the step-through.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Drawn {
    /// A hit's normal: `Stroke::Normal` all along.
    Normal,
    /// A node's ray or one of its shadow rays, in `kind`'s colour once the
    /// event that casts it (`cast_at`; none when no event does) is reached.
    Ray {
        ray: CurrentRay,
        kind: Stroke,
        cast_at: Option<usize>,
    },
}

impl Segment {
    /// Its stroke with the step-through at `progress`: the current ray's
    /// `Current`, a ray whose cast is reached its kind's, else `Later`.
    pub fn stroke_at(&self, progress: Progress) -> Stroke {
        match self.drawn {
            Drawn::Normal => Stroke::Normal,
            Drawn::Ray { ray, .. } if progress.current == Some(ray) => Stroke::Current,
            Drawn::Ray {
                kind,
                cast_at: Some(at),
                ..
            } if at <= progress.reached => kind,
            Drawn::Ray { .. } => Stroke::Later,
        }
    }
}

/// How far a step-through has come, for the strokes: rays cast by the
/// events up to `reached` (included) get their kind's colour, later ones are
/// `Later`, and the ray of `current` is `Current`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Progress {
    pub(crate) reached: usize,
    pub(crate) current: Option<CurrentRay>,
}

/// The ray the step-through is at: a node's own ray, or (with `light`) its
/// shadow ray to that light.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct CurrentRay {
    pub(crate) node: NodeId,
    pub(crate) light: Option<usize>,
}

impl Progress {
    /// Every event reached and none current: each ray in its kind's colour.
    pub fn done(tree: &RayTree) -> Progress {
        Progress {
            reached: tree.events.len(),
            current: None,
        }
    }

    /// How far the step-through at event `current` has come: the current
    /// event's ray is its node's, or its shadow ray when the event is
    /// about a light.
    pub fn at(tree: &RayTree, current: usize) -> Progress {
        let ray = tree.events.get(current).map(|e| CurrentRay {
            node: e.node,
            light: e.kind.light(),
        });
        Progress {
            reached: current,
            current: ray,
        }
    }
}

/// What a shadow ray's S makes it: lit at 1, blocked at 0, partly
/// blocked between (transparent blockers only).
pub(crate) fn shadow_stroke(s: f64) -> Stroke {
    if s >= 1.0 {
        Stroke::ShadowLit
    } else if s <= 0.0 {
        Stroke::ShadowBlocked
    } else {
        Stroke::ShadowPartial
    }
}

/// A shadow ray's blocker, where it crosses, and its ray's kind (blocked
/// or partly blocked), for the colour of its ×.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BlockerMark {
    pub at: DVec2,
    pub stroke: Stroke,
    /// The node whose shadow ray it blocks, and the blocking object.
    pub(crate) shadow_of: NodeId,
    pub(crate) object: usize,
}

/// The rays of a pixel as projected segments, plus blocker points. Linear
/// in the events and rays: one pass over the events finds the one that
/// casts each ray and shadow ray, which reaches it.
pub(crate) fn ray_segments(
    tree: &RayTree,
    scene: &Scene,
    projection: &Projection,
    progress: Progress,
) -> (Vec<Segment>, Vec<BlockerMark>) {
    let casts = Casts::of(tree);
    let miss_length = miss_length(tree, scene);
    let mut segments = Vec::new();
    let mut blockers = Vec::new();
    let mut push = |from, to, shadow_of, drawn| {
        let mut segment = Segment {
            from: projection.project(from),
            to: projection.project(to),
            stroke: Stroke::Normal,
            shadow_of,
            drawn,
        };
        segment.stroke = segment.stroke_at(progress);
        segments.push(segment);
    };
    for (id, node) in tree.nodes.iter().enumerate() {
        let end = node.hit.as_ref().map_or(
            node.origin + node.direction.normalize() * miss_length,
            |h| h.point,
        );
        let kind = match node.kind {
            raystep_engine::trace::RayKind::Primary => Stroke::Primary,
            raystep_engine::trace::RayKind::Reflected => Stroke::Reflected,
            raystep_engine::trace::RayKind::Transmitted => Stroke::Transmitted,
        };
        let ray = CurrentRay {
            node: id,
            light: None,
        };
        let cast_at = casts.ray[id];
        push(node.origin, end, None, Drawn::Ray { ray, kind, cast_at });
        let Some(hit) = &node.hit else { continue };
        let normal_end = hit.point + hit.normal * miss_length * 0.08;
        push(hit.point, normal_end, None, Drawn::Normal);
        for light in &node.lights {
            let Some(shadow) = &light.shadow else {
                continue;
            };
            let target = scene
                .lights
                .get(light.light_index)
                .map_or(hit.point, |l| light_place(l, hit.point, miss_length));
            let ray = CurrentRay {
                node: id,
                light: Some(light.light_index),
            };
            let cast_at = casts.shadow.get(&(id, light.light_index)).copied();
            let kind = shadow_stroke(shadow.s);
            push(
                hit.point,
                target,
                Some(id),
                Drawn::Ray { ray, kind, cast_at },
            );
            // A blocker of a ray S = 1 lets all through (Kt = 1): its × as
            // a partly blocked one's.
            let kind = match kind {
                Stroke::ShadowBlocked => Stroke::ShadowBlocked,
                _ => Stroke::ShadowPartial,
            };
            blockers.extend(shadow.blockers.iter().map(|b| BlockerMark {
                at: projection.project(shadow.origin + shadow.direction * b.t),
                stroke: kind,
                shadow_of: id,
                object: b.object_index,
            }));
        }
    }
    (segments, blockers)
}

/// The first event casting each node's ray, and each of its shadow rays
/// (by node and the light's index in the scene).
struct Casts {
    ray: Vec<Option<usize>>,
    shadow: HashMap<(NodeId, usize), usize>,
}

impl Casts {
    fn of(tree: &RayTree) -> Casts {
        let mut casts = Casts {
            ray: vec![None; tree.nodes.len()],
            shadow: HashMap::new(),
        };
        for (i, event) in tree.events.iter().enumerate() {
            match event.kind {
                EventKind::RayCast { .. } => {
                    if let Some(first @ None) = casts.ray.get_mut(event.node) {
                        *first = Some(i);
                    }
                }
                EventKind::ShadowCast { light } => {
                    casts.shadow.entry((event.node, light)).or_insert(i);
                }
                _ => {}
            }
        }
        casts
    }
}

/// Where a light is drawn as seen from `from`: a point light at its
/// position; a directional one, which has none, `reach` along its L (MODEL
/// §4), as far as a missed ray is drawn, so its shadow rays run off
/// towards it parallel.
pub(crate) fn light_place(light: &Light, from: DVec3, reach: f64) -> DVec3 {
    match light.kind {
        LightKind::Point { position } => position,
        LightKind::Directional { direction } => from + direction * reach,
    }
}

/// How far a missed ray is drawn: half the size of the pixel's scene (its
/// hits, the eye and the point lights).
pub(crate) fn miss_length(tree: &RayTree, scene: &Scene) -> f64 {
    let mut points: Vec<DVec3> = tree
        .nodes
        .iter()
        .filter_map(|n| n.hit.as_ref().map(|h| h.point))
        .collect();
    points.push(tree.root().origin);
    points.extend(scene.lights.iter().filter_map(Light::position));
    let min = points.iter().fold(DVec3::INFINITY, |a, &p| a.min(p));
    let max = points.iter().fold(DVec3::NEG_INFINITY, |a, &p| a.max(p));
    ((max - min).length() * 0.5).max(1.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagram::DiagramPlane;
    use raystep_engine::test_scenes::ball;

    fn close(a: DVec2, b: DVec2) -> bool {
        (a - b).length() < 1e-9
    }

    /// The rule as the step-through states it, asked the old way: for
    /// each ray, whether an event up to the progress casts it, scanning
    /// the events (quadratic): the reference for the one pass.
    fn strokes_by_scan(tree: &RayTree, progress: Progress) -> Vec<Stroke> {
        let reached = |test: &dyn Fn(&EventKind, NodeId) -> bool| {
            (tree.events.iter())
                .take(progress.reached.saturating_add(1))
                .any(|e| test(&e.kind, e.node))
        };
        let mut strokes = Vec::new();
        for (id, node) in tree.nodes.iter().enumerate() {
            let current = |light| progress.current == Some(CurrentRay { node: id, light });
            let cast = |k: &EventKind, n| n == id && matches!(k, EventKind::RayCast { .. });
            strokes.push(match node.kind {
                _ if current(None) => Stroke::Current,
                _ if !reached(&cast) => Stroke::Later,
                raystep_engine::trace::RayKind::Primary => Stroke::Primary,
                raystep_engine::trace::RayKind::Reflected => Stroke::Reflected,
                raystep_engine::trace::RayKind::Transmitted => Stroke::Transmitted,
            });
            if node.hit.is_none() {
                continue;
            }
            strokes.push(Stroke::Normal);
            for light in &node.lights {
                let Some(shadow) = &light.shadow else {
                    continue;
                };
                let index = light.light_index;
                let cast = |k: &EventKind, n| {
                    n == id && matches!(k, EventKind::ShadowCast { light: l } if *l == index)
                };
                strokes.push(match () {
                    _ if current(Some(index)) => Stroke::Current,
                    _ if !reached(&cast) => Stroke::Later,
                    _ => shadow_stroke(shadow.s),
                });
            }
        }
        strokes
    }

    #[test]
    fn one_pass_strokes_every_ray_as_the_scan_did_at_every_event() {
        // Mirrors, glass (TIR), shadows and misses: the built-in scene on
        // a grid of pixels and glass.toml's ball and block, at every
        // event of each tree and at its end.
        let builtin = raystep_engine::scene::builtin::load_file_or_builtin(None).unwrap();
        let glass = raystep_engine::scene::parse(
            std::path::Path::new("glass.toml"),
            include_str!("../../../../scenes/glass.toml"),
        )
        .unwrap();
        let mut pixels: Vec<(&Scene, u32, u32)> = vec![];
        for y in (0..builtin.height).step_by(20) {
            for x in (0..builtin.width).step_by(20) {
                pixels.push((&builtin, x, y));
            }
        }
        pixels.extend([(&glass, 72, 45), (&glass, 132, 88), (&glass, 135, 58)]);
        for (scene, x, y) in pixels {
            let tree = raystep_engine::record::record_pixel(scene, &scene.settings, x, y);
            let top = Projection::new(DiagramPlane::Top, scene, &tree);
            let at = (0..tree.events.len()).map(|i| Progress::at(&tree, i));
            for progress in at.chain([Progress::done(&tree)]) {
                let (segments, _) = ray_segments(&tree, scene, &top, progress);
                let strokes: Vec<Stroke> = segments.iter().map(|s| s.stroke).collect();
                assert_eq!(strokes, strokes_by_scan(&tree, progress), "({x}, {y})");
                let again: Vec<Stroke> = segments.iter().map(|s| s.stroke_at(progress)).collect();
                assert_eq!(again, strokes);
            }
        }
    }

    #[test]
    fn segments_follow_the_step_through() {
        let (scene, tree) = ball();
        let top = Projection::new(DiagramPlane::Top, &scene, &tree);
        let strokes = |current| {
            let (segments, blockers) =
                ray_segments(&tree, &scene, &top, Progress::at(&tree, current));
            assert!(blockers.is_empty(), "nothing blocks the lamp");
            segments.iter().map(|s| s.stroke).collect::<Vec<_>>()
        };
        // r0, its normal, its shadow ray to the lamp, then r1 (no hit: no normal).
        use Stroke::*;
        assert_eq!(strokes(0), [Current, Normal, Later, Later], "at r0's cast");
        assert_eq!(
            strokes(3),
            [Primary, Normal, Current, Later],
            "its shadow ray"
        );
        assert_eq!(
            strokes(9),
            [Current, Normal, ShadowLit, Reflected],
            "r0 done"
        );
        // r1 misses: drawn half the scene's size long. The hit (0, 0, 1), the
        // eye (0, 0, 10) and the lamp (5, 0, 10) span (5, 0, 9): half of
        // √106 from (0, 0, 1) along +z, which the top view shows downward.
        let (segments, _) = ray_segments(&tree, &scene, &top, Progress::at(&tree, 9));
        let r1 = &segments[3];
        assert!(close(r1.from, DVec2::ZERO));
        assert!(close(r1.to, DVec2::new(0.0, -(106f64.sqrt() / 2.0))));
    }
}
