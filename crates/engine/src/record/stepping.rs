//! Moving through a recording's events like a debugger moves through code.
//! A shading ray is the "function call": casting a child ray enters it, the
//! parent's `ChildReturned` event is where it returns. Every function takes
//! the current event index and returns the new one; none changes the tree.

use super::{EventKind, RayTree};

/// A way to move to another event.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Step {
    /// The next event, whatever ray it belongs to.
    Next,
    Previous,
    /// The next ray cast: enter the next child ray.
    Into,
    /// The next event of the same ray, skipping child rays' events.
    Over,
    /// Where this ray returns to its parent (the end, for the primary ray).
    Out,
    /// The first event.
    Start,
    /// The last event: the primary ray is done.
    End,
}

/// A condition to run forward to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Breakpoint {
    /// The first blocker of a shadow ray: a light is (partly) in shadow.
    BlockedShadow,
    /// A shading ray hits this object (index in the scene).
    HitObject(usize),
    /// Total internal reflection.
    Tir,
}

fn last(tree: &RayTree) -> usize {
    tree.events.len().saturating_sub(1)
}

/// The first event after `at` that satisfies `test`.
fn find_after(tree: &RayTree, at: usize, test: impl Fn(usize) -> bool) -> Option<usize> {
    (at + 1..tree.events.len()).find(|&i| test(i))
}

pub fn step(tree: &RayTree, at: usize, step: Step) -> usize {
    let Some(event) = tree.events.get(at) else {
        return 0;
    };
    let end = last(tree);
    let node = event.node;
    match step {
        Step::Next => (at + 1).min(end),
        Step::Previous => at.saturating_sub(1),
        Step::Into => find_after(tree, at, |i| {
            matches!(tree.events[i].kind, EventKind::RayCast { .. })
        })
        .unwrap_or(end),
        Step::Over => {
            find_after(tree, at, |i| tree.events[i].node == node).unwrap_or((at + 1).min(end))
        }
        Step::Out => match tree.nodes[node].parent {
            Some(parent) => find_after(tree, at, |i| tree.events[i].node == parent).unwrap_or(end),
            None => end,
        },
        Step::Start => 0,
        Step::End => end,
    }
}

/// Whether event `i` is where `breakpoint` stops.
pub fn matches(tree: &RayTree, i: usize, breakpoint: Breakpoint) -> bool {
    match (breakpoint, &tree.events[i].kind) {
        (Breakpoint::BlockedShadow, EventKind::Blocker { .. }) => {
            i > 0 && matches!(tree.events[i - 1].kind, EventKind::ShadowCast { .. })
        }
        (Breakpoint::HitObject(object), EventKind::Hit { object: hit, .. }) => *hit == object,
        (Breakpoint::Tir, EventKind::Refraction { tir }) => *tir,
        _ => false,
    }
}

/// The next event after `at` where `breakpoint` stops, if any.
pub fn run_to(tree: &RayTree, at: usize, breakpoint: Breakpoint) -> Option<usize> {
    find_after(tree, at, |i| matches(tree, i, breakpoint))
}

/// The event where `node`'s ray is cast.
pub fn cast_event(tree: &RayTree, node: usize) -> Option<usize> {
    tree.events
        .iter()
        .position(|e| e.node == node && matches!(e.kind, EventKind::RayCast { .. }))
}

/// The event where `node` casts its shadow ray to `light`, or where it finds
/// the light facing away.
pub fn light_event(tree: &RayTree, node: usize, light: usize) -> Option<usize> {
    let shadow = tree.events.iter().position(|e| {
        e.node == node && matches!(e.kind, EventKind::ShadowCast { light: l } if l == light)
    });
    shadow.or_else(|| {
        tree.events.iter().position(|e| {
            e.node == node && matches!(e.kind, EventKind::Light { light: l, .. } if l == light)
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_scenes::ball;

    #[test]
    fn steps_move_through_the_ball_pixels_events() {
        // Events: 0-4 r0, 5 r1 cast, 6 r1 miss, 7 r1 done, 8 r0 (r1 returns), 9 r0 done.
        let (_, tree) = ball();
        let at = |from, how| step(&tree, from, how);
        assert_eq!(at(0, Step::Next), 1);
        assert_eq!(at(9, Step::Next), 9, "nothing after the last");
        assert_eq!(at(0, Step::Previous), 0, "nothing before the first");
        assert_eq!(at(0, Step::Into), 5, "into r1's cast");
        assert_eq!(at(4, Step::Over), 8, "over r1: r0's next event");
        assert_eq!(at(6, Step::Out), 8, "out of r1: where it returns to r0");
        assert_eq!(at(2, Step::Out), 9, "out of the primary ray: the end");
        assert_eq!((at(6, Step::Start), at(2, Step::End)), (0, 9));
        assert_eq!(at(8, Step::Into), 9, "no ray cast left: the end");
    }

    #[test]
    fn breakpoints_stop_only_where_they_match() {
        let (_, tree) = ball();
        // The ball (object 0) is hit once, by r0 at event 1.
        assert_eq!(run_to(&tree, 0, Breakpoint::HitObject(0)), Some(1));
        assert_eq!(run_to(&tree, 1, Breakpoint::HitObject(0)), None);
        // Nothing blocks the lamp; no glass, no TIR.
        assert_eq!(run_to(&tree, 0, Breakpoint::BlockedShadow), None);
        assert_eq!(run_to(&tree, 0, Breakpoint::Tir), None);
    }

    #[test]
    fn rows_find_their_events() {
        let (_, tree) = ball();
        assert_eq!(cast_event(&tree, 1), Some(5));
        assert_eq!(light_event(&tree, 0, 0), Some(3), "the shadow ray first");
        assert_eq!(light_event(&tree, 1, 0), None, "r1 missed: no lights");
        assert_eq!(tree.events[4].kind.light(), Some(0));
        assert_eq!(tree.events[5].kind.light(), None);
    }
}
