//! The nodes the queries walk, and the ray/box slab test.
//!
//! The builder's binary tree (`bvh::BuildNode`) is collapsed into a tree of
//! up to four children per node, whose boxes sit side by side in the node:
//! one ray meets all four in a handful of SSE2 instructions (`lanes`, two
//! boxes per instruction; `wide` does four per instruction where the CPU has
//! AVX), and a walk takes half as many steps down as in the binary tree, each
//! a single node read.
//!
//! Bounds are stored as f32 rounded outward and widened to f64 for the test
//! (see `Node`): each box holds the builder's, so the walk opens every box a
//! hit lies in, and the hits themselves come from the objects' own f64
//! tests. The test's arithmetic is f64, like the tracing.

use super::bvh::{BuildNode, surface_area};
use super::lanes::Lanes;
use raystep_model::math::Ray;
use raystep_model::shapes::Aabb;

/// Children per node at most.
pub(super) const WIDTH: usize = 4;

/// What a child of a node is: a leaf's run of objects or another node.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Child {
    /// Leaf: the first position in the object array; interior: the node's index.
    pub(crate) offset: u32,
    /// Leaf: how many objects; interior: `INTERIOR`.
    pub(crate) count: u16,
}

const INTERIOR: u16 = u16::MAX;

impl Child {
    /// No child: an empty leaf with an empty box, filling a node's unused places.
    pub(crate) const NOTHING: Child = Child {
        offset: 0,
        count: 0,
    };

    pub(crate) fn node(index: usize) -> Child {
        Child {
            offset: index as u32,
            count: INTERIOR,
        }
    }

    pub(crate) fn is_leaf(self) -> bool {
        self.count != INTERIOR
    }
}

/// The boxes of up to four children and what they are. An absent child has
/// an empty box, which no ray meets.
///
/// The corners are f32, rounded outward (`outward`), widened back to f64 by
/// the box tests: every box holds the builder's, so no ray misses a box it
/// would meet, and a node is 128 bytes, two cache lines, where f64 corners
/// took four. On a scene far larger than the caches (a million spheres)
/// the walk waits on those lines; on the SPD scenes the widening costs
/// about what the smaller node saves. A box grows by at most one f32 step,
/// 2^-24 of its coordinates: a ray passing that close to a box opens it
/// for nothing, which changes the counted tests of a few rays only.
///
/// Aligned on a cache line, so that no load of corners straddles two.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
pub(super) struct Node {
    /// The children's least coordinates (`corners[0]`) and greatest
    /// (`corners[1]`), per axis, child by child.
    pub(super) corners: [[[f32; WIDTH]; 3]; 2],
    /// What each child is (`child`), split so the node fits two lines.
    offsets: [u32; WIDTH],
    counts: [u16; WIDTH],
    /// How many children are present: the boxes a visit tests, for the cost.
    pub(crate) arity: u32,
}

/// `x` rounded to an f32 towards `towards` (-inf for least corners, +inf
/// for greatest): the nearest f32 on that side, or `x` itself when exact.
/// Infinities stay; coordinates beyond f32's range become infinite.
fn outward(x: f64, towards: f64) -> f32 {
    let rounded = x as f32;
    let back = f64::from(rounded);
    if (towards < 0.0 && back > x) || (towards > 0.0 && back < x) {
        if towards < 0.0 {
            rounded.next_down()
        } else {
            rounded.next_up()
        }
    } else {
        rounded
    }
}

impl Node {
    pub(super) fn new(boxes: &[Aabb], children: &[Child]) -> Node {
        debug_assert!(boxes.len() == children.len() && children.len() <= WIDTH);
        let mut all = [Aabb::EMPTY; WIDTH];
        all[..boxes.len()].copy_from_slice(boxes);
        let mut node = Node {
            corners: [0, 1].map(|side| {
                let towards = if side == 0 { -1.0 } else { 1.0 };
                [0, 1, 2].map(|axis| {
                    all.map(|b| {
                        let corner = if side == 0 { b.min } else { b.max };
                        outward(corner[axis], towards)
                    })
                })
            }),
            offsets: [Child::NOTHING.offset; WIDTH],
            counts: [Child::NOTHING.count; WIDTH],
            arity: children.len() as u32,
        };
        for (i, &child) in children.iter().enumerate() {
            node.set_child(i, child);
        }
        node
    }

