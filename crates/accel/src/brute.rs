//! The brute-force queries: every object, in file order. Too slow for a render
//! of thousands of objects, but obviously right, so it is the oracle the
//! hierarchy is tested against, and the baseline its costs are compared with.

use std::ops::ControlFlow;

use super::{Candidate, Cost};
use raystep_model::math::{Interval, Ray};
use raystep_model::object::Object;

/// The nearest hit in `range`; on equal distances the first object in file order.
pub fn closest(
    objects: &[Object],
    ray: &Ray,
    range: Interval,
    cost: &mut Cost,
) -> Option<Candidate> {
    let mut best: Option<Candidate> = None;
    let mut range = range;
    for (object, o) in objects.iter().enumerate() {
        cost.primitives += 1;
        if let Some(t) = o.shape.intersect(ray, range) {
            best = Some(Candidate { object, t });
            // Keep strictly nearer hits only, so the first object wins a tie.
            range.max = t;
        }
    }
    best
}

/// Calls `visit(object, t)` for every crossing of the segment `range`, object
/// by object in file order and each object's roots in increasing t, until it breaks.
pub fn crossings(
    objects: &[Object],
    ray: &Ray,
    range: Interval,
    cost: &mut Cost,
    mut visit: impl FnMut(usize, f64) -> ControlFlow<()>,
) {
    for (object, o) in objects.iter().enumerate() {
        cost.primitives += 1;
        for &t in o.shape.roots(ray, range).as_slice() {
            if visit(object, t).is_break() {
                return;
            }
        }
    }
}
