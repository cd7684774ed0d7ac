//! Which objects a ray meets: the closest-hit query for rays that shade, and
//! the every-crossing query for shadow rays.
//!
//! The bounded objects sit in a bounding volume hierarchy: a tree of boxes,
//! each around everything below it, built binary (`bvh`) and stored as one
//! flat array of nodes of up to four children (`node`). A query walks it from
//! the root, skipping every subtree whose box the ray misses, nearest child
//! first. Infinite planes have no box; they are kept
//! aside and tested on every query. The answers are exactly those of testing
//! every object in file order (`brute`, kept as the oracle): the same nearest
//! hit to the bit, the same crossings (in another order). Only the cost, the
//! nodes visited and primitives tested that the debugger shows, differs.
//!
//! Each query is compiled twice: for any x86-64, testing a node's boxes with
//! SSE2, and for CPUs with AVX2 and FMA, with AVX (`wide`); the second runs
//! where the CPU allows. Both give the same answers; the same costs too,
//! except where a ray grazes a box within rounding (none of the 10^8 box
//! tests of the seven SPD scenes does).
//!
//! Beside the hierarchy live the render's other speed-ups, so that `shapes`
//! and `trace` read as the lecture; each gives the plain code's answers to
//! the bit, and its tests compare it with the plain code: the leaves'
//! packed shape records (`leaf_shapes`, with `edge_bands` for many-sided
//! polygons), the shadow query that tries a row's last blocker first
//! (`shadow`), the objects' materials and normal recipes side by side
//! (`object_tables`, `normals`), and a row's primary rays' nearest hits
//! found eight at a time in one walk (`packet`,
//! whose leaves test each triangle across the rays, `packet_triangles`).

pub mod brute;
mod bvh;
mod cylinder_reach;
mod edge_bands;
mod lanes;
mod leaf_shapes;
mod node;
mod normals;
mod object_tables;
mod packet;
mod packet_triangles;
mod ray_lanes;
mod shadow;
#[cfg(target_arch = "x86_64")]
mod wide;

use std::fmt;
use std::ops::ControlFlow;

use arrayvec::ArrayVec;
use glam::DVec3;
use serde::Serialize;

use bvh::{Bvh, MAX_DEPTH, PrimitiveRef};
use leaf_shapes::LeafShape;
use node::{BoxTesting, Child, Node, WIDTH, nearest_first};
pub use object_tables::ObjectTables;
pub use packet::PACKET;
use raystep_model::math::{Interval, Ray};
use raystep_model::object::Object;
use raystep_model::shapes::Roots;
pub use shadow::ShadowCache;

/// What one query tested: the price of a ray, shown to students.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Cost {
    /// Bounding-volume nodes whose box was tested against the ray (all the
    /// children of each node the walk reached).
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
#[derive(Clone)]
pub struct Accel {
    /// The hierarchy, up to four child boxes per node, the walk's start
    /// first (`node::collapse`); empty when no object is bounded.
    nodes: Vec<Node>,
    /// The objects of the leaves: a leaf holds `objects[offset..offset + count]`.
    objects: Vec<u32>,
    /// Objects without bounds (planes), in file order, tested by every query.
    unbounded: Vec<u32>,
    /// Beside each entry of `objects`, what its test reads, packed.
    shapes: Vec<LeafShape>,
    /// Each object's position in `objects` (and `shapes`), `u32::MAX` for
    /// the unbounded: the shadow query tests a remembered blocker by its record.
    positions: Vec<u32>,
}

impl Accel {
    pub fn build(objects: &[Object]) -> Accel {
        let (bvh, unbounded) = build_tree(objects);
        // The builder's tree is freed before the leaf records are made: at
        // once they were the peak of a large scene's memory (28 bytes a
        // triangle of tetra at 4^8 and 4^10).
        let nodes = node::collapse(&bvh.nodes);
        let Bvh {
            nodes: binary,
            objects: order,
        } = bvh;
        drop(binary);
        let shapes = order
            .iter()
            .map(|&object| LeafShape::of(&objects[object as usize].shape))
            .collect();
        let mut positions = vec![u32::MAX; objects.len()];
        for (position, &object) in order.iter().enumerate() {
            positions[object as usize] = position as u32;
        }
        Accel {
            nodes,
            objects: order,
            unbounded,
            shapes,
            positions,
        }
    }