    /// Child `i`: a leaf's run of objects, another node, or `Child::NOTHING`.
    #[inline(always)]
    pub(crate) fn child(&self, i: usize) -> Child {
        Child {
            offset: self.offsets[i],
            count: self.counts[i],
        }
    }

    pub(super) fn set_child(&mut self, i: usize, child: Child) {
        self.offsets[i] = child.offset;
        self.counts[i] = child.count;
    }

    /// One axis's corners of children 0 and 1 (`half` 0) or 2 and 3, on one
    /// side (0 least, 1 greatest), widened to f64.
    #[inline(always)]
    pub(super) fn corner_lanes(&self, side: usize, axis: usize, half: usize) -> Lanes {
        let pair: &[f32; 2] = self.corners[side][axis][2 * half..2 * half + 2]
            .try_into()
            .expect("two corners");
        Lanes::widen(pair)
    }

    /// Child `i`'s box as the walk sees it: the builder's, rounded outward.
    #[cfg(test)]
    pub(crate) fn bounds(&self, i: usize) -> Aabb {
        let corner = |side: usize| {
            glam::DVec3::from([0, 1, 2].map(|axis| f64::from(self.corners[side][axis][i])))
        };
        Aabb::new(corner(0), corner(1))
    }
}

/// Collapses the builder's tree (depth first, the first child right after
/// its parent, the second at `offset`) into nodes of up to four children,
/// each node before the nodes below it. The walk starts at the first node:
/// the root's children, whose boxes lie inside the root's (so the root's own
/// box needs no test); or, when the root is a leaf, a node holding it alone.
pub(super) fn collapse(tree: &[BuildNode]) -> Vec<Node> {
    let Some(root) = tree.first() else {
        return Vec::new();
    };
    let mut nodes = Vec::with_capacity(tree.len() / 3 + 1);
    if root.is_leaf() {
        let leaf = place(tree, 0, &mut nodes);
        nodes.push(Node::new(&[root.bounds], &[leaf]));
    } else {
        place(tree, 0, &mut nodes);
    }
    nodes
}

/// The child that stands for `tree[index]`, appending its node (and all
/// below it) when it is interior. The node's children are the binary
/// subtrees met by opening, up to four, the interior one of largest surface
/// (the one most rays will open anyway), keeping the tree's left-to-right order.
fn place(tree: &[BuildNode], index: usize, nodes: &mut Vec<Node>) -> Child {
    let node = &tree[index];
    if node.is_leaf() {
        return Child {
            offset: node.offset,
            count: node.count,
        };
    }
    let mut under = vec![index + 1, node.offset as usize];
    while under.len() < WIDTH {
        let widest = under
            .iter()
            .enumerate()
            .filter(|&(_, &i)| !tree[i].is_leaf())
            .max_by(|&(_, &i), &(_, &j)| {
                surface_area(&tree[i].bounds).total_cmp(&surface_area(&tree[j].bounds))
            });
        let Some((at, &i)) = widest else { break };
        under.splice(at..=at, [i + 1, tree[i].offset as usize]);
    }
    let at = nodes.len();
    let boxes: Vec<Aabb> = under.iter().map(|&i| tree[i].bounds).collect();
    nodes.push(Node::new(&boxes, &vec![Child::NOTHING; under.len()]));
    for (slot, &i) in under.iter().enumerate() {
        let child = place(tree, i, nodes);
        nodes[at].set_child(slot, child);
    }
    Child::node(at)
}

/// A ray prepared once for many box tests: per axis its origin and inverse
/// direction in both lanes, and whether it runs towards decreasing coordinates.
#[derive(Clone, Copy, Debug)]
pub(super) struct BoxTest {
    origin: [Lanes; 3],
    inverse: [Lanes; 3],
    /// Per axis, whether the ray runs towards decreasing coordinates, and so
    /// meets a box's greatest corner first. Used as an index into the
    /// corners, not in a branch or a conditional move per box.
    downwards: [bool; 3],
}

/// A ray prepared for testing the four boxes of a node at once.
pub(super) trait BoxTesting {
    fn new(ray: &Ray) -> Self;

