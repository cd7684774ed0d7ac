//! The nodes the queries walk, and the ray/box slab test.
//!
//! The builder's binary tree (`bvh::BuildNode`) is collapsed into a tree of
//! up to four children per node, whose boxes sit side by side in the node:
//! one ray meets all four in a handful of SSE2 instructions (`lanes`, two
//! boxes per instruction; `wide` does four per instruction where the CPU has
//! AVX), and a walk takes half as many steps down as in the binary tree, each
//! a single node read.
//!
//! Bounds are f64, like the tracing, so a box test answers exactly as the
//! scalar slab test would. Nodes with f32 bounds (rounded outward) were
//! measured before: the conversions cost more than the smaller nodes saved.

use glam::DVec3;

use super::bvh::{BuildNode, surface_area};
use super::lanes::Lanes;
use crate::math::Ray;
use crate::shapes::Aabb;

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
/// an empty box, which no ray meets. Aligned on a cache line: with 16-byte
/// alignment (240-byte nodes) three nodes in four began inside a line, and
/// some of the box test's 32-byte loads of corners straddled two (2 to 4 %
/// of the trace time of teapot, tetra and balls).
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
pub(super) struct Node {
    /// The children's least coordinates (`corners[0]`) and greatest
    /// (`corners[1]`), per axis: children 0 and 1, then 2 and 3.
    pub(super) corners: [[[Lanes; 2]; 3]; 2],
    pub(crate) children: [Child; WIDTH],
    /// How many children are present: the boxes a visit tests, for the cost.
    pub(crate) arity: u32,
}

impl Node {
    pub(super) fn new(boxes: &[Aabb], children: &[Child]) -> Node {
        debug_assert!(boxes.len() == children.len() && children.len() <= WIDTH);
        let mut all = [Aabb::EMPTY; WIDTH];
        all[..boxes.len()].copy_from_slice(boxes);
        let mut placed = [Child::NOTHING; WIDTH];
        placed[..children.len()].copy_from_slice(children);
        let lanes = |corner: fn(&Aabb) -> DVec3, axis: usize| {
            [0, 1].map(|half| Lanes::new([0, 1].map(|i| corner(&all[2 * half + i])[axis])))
        };
        Node {
            corners: [
                [0, 1, 2].map(|axis| lanes(|b| b.min, axis)),
                [0, 1, 2].map(|axis| lanes(|b| b.max, axis)),
            ],
            children: placed,
            arity: children.len() as u32,
        }
    }

    /// Child `i`'s box, as the builder made it.
    #[cfg(test)]
    pub(crate) fn bounds(&self, i: usize) -> Aabb {
        let corner = |l: &[[Lanes; 2]; 3]| DVec3::from(l.map(|v| v[i / 2].to_array()[i % 2]));
        Aabb::new(corner(&self.corners[0]), corner(&self.corners[1]))
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
        nodes[at].children[slot] = child;
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
                let near = node.corners[usize::from(downwards)][axis][half];
                let far = node.corners[usize::from(!downwards)][axis][half];
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
    use super::*;

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
    fn a_node_fills_four_cache_lines() {
        // Four boxes (192 bytes), four children (32), the arity (4), padded
        // to 64 and aligned on a line: no load of four corners straddles two lines.
        assert_eq!(std::mem::size_of::<Node>(), 256);
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