    /// `objects[object].shape.geometric_normal(point)` from the object's
    /// leaf record, when that is a triangle's test or a sphere; else `None`.
    #[inline]
    pub(crate) fn leaf_normal(&self, object: usize, point: DVec3) -> Option<DVec3> {
        let position = *self.positions.get(object)?;
        self.shapes.get(position as usize)?.normal_at(point)
    }

    /// The nearest hit in `range`; on equal distances the first object in file order.
    #[inline]
    pub fn closest(
        &self,
        objects: &[Object],
        ray: &Ray,
        range: Interval,
        cost: &mut Cost,
    ) -> Option<Candidate> {
        #[cfg(target_arch = "x86_64")]
        if wide::available() {
            // SAFETY: the CPU has the features `closest_wide` is compiled for.
            return unsafe { self.closest_wide(objects, ray, range, cost) };
        }
        self.closest_sse2(objects, ray, range, cost)
    }

    /// `closest` with the SSE2 box test. Not inlined into `closest`: its
    /// large frame (the walk's stack) would then be set up, and its registers
    /// saved, on every query, before the choice of copy.
    #[inline(never)]
    fn closest_sse2(
        &self,
        objects: &[Object],
        ray: &Ray,
        range: Interval,
        cost: &mut Cost,
    ) -> Option<Candidate> {
        self.closest_with::<node::BoxTest>(objects, ray, range, cost)
    }

    /// `closest` compiled for CPUs with AVX2, FMA and their companions (the
    /// features `wide::available` checks), with the AVX box test.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx,avx2,fma,bmi1,bmi2,lzcnt,popcnt,sse3,ssse3,sse4.1,sse4.2")]
    unsafe fn closest_wide(
        &self,
        objects: &[Object],
        ray: &Ray,
        range: Interval,
        cost: &mut Cost,
    ) -> Option<Candidate> {
        self.closest_with::<wide::BoxTest>(objects, ray, range, cost)
    }

    /// The query itself, for either box test.
    #[inline(always)]
    fn closest_with<B: BoxTesting>(
        &self,
        objects: &[Object],
        ray: &Ray,
        range: Interval,
        cost: &mut Cost,
    ) -> Option<Candidate> {
        let mut nearest = Nearest {
            objects,
            ray,
            range,
            best: Candidate {
                object: NONE_YET,
                t: range.max,
            },
        };
        // Planes first: a hit there shortens the ray before the walk.
        for &object in &self.unbounded {
            nearest.test(object, &LeafShape::Other, cost);
        }
        self.walk::<true, B>(ray, range.min, range.max, cost, |first, leaf, cost| {
            for (&object, shape) in leaf.iter().zip(&self.shapes[first..]) {
                nearest.test(object, shape, cost);
            }
            ControlFlow::Continue(nearest.best.t)
        });
        let best = nearest.best;
        (best.object != NONE_YET).then_some(best)
    }

    /// Calls `visit(object, t)` for every crossing of the segment `range` until
    /// it breaks. The order of the calls is fixed for a given ray and scene:
    /// the planes in file order, then the leaves in the order of the walk
    /// (children met in tree order, not by distance: most shadow segments
    /// reach their light, so all their boxes are opened anyway, and sorting
    /// cost more than it saved), each leaf in file order and each object's
    /// roots in increasing t. It is not sorted by t.
    pub fn crossings(
        &self,
        objects: &[Object],
        ray: &Ray,
        range: Interval,
        cost: &mut Cost,
        visit: impl FnMut(usize, f64) -> ControlFlow<()>,
    ) {
        #[cfg(target_arch = "x86_64")]
        if wide::available() {
            // SAFETY: the CPU has the features `crossings_wide` is compiled for.
            return unsafe { self.crossings_wide(objects, ray, range, cost, visit) };
        }
        self.crossings_sse2(objects, ray, range, cost, visit)
    }