    /// Where the ray enters each child's box within (t_min, t_max): bit i of
    /// the mask is set when it meets child i's box, entering at `entry[i]`.
    fn entries(&self, node: &Node, t_min: f64, t_max: f64) -> (u32, [f64; WIDTH]);
}

impl BoxTesting for BoxTest {
    #[inline(always)]
    fn new(ray: &Ray) -> BoxTest {
        // Component by component: going through arrays made the compiler
        // store whole vectors and reload halves, stalling every query.
        let (o, d) = (ray.origin, ray.direction);
        let inverse = [1.0 / d.x, 1.0 / d.y, 1.0 / d.z];
        BoxTest {
            origin: [Lanes::splat(o.x), Lanes::splat(o.y), Lanes::splat(o.z)],
            inverse: [
                Lanes::splat(inverse[0]),
                Lanes::splat(inverse[1]),
                Lanes::splat(inverse[2]),
            ],
            // 1 / -0 = -inf: a ray with a -0 component counts as running downwards.
            downwards: inverse.map(f64::is_sign_negative),
        }
    }

    #[inline(always)]
    fn entries(&self, node: &Node, t_min: f64, t_max: f64) -> (u32, [f64; WIDTH]) {
        let mut mask = 0;
        let mut entry = [0.0; WIDTH];
        for half in 0..2 {
            let mut low = Lanes::splat(t_min);
            let mut high = Lanes::splat(t_max);
            for axis in 0..3 {
                let downwards = self.downwards[axis];
                let near = node.corner_lanes(usize::from(downwards), axis, half);
                let far = node.corner_lanes(usize::from(!downwards), axis, half);
                let t_near = near.sub(self.origin[axis]).mul(self.inverse[axis]);
                let t_far = far.sub(self.origin[axis]).mul(self.inverse[axis]);
                // A NaN (a ray along a face) keeps the bound: the second operand.
                low = t_near.max(low);
                high = t_far.min(high);
            }
            mask |= low.le_mask(high) << (2 * half);
            let [a, b] = low.to_array();
            entry[2 * half] = a;
            entry[2 * half + 1] = b;
        }
        (mask, entry)
    }
}

