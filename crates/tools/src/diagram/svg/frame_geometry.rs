//! The figure's plane geometry: boxes (a label's, a mark's, the frame the
//! scene is drawn in), whether they overlap or one holds another, and
//! segments (rays, outlines) cut to a box or measured to it.

use glam::DVec2;

/// A box as its (top-left, bottom-right) corners.
pub(crate) type Box2 = (DVec2, DVec2);

/// Whether the boxes `a` and `b` share more than an edge.
pub(super) fn overlap(a: Box2, b: Box2) -> bool {
    a.0.x < b.1.x && b.0.x < a.1.x && a.0.y < b.1.y && b.0.y < a.1.y
}

/// How far the segment from `a` to `b` comes to the box `r`: 0 when it
/// meets it; else the nearest of its ends to the box, or of the box's
/// corners to it (two convex shapes apart are nearest at a corner of one).
pub(super) fn segment_box_distance(a: DVec2, b: DVec2, r: Box2) -> f64 {
    if clip(a, b, r).is_some() {
        return 0.0;
    }
    let to_box = |p: DVec2| (p.clamp(r.0, r.1) - p).length();
    let to_segment = |p: DVec2| {
        let d = b - a;
        let t = ((p - a).dot(d) / d.length_squared()).clamp(0.0, 1.0);
        if d == DVec2::ZERO {
            (p - a).length()
        } else {
            (a + d * t - p).length()
        }
    };
    let corners = [r.0, DVec2::new(r.1.x, r.0.y), r.1, DVec2::new(r.0.x, r.1.y)];
    (corners.into_iter().map(to_segment))
        .chain([to_box(a), to_box(b)])
        .fold(f64::INFINITY, f64::min)
}

/// `inner` lies wholly inside `outer`.
pub(crate) fn contains(outer: Box2, inner: Box2) -> bool {
    outer.0.x <= inner.0.x
        && outer.0.y <= inner.0.y
        && inner.1.x <= outer.1.x
        && inner.1.y <= outer.1.y
}

/// The part of the segment from `a` to `b` inside `frame` (Liang-Barsky:
/// the segment's parameter range narrowed by each of the four edges), or
/// none when it misses the box.
pub(crate) fn clip(a: DVec2, b: DVec2, frame: Box2) -> Option<(DVec2, DVec2)> {
    let d = b - a;
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for (p, q) in [
        (-d.x, a.x - frame.0.x),
        (d.x, frame.1.x - a.x),
        (-d.y, a.y - frame.0.y),
        (d.y, frame.1.y - a.y),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
            continue;
        }
        let t = q / p;
        if p < 0.0 {
            t0 = t0.max(t);
        } else {
            t1 = t1.min(t);
        }
    }
    (t0 <= t1).then(|| (a + d * t0, a + d * t1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_segment_is_clipped_to_the_frame() {
        // y = 50 from x -10 to 110 through the box 0..100: cut at x 0 and 100.
        let frame = (DVec2::ZERO, DVec2::splat(100.0));
        let inside = clip(DVec2::new(-10.0, 50.0), DVec2::new(110.0, 50.0), frame);
        assert_eq!(
            inside,
            Some((DVec2::new(0.0, 50.0), DVec2::new(100.0, 50.0)))
        );
        // The diagonal from (50, 50) to (150, 150) leaves at (100, 100).
        let out = clip(DVec2::splat(50.0), DVec2::splat(150.0), frame);
        assert_eq!(out, Some((DVec2::splat(50.0), DVec2::splat(100.0))));
        // Wholly beside it, or parallel outside: none.
        assert_eq!(
            clip(DVec2::new(120.0, 0.0), DVec2::new(130.0, 90.0), frame),
            None
        );
        assert_eq!(
            clip(DVec2::new(-5.0, 0.0), DVec2::new(-5.0, 90.0), frame),
            None
        );
    }
}