    /// `crossings` with the SSE2 box test, apart for the reason given at
    /// `closest_sse2`.
    #[inline(never)]
    fn crossings_sse2(
        &self,
        objects: &[Object],
        ray: &Ray,
        range: Interval,
        cost: &mut Cost,
        visit: impl FnMut(usize, f64) -> ControlFlow<()>,
    ) {
        self.crossings_with::<node::BoxTest>(objects, ray, range, cost, visit)
    }

    /// `crossings` compiled for CPUs with AVX2, FMA and their companions (the
    /// features `wide::available` checks), with the AVX box test.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx,avx2,fma,bmi1,bmi2,lzcnt,popcnt,sse3,ssse3,sse4.1,sse4.2")]
    unsafe fn crossings_wide(
        &self,
        objects: &[Object],
        ray: &Ray,
        range: Interval,
        cost: &mut Cost,
        visit: impl FnMut(usize, f64) -> ControlFlow<()>,
    ) {
        self.crossings_with::<wide::BoxTest>(objects, ray, range, cost, visit)
    }

    /// The query itself, for either box test.
    #[inline(always)]
    fn crossings_with<B: BoxTesting>(
        &self,
        objects: &[Object],
        ray: &Ray,
        range: Interval,
        cost: &mut Cost,
        mut visit: impl FnMut(usize, f64) -> ControlFlow<()>,
    ) {
        // Each object's crossings, in increasing t.
        let mut cross = |object: usize, roots: Roots| {
            roots.as_slice().iter().try_for_each(|&t| visit(object, t))
        };
        for &object in &self.unbounded {
            cost.primitives += 1;
            let object = object as usize;
            if cross(object, objects[object].shape.roots(ray, range)).is_break() {
                return;
            }
        }
        self.walk::<false, B>(ray, range.min, range.max, cost, |first, leaf, cost| {
            for (&object, shape) in leaf.iter().zip(&self.shapes[first..]) {
                cost.primitives += 1;
                let object = object as usize;
                cross(object, shape.roots(objects, object, ray, range))?;
            }
            ControlFlow::Continue(range.max)
        });
    }