/// The children met (`mask`, three or four of them) nearest first by their
/// `entry`, ties in child order, as keys: an entry's bits with the child's
/// index in the two lowest (entries are not negative, so their bits sort as
/// they do), put in order by a network of compare-and-swap. The keys of the
/// children not met are `u64::MAX`, after the others.
#[inline(always)]
pub(super) fn nearest_first(mask: u32, entry: [f64; WIDTH]) -> [u64; WIDTH] {
    let mut keys = [u64::MAX; WIDTH];
    for (i, (key, t)) in keys.iter_mut().zip(entry).enumerate() {
        if mask & 1 << i != 0 {
            *key = (t.to_bits() & !3) | i as u64;
        }
    }
    for (x, y) in [(0, 1), (2, 3), (0, 2), (1, 3), (1, 2)] {
        let (low, high) = (keys[x].min(keys[y]), keys[x].max(keys[y]));
        keys[x] = low;
        keys[y] = high;
    }
    keys
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;

    #[test]
    fn corners_round_outward_to_the_nearest_f32() {
        // 0.1 lies between the f32 0.099999994 and 0.1 (0.100000001490116...):
        // a least corner takes the first, a greatest the second.
        assert_eq!(outward(0.1, -1.0), 0.099_999_994);
        assert_eq!(outward(0.1, 1.0), 0.1_f32);
        assert!(f64::from(outward(0.1, -1.0)) < 0.1 && f64::from(outward(0.1, 1.0)) > 0.1);
        assert_eq!(outward(-0.1, -1.0), -0.1_f32);
        assert_eq!(outward(-0.1, 1.0), -0.099_999_994);
        // Exact values, infinities and zeros stay; beyond f32's range is infinite.
        for x in [0.5, -3.0, 0.0, f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(f64::from(outward(x, -1.0)), x);
            assert_eq!(f64::from(outward(x, 1.0)), x);
        }
        assert_eq!(outward(1e39, 1.0), f32::INFINITY);
        assert_eq!(outward(1e39, -1.0), f32::MAX);
        assert_eq!(outward(-1e39, -1.0), f32::NEG_INFINITY);
        // Below f32's least step, a positive least corner rounds to 0.
        assert_eq!(outward(1e-50, -1.0), 0.0);
        assert_eq!(outward(1e-50, 1.0), f32::from_bits(1));
    }

    #[test]
    fn a_node_holds_each_box_it_was_given() {
        let boxes = [
            Aabb::new(
                DVec3::new(0.1, -0.3, 1e-3),
                DVec3::new(0.7, 2.0 / 3.0, 1e5 + 0.1),
            ),
            Aabb::new(DVec3::splat(-1e-9), DVec3::splat(1e-9)),
        ];
        let leaf = Child {
            offset: 0,
            count: 1,
        };
        let node = Node::new(&boxes, &[leaf; 2]);
        for (i, b) in boxes.iter().enumerate() {
            let held = node.bounds(i);
            assert!(
                held.min.cmple(b.min).all() && b.max.cmple(held.max).all(),
                "{held:?}"
            );
            // Grown by at most one f32 step of each coordinate.
            let step = (b.min.abs().max(b.max.abs())) * 2f64.powi(-23) + 1e-44;
            assert!((b.min - held.min).cmple(step).all() && (held.max - b.max).cmple(step).all());
        }
    }

    fn unit_box() -> Aabb {
        Aabb::new(DVec3::ZERO, DVec3::ONE)
    }

    impl BoxTest {
        /// Whether the ray meets the box within (t_min, t_max), asked in
        /// each of the four places, with the other places' boxes elsewhere.
        fn hits(&self, bounds: &Aabb, t_min: f64, t_max: f64) -> bool {
            let leaf = Child {
                offset: 0,
                count: 1,
            };
            let other = Aabb::new(DVec3::splat(-3.0), DVec3::splat(-2.0));
            let answers: Vec<Option<f64>> = (0..WIDTH)
                .map(|i| {
                    let mut boxes = [other; WIDTH];
                    boxes[i] = *bounds;
                    let (mask, entry) =
                        self.entries(&Node::new(&boxes, &[leaf; WIDTH]), t_min, t_max);
                    assert_eq!(mask & !(1 << i), 0, "only child {i} may be met");
                    (mask & 1 << i != 0).then_some(entry[i])
                })
                .collect();
            assert!(
                answers.iter().all(|a| *a == answers[0]),
                "all places answer alike"
            );
            answers[0].is_some()
        }
    }

    fn test(origin: [f64; 3], direction: [f64; 3]) -> BoxTest {
        BoxTest::new(&Ray::new(DVec3::from(origin), DVec3::from(direction)))
    }

    #[test]
    fn a_node_fills_two_cache_lines() {
        // Four boxes in f32 (96 bytes), four children (16 + 8), the arity
        // (4), padded to 64 and aligned on a line: two lines.
        assert_eq!(std::mem::size_of::<Node>(), 128);
        assert_eq!(std::mem::align_of::<Node>(), 64);
    }

    #[test]
    fn the_empty_box_is_never_met() {
        let t = test([0.5, 0.5, 0.5], [0.3, -0.2, 0.9]);
        assert!(!t.hits(&Aabb::EMPTY, 0.0, f64::INFINITY));
        let t = test([0.0, 0.0, 0.0], [0.0, 0.0, 0.0]);
        assert!(!t.hits(&Aabb::EMPTY, 0.0, f64::INFINITY));
    }

    #[test]
    fn oblique_ray_enters_and_leaves() {
        // From (-1, 0.5, 0.5) along (1, 0.25, 0): enters x = 0 at t = 1, leaves x = 1 at t = 2.
        let t = test([-1.0, 0.5, 0.5], [1.0, 0.25, 0.0]);
        assert!(t.hits(&unit_box(), 0.0, f64::INFINITY));
        // The segment must reach t = 1; the range is closed there.
        assert!(t.hits(&unit_box(), 0.0, 1.0));
        assert!(!t.hits(&unit_box(), 0.0, 0.999));
        assert!(t.hits(&unit_box(), 2.0, 5.0));
        assert!(!t.hits(&unit_box(), 2.001, 5.0));
        // Aimed past the box: at x = 0 it is at y = 1.75.
        assert!(!test([-1.0, 0.5, 0.5], [1.0, 1.25, 0.0]).hits(&unit_box(), 0.0, f64::INFINITY));
    }

    #[test]
    fn box_behind_the_ray_is_missed_and_origin_inside_is_hit() {
        assert!(!test([2.0, 0.5, 0.5], [1.0, 0.0, 0.0]).hits(&unit_box(), 1e-4, f64::INFINITY));
        assert!(test([0.5, 0.5, 0.5], [0.3, -0.2, 0.9]).hits(&unit_box(), 1e-4, f64::INFINITY));
    }

    #[test]
    fn axis_parallel_rays_with_zero_components() {
        // d = (0, 0, -1): x and y inverses are +inf.
        assert!(test([0.5, 0.5, 5.0], [0.0, 0.0, -1.0]).hits(&unit_box(), 0.0, f64::INFINITY));
        // Outside the x slab: (x - o) * inf is +inf for both faces: empty.
        assert!(!test([1.5, 0.5, 5.0], [0.0, 0.0, -1.0]).hits(&unit_box(), 0.0, f64::INFINITY));
        assert!(!test([-0.5, 0.5, 5.0], [0.0, 0.0, -1.0]).hits(&unit_box(), 0.0, f64::INFINITY));
        // Negative zero components: inverses are -inf; same answers.
        assert!(test([0.5, 0.5, 5.0], [-0.0, -0.0, -1.0]).hits(&unit_box(), 0.0, f64::INFINITY));
        assert!(!test([1.5, 0.5, 5.0], [-0.0, -0.0, -1.0]).hits(&unit_box(), 0.0, f64::INFINITY));
        assert!(!test([-0.5, 0.5, 5.0], [-0.0, 0.0, -1.0]).hits(&unit_box(), 0.0, f64::INFINITY));
    }

    #[test]
    fn ray_along_a_face_meets_the_box() {
        // Origin on the face x = 0 (and on x = 1), direction with x = 0: 0 * inf = NaN is ignored.
        for x in [0.0, 1.0] {
            for dx in [0.0, -0.0] {
                assert!(test([x, 0.5, 5.0], [dx, 0.0, -1.0]).hits(&unit_box(), 0.0, f64::INFINITY));
                // Still missed when the box is out of the range.
                assert!(!test([x, 0.5, 5.0], [dx, 0.0, -1.0]).hits(&unit_box(), 0.0, 3.0));
            }
        }
        // Along an edge: two NaN slabs.
        assert!(test([0.0, 1.0, 5.0], [0.0, -0.0, -1.0]).hits(&unit_box(), 0.0, f64::INFINITY));
        // Along the face's plane but outside the box in y.
        assert!(!test([0.0, 2.0, 5.0], [0.0, 0.0, -1.0]).hits(&unit_box(), 0.0, f64::INFINITY));
    }

    #[test]
    fn flat_box_is_hit_across_and_along() {
        // The box of a polygon in the plane z = 0: zero thickness.
        let flat = Aabb::new(DVec3::ZERO, DVec3::new(1.0, 1.0, 0.0));
        assert!(test([0.5, 0.5, 2.0], [0.0, 0.0, -1.0]).hits(&flat, 0.0, 2.0));
        assert!(test([0.5, 0.5, -2.0], [0.1, 0.0, 1.0]).hits(&flat, 0.0, f64::INFINITY));
        assert!(test([-1.0, 0.5, 0.0], [1.0, 0.0, 0.0]).hits(&flat, 0.0, f64::INFINITY));
        assert!(!test([-1.0, 0.5, 1e-9], [1.0, 0.0, 0.0]).hits(&flat, 0.0, f64::INFINITY));
    }

    #[test]
    fn zero_direction_meets_only_a_box_around_the_origin() {
        // Every inverse is infinite; every t is +-inf or NaN.
        assert!(test([0.5, 0.5, 0.5], [0.0, 0.0, 0.0]).hits(&unit_box(), 0.0, 1.0));
        assert!(!test([2.0, 0.5, 0.5], [0.0, 0.0, 0.0]).hits(&unit_box(), 0.0, 1.0));
    }
}
