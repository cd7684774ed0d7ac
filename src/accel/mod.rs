//! Which objects a ray meets: the closest-hit query for rays that shade, and
//! the every-crossing query for shadow rays.
//!
//! The bounded objects sit in a bounding volume hierarchy (`bvh`): a binary
//! tree of boxes, each around everything below it, stored as one flat array.
//! A query walks it from the root, skipping every subtree whose box the ray
//! misses, nearer child first. Infinite planes have no box; they are kept
//! aside and tested on every query. The answers are exactly those of testing
//! every object in file order (`brute`, kept as the oracle): only the cost,
//! the nodes visited and primitives tested that the debugger shows, differs.

pub mod brute;
mod bvh;
mod node;

use std::fmt;
use std::ops::ControlFlow;

use serde::Serialize;

use crate::math::{Interval, Ray};
use crate::scene::Object;
use bvh::{MAX_DEPTH, PrimitiveRef};
use node::{BoxTest, Node};

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

/// The query structure of a scene's objects, built once by `Accel::build`.
/// The queries take the same object list it was built from.
#[derive(Default)]
pub struct Accel {
    /// The hierarchy, root first; empty when no object is bounded.
    nodes: Vec<Node>,
    /// The objects of the leaves: a leaf holds `objects[offset..offset + count]`.
    objects: Vec<u32>,
    /// Objects without bounds (planes), in file order, tested by every query.
    unbounded: Vec<u32>,
}

impl Accel {
    pub fn build(objects: &[Object]) -> Accel {
        assert!(
            u32::try_from(objects.len()).is_ok(),
            "more objects than a u32 can count"
        );
        let mut bounded = Vec::with_capacity(objects.len());
        let mut unbounded = Vec::new();
        for (index, object) in objects.iter().enumerate() {
            let index = index as u32;
            match object.shape.bounds() {
                Some(b) if b.min.is_finite() && b.max.is_finite() => {
                    bounded.push(PrimitiveRef::new(index, b));
                }
                _ => unbounded.push(index),
            }
        }
        let bvh = bvh::build(bounded);
        Accel {
            nodes: bvh.nodes,
            objects: bvh.objects,
            unbounded,
        }
    }

    /// The nearest hit in `range`; on equal distances the first object in file order.
    pub fn closest(
        &self,
        objects: &[Object],
        ray: &Ray,
        range: Interval,
        cost: &mut Cost,
    ) -> Option<Candidate> {
        let mut nearest = Nearest {
            objects,
            ray,
            min: range.min,
            max: range.max,
            best: None,
        };
        // Planes first: a hit there shortens the ray before the walk.
        for &object in &self.unbounded {
            nearest.test(object, cost);
        }
        self.walk(ray, range.min, range.max, cost, |leaf, cost| {
            for &object in leaf {
                nearest.test(object, cost);
            }
            ControlFlow::Continue(nearest.max)
        });
        nearest.best
    }

    /// Calls `visit(object, t)` for every crossing of the segment `range` until
    /// it breaks. The order of the calls is fixed for a given ray and scene:
    /// the planes in file order, then the leaves nearer first, each leaf in
    /// file order and each object's roots in increasing t. It is not sorted by t.
    pub fn crossings(
        &self,
        objects: &[Object],
        ray: &Ray,
        range: Interval,
        cost: &mut Cost,
        mut visit: impl FnMut(usize, f64) -> ControlFlow<()>,
    ) {
        let mut segment = |object: u32, cost: &mut Cost| {
            cost.primitives += 1;
            let object = object as usize;
            for &t in objects[object].shape.roots(ray, range).as_slice() {
                visit(object, t)?;
            }
            ControlFlow::Continue(())
        };
        for &object in &self.unbounded {
            if segment(object, cost).is_break() {
                return;
            }
        }
        self.walk(ray, range.min, range.max, cost, |leaf, cost| {
            for &object in leaf {
                segment(object, cost)?;
            }
            ControlFlow::Continue(range.max)
        });
    }

    /// Visits, nearer child first, every leaf whose box meets the ray between
    /// `t_min` and `t_max`; `leaf` returns the new `t_max` or stops the walk.
    #[inline]
    fn walk(
        &self,
        ray: &Ray,
        t_min: f64,
        mut t_max: f64,
        cost: &mut Cost,
        mut leaf: impl FnMut(&[u32], &mut Cost) -> ControlFlow<(), f64>,
    ) {
        if self.nodes.is_empty() {
            return;
        }
        let boxes = BoxTest::new(ray);
        let mut stack = [0u32; MAX_DEPTH];
        let mut pending = 0;
        let mut index = 0;
        loop {
            let node = &self.nodes[index];
            cost.nodes += 1;
            if boxes.hits(node, t_min, t_max) {
                if !node.is_leaf() {
                    // The first child holds the smaller centroids along the axis.
                    let (near, far) = if boxes.negative(node.axis) {
                        (node.offset as usize, index + 1)
                    } else {
                        (index + 1, node.offset as usize)
                    };
                    stack[pending] = far as u32;
                    pending += 1;
                    index = near;
                    continue;
                }
                let first = node.offset as usize;
                match leaf(&self.objects[first..first + usize::from(node.count)], cost) {
                    ControlFlow::Continue(max) => t_max = max,
                    ControlFlow::Break(()) => return,
                }
            }
            if pending == 0 {
                return;
            }
            pending -= 1;
            index = stack[pending] as usize;
        }
    }
}

/// The closest-hit search so far: the best candidate and the range still open.
struct Nearest<'a> {
    objects: &'a [Object],
    ray: &'a Ray,
    min: f64,
    /// The best hit's t, or the range's end while there is none.
    max: f64,
    best: Option<Candidate>,
}

impl Nearest<'_> {
    /// Tests one object. The objects come in tree order, not file order, so a
    /// hit at exactly the best t must still win when its object comes first in
    /// the file: for such objects the range is closed at the best t.
    #[inline]
    fn test(&mut self, object: u32, cost: &mut Cost) {
        cost.primitives += 1;
        let object = object as usize;
        let max = match self.best {
            Some(best) if object < best.object => best.t.next_up(),
            _ => self.max,
        };
        if let Some(t) = self.objects[object]
            .shape
            .intersect(self.ray, Interval::new(self.min, max))
        {
            self.best = Some(Candidate { object, t });
            self.max = t;
        }
    }
}

impl fmt::Debug for Accel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Accel")
            .field("nodes", &self.nodes.len())
            .field("bounded", &self.objects.len())
            .field("unbounded", &self.unbounded.len())
            .finish()
    }
}