    /// Visits every leaf whose box meets the ray between `t_min` and `t_max`,
    /// the children of a node nearest first when `NEAREST_FIRST`, else in
    /// tree order. `leaf` gets the leaf's first position in `objects` (and so
    /// in `shapes`) and its objects, and returns the new `t_max` or stops
    /// the walk. Every
    /// query's range starts at `EPS`: `t_min` must not be negative, or the
    /// ordering below would round entries up rather than down.
    #[inline(always)]
    fn walk<const NEAREST_FIRST: bool, B: BoxTesting>(
        &self,
        ray: &Ray,
        t_min: f64,
        mut t_max: f64,
        cost: &mut Cost,
        mut leaf: impl FnMut(usize, &[u32], &mut Cost) -> ControlFlow<(), f64>,
    ) {
        if self.nodes.is_empty() {
            return;
        }
        debug_assert!(t_min >= 0.0, "walks start in front of the ray: {t_min}");
        let boxes = B::new(ray);
        // The children met are entered nearest first; the others wait with
        // their entry distances, and are skipped once a hit closer than their
        // entry is known. Not zeroed: a shadow ray visits a handful of nodes,
        // and clearing a whole array for it cost a fifth of the walk.
        let mut stack = ArrayVec::<(Child, f64), { MAX_DEPTH * (WIDTH - 1) }>::new();
        let mut node = &self.nodes[0];
        // Counted here and added once: `cost` is also the leaves', so adding
        // to it on every step would go through memory.
        let mut tested = 0;
        'walk: loop {
            tested += node.arity;
            let (mask, entry) = boxes.entries(node, t_min, t_max);
            let mut next = match mask {
                0 => None,
                // One child met: one arm per child, so that the next node's
                // address follows a predicted branch rather than the box
                // test's result, and its load can start before the test ends.
                1 => Some(node.child(0)),
                2 => Some(node.child(1)),
                4 => Some(node.child(2)),
                8 => Some(node.child(3)),
                _ if !NEAREST_FIRST => {
                    // The first child met goes next, the others wait.
                    let mut rest = mask & (mask - 1);
                    while rest != 0 {
                        let i = rest.trailing_zeros() as usize;
                        stack.push((node.child(i), entry[i]));
                        rest &= rest - 1;
                    }
                    Some(node.child(mask.trailing_zeros() as usize))
                }
                // Nearest first, ties in child order; the others wait on the
                // stack, the farthest pushed first. An entry is at least
                // t_min >= 0, and a non-negative f64 orders as its bits do:
                // with the child in the two lowest bits (the entry rounded
                // down, which keeps the pruning safe) the keys compare as
                // integers.
                // Two children met (a fifth of all steps): one comparison,
                // again an arm per pair, so that the next node's address
                // follows predicted branches.
                3 => Some(nearer_of_two(&mut stack, node, &entry, 0, 1)),
                5 => Some(nearer_of_two(&mut stack, node, &entry, 0, 2)),
                6 => Some(nearer_of_two(&mut stack, node, &entry, 1, 2)),
                9 => Some(nearer_of_two(&mut stack, node, &entry, 0, 3)),
                10 => Some(nearer_of_two(&mut stack, node, &entry, 1, 3)),
                12 => Some(nearer_of_two(&mut stack, node, &entry, 2, 3)),
                _ => {
                    // Three or four: a sorting network of compare-and-swap.
                    let keys = nearest_first(mask, entry);
                    let count = mask.count_ones() as usize;
                    for &key in keys[1..count].iter().rev() {
                        stack.push((node.child((key & 3) as usize), f64::from_bits(key & !3)));
                    }
                    Some(node.child((keys[0] & 3) as usize))
                }
            };
            loop {
                match next {
                    Some(child) if child.is_leaf() => {
                        let first = child.offset as usize;
                        let run = &self.objects[first..first + usize::from(child.count)];
                        match leaf(first, run, cost) {
                            ControlFlow::Continue(max) => t_max = max,
                            ControlFlow::Break(()) => break 'walk,
                        }
                    }
                    Some(child) => {
                        node = &self.nodes[child.offset as usize];
                        break;
                    }
                    None => {}
                }
                next = loop {
                    let Some((child, entry)) = stack.pop() else {
                        break 'walk;
                    };
                    if entry <= t_max {
                        break Some(child);
                    }
                };
            }
        }
        cost.nodes += tested;
    }
}

/// Of children `i` < `j` of `node`, both met, the nearer (by entry rounded
/// down as the walk's keys are, `i` on a tie), pushing the other with its
/// entry so rounded.
#[inline(always)]
fn nearer_of_two<const N: usize>(
    stack: &mut ArrayVec<(Child, f64), N>,
    node: &Node,
    entry: &[f64; WIDTH],
    i: usize,
    j: usize,
) -> Child {
    let (a, b) = (entry[i].to_bits() & !3, entry[j].to_bits() & !3);
    if a <= b {
        stack.push((node.child(j), f64::from_bits(b)));
        node.child(i)
    } else {
        stack.push((node.child(i), f64::from_bits(a)));
        node.child(j)
    }
}

/// The builder's binary tree over the bounded objects, and the unbounded ones.
fn build_tree(objects: &[Object]) -> (Bvh, Vec<u32>) {
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
    (bvh::build(bounded), unbounded)
}

/// The closest-hit search so far: the query's range and the best candidate.
struct Nearest<'a> {
    objects: &'a [Object],
    ray: &'a Ray,
    range: Interval,
    /// Before any hit, `NONE_YET` at the range's end. Not an `Option`: the
    /// answer was read back whole from memory just after a part of it was
    /// written, which stalled every query (a tenth of an empty scene's time).
    best: Candidate,
}

/// No object: greater than every object's index, so never first in the file.
const NONE_YET: usize = usize::MAX;

