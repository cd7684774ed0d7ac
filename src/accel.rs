//! Which objects a ray meets: the closest-hit query for rays that shade, and
//! the every-crossing query for shadow rays.
//!
//! This first version tests every object in file order; a bounding volume
//! hierarchy replaces it behind the same interface.

use std::ops::ControlFlow;

use serde::Serialize;

use crate::math::{Interval, Ray};
use crate::scene::Object;

/// What one query tested: the price of a ray, shown to students.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Cost {
    /// Bounding-volume nodes visited.
    pub nodes: u32,
    /// Primitives whose intersection routine ran.
    pub primitives: u32,
}

/// The nearest object along a ray and its distance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Candidate {
    pub object: usize,
    pub t: f64,
}

#[derive(Debug, Default)]
pub struct Accel {
    object_count: usize,
}

impl Accel {
    pub fn build(objects: &[crate::scene::Object]) -> Accel {
        Accel { object_count: objects.len() }
    }

    /// The nearest hit in `range`; on equal distances the first object in file order.
    pub fn closest(&self, objects: &[Object], ray: &Ray, range: Interval, cost: &mut Cost) -> Option<Candidate> {
        let mut best: Option<Candidate> = None;
        let mut range = range;
        for (object, o) in objects.iter().enumerate().take(self.object_count) {
            cost.primitives += 1;
            if let Some(t) = o.shape.intersect(ray, range) {
                best = Some(Candidate { object, t });
                // Keep strictly nearer hits only, so the first object wins a tie.
                range.max = t;
            }
        }
        best
    }

    /// Calls `visit(object, t)` for every crossing of the segment `range` until
    /// it breaks. The order of the calls is fixed for a given ray.
    pub fn crossings(
        &self,
        objects: &[Object],
        ray: &Ray,
        range: Interval,
        cost: &mut Cost,
        mut visit: impl FnMut(usize, f64) -> ControlFlow<()>,
    ) {
        for (object, o) in objects.iter().enumerate().take(self.object_count) {
            cost.primitives += 1;
            for &t in o.shape.roots(ray, range).as_slice() {
                if visit(object, t).is_break() {
                    return;
                }
            }
        }
    }
}