impl Nearest<'_> {
    /// Tests one object, through its packed record. The objects come in tree
    /// order, not file order, so a hit at exactly the best t must still win
    /// when its object comes first in the file: for such objects the range is
    /// closed at the best t. (`test_with` is the same steps; written through
    /// it, with a closure, the SPD scenes took 0.2 to 0.4 % more instructions.)
    #[inline]
    fn test(&mut self, object: u32, shape: &LeafShape, cost: &mut Cost) {
        cost.primitives += 1;
        let object = object as usize;
        let best = self.best;
        let max = if object < best.object && best.object != NONE_YET {
            best.t.next_up()
        } else {
            best.t
        };
        let range = Interval::new(self.range.min, max);
        if let Some(t) = shape.intersect(self.objects, object, self.ray, range) {
            self.best = Candidate { object, t };
        }
    }
}

#[cfg(test)]
impl Nearest<'_> {
    /// `test` with the intersection given: `hit(range)` is the object's
    /// nearest hit in `range`, as `LeafShape::intersect` gives it.
    #[inline(always)]
    fn test_with(&mut self, object: u32, hit: impl FnOnce(&Ray, Interval) -> Option<f64>) {
        let object = object as usize;
        let best = self.best;
        let max = if object < best.object && best.object != NONE_YET {
            best.t.next_up()
        } else {
            best.t
        };
        if let Some(t) = hit(self.ray, Interval::new(self.range.min, max)) {
            self.best = Candidate { object, t };
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

/// A small deterministic generator for the tests of accel's files (no
/// dependency needed for this); each test file adds the draws it needs.
#[cfg(test)]
struct Numbers(u64);

#[cfg(test)]
impl Numbers {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::bvh::MAX_LEAF;
    use super::*;
    use raystep_model::shapes::{Aabb, Plane, Shape, Sphere};

    fn sphere(center: DVec3, radius: f64) -> Object {
        Object {
            name: "".into(),
            shape: Shape::Sphere(Sphere::new(center, radius).unwrap()),
            material: 0,
        }
    }

    /// Checks the child whose box is `b`, reached `depth` boxes down, and
    /// returns its depth, the nodes under it and the objects of its leaves.
    fn check(
        accel: &Accel,
        objects: &[Object],
        child: Child,
        b: &Aabb,
        outer: &Aabb,
        depth: usize,
    ) -> (usize, Vec<usize>, Vec<u32>) {
        assert!(
            outer.min.cmple(b.min).all() && b.max.cmple(outer.max).all(),
            "{child:?} sticks out of its parent"
        );
        if child.is_leaf() {
            let first = child.offset as usize;
            let leaf = &accel.objects[first..first + usize::from(child.count)];
            assert!(
                !leaf.is_empty() && leaf.len() <= MAX_LEAF && leaf.is_sorted(),
                "{child:?}: {leaf:?}"
            );
            for &o in leaf {
                let p = objects[o as usize].shape.bounds().unwrap();
                assert!(
                    b.min.cmplt(p.min).all() && p.max.cmplt(b.max).all(),
                    "object {o} not strictly inside"
                );
            }
            return (depth, Vec::new(), leaf.to_vec());
        }
        let index = child.offset as usize;
        let node = &accel.nodes[index];
        let arity = node.arity as usize;
        assert!(
            (2..=WIDTH).contains(&arity),
            "node {index} has {arity} children"
        );
        for unused in arity..WIDTH {
            assert_eq!(node.child(unused), Child::NOTHING);
            assert_eq!(node.bounds(unused), Aabb::EMPTY);
        }
        let (mut deepest, mut nodes, mut under) = (depth, vec![index], Vec::new());
        for lane in 0..arity {
            let (d, n, o) = check(
                accel,
                objects,
                node.child(lane),
                &node.bounds(lane),
                b,
                depth + 1,
            );
            deepest = deepest.max(d);
            nodes.extend(n);
            under.extend(o);
        }
        (deepest, nodes, under)
    }

    fn check_all(objects: &[Object]) -> usize {
        let accel = Accel::build(objects);
        // The walk starts at node 0: the root's children, or a lone leaf.
        let everything = Aabb::new(DVec3::NEG_INFINITY, DVec3::INFINITY);
        let top = &accel.nodes[0];
        let (depth, mut nodes, mut seen) = if top.arity == 1 {
            assert!(top.child(0).is_leaf(), "a lone root is a leaf");
            let (depth, _, seen) = check(
                &accel,
                objects,
                top.child(0),
                &top.bounds(0),
                &everything,
                1,
            );
            (depth, vec![0], seen)
        } else {
            check(&accel, objects, Child::node(0), &everything, &everything, 0)
        };
        // Every node is reached exactly once.
        nodes.sort_unstable();
        assert_eq!(nodes, (0..accel.nodes.len()).collect::<Vec<_>>());
        assert!(depth <= bvh::MAX_DEPTH);
        seen.extend(&accel.unbounded);
        seen.sort_unstable();
        assert_eq!(
            seen,
            (0..objects.len() as u32).collect::<Vec<_>>(),
            "every object exactly once"
        );
        depth
    }

    #[test]
    fn tree_holds_every_object_once_inside_its_boxes() {
        // A deterministic scatter of spheres of many sizes, and a plane.
        let mut objects: Vec<Object> = (0..3000)
            .map(|i| {
                let f = i as f64;
                let center = DVec3::new(
                    (f * 0.618).fract(),
                    (f * 0.414).fract(),
                    (f * 0.732).fract(),
                ) * 100.0;
                sphere(center, 0.01 + (f * 0.3).fract())
            })
            .collect();
        objects.push(Object {
            name: "".into(),
            shape: Shape::Plane(Plane::new(DVec3::Y, DVec3::ZERO).unwrap()),
            material: 0,
        });
        let depth = check_all(&objects);
        assert!(depth < 30, "depth {depth}");
    }

    #[test]
    fn a_root_that_is_a_leaf_gets_a_node_of_its_own() {
        // Three spheres around one centre cannot be told apart: one leaf, so
        // node 0 holds it alone.
        let objects: Vec<Object> = (1..4).map(|i| sphere(DVec3::ZERO, i as f64)).collect();
        check_all(&objects);
        let accel = Accel::build(&objects);
        assert_eq!((accel.nodes.len(), accel.nodes[0].arity), (1, 1));
    }

    #[test]
    fn coincident_objects_are_split_into_small_leaves() {
        // Nothing tells them apart: the list is halved until leaves are small.
        let objects: Vec<Object> = (0..1000).map(|_| sphere(DVec3::ONE, 1.0)).collect();
        check_all(&objects);
    }

    #[test]
    fn centroids_spread_beyond_the_f64_range_are_halved() {
        // From -1e308 to 1e308 the extent overflows to infinity: no bins.
        let objects: Vec<Object> = (0..100)
            .map(|i| sphere(DVec3::X * if i % 2 == 0 { 1e308 } else { -1e308 }, 1.0))
            .collect();
        check_all(&objects);
    }

    #[test]
    fn depth_stays_bounded_on_a_skewed_scene() {
        // Radii and spacing doubling every other sphere: the SAH peels a pair off
        // per level, until the median split takes over.
        let objects: Vec<Object> = (0..200)
            .map(|i| sphere(DVec3::X * 2f64.powi(i / 2), 2f64.powi(i / 2 - 3)))
            .collect();
        check_all(&objects);
        let (bvh, _) = build_tree(&objects);
        assert!(
            binary_depth(&bvh.nodes, 0) > 32,
            "deep enough to need the median split"
        );
    }

    /// Levels of the builder's binary tree under `tree[index]`, itself included.
    fn binary_depth(tree: &[bvh::BuildNode], index: usize) -> usize {
        let node = &tree[index];
        if node.is_leaf() {
            return 1;
        }
        1 + binary_depth(tree, index + 1).max(binary_depth(tree, node.offset as usize))
    }

    #[test]
    fn unbounded_and_non_finite_objects_are_tested_on_every_query() {
        let objects = vec![
            sphere(DVec3::ZERO, 1.0),
            Object {
                name: "".into(),
                shape: Shape::Plane(Plane::new(DVec3::Z, DVec3::ZERO).unwrap()),
                material: 0,
            },
            sphere(DVec3::new(f64::NAN, 0.0, 0.0), 1.0),
        ];
        let accel = Accel::build(&objects);
        assert_eq!(accel.unbounded, [1, 2]);
        assert_eq!(accel.objects, [0]);
    }
}
