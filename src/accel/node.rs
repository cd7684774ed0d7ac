//! The nodes the queries walk, and the ray/box slab test.
//!
//! The builder's binary tree (`bvh::BuildNode`) is laid out again so that
//! each node holds the boxes of its two children side by side, lane 0 the
//! first child and lane 1 the second: one ray meets both boxes in the same
//! SSE2 instructions (`lanes`), and the walk reads one node per step instead
//! of two. The root gets a node of its own, with nothing in lane 1.
//!
//! Bounds are f64, like the tracing, so a box test answers exactly as the
//! scalar slab test would. Nodes with f32 bounds (rounded outward) were
//! measured before: the conversions cost more than the smaller nodes saved.

use glam::DVec3;

use super::bvh::BuildNode;
use super::lanes::Lanes;
use crate::math::Ray;
use crate::shapes::Aabb;

/// What a child of a node is: a leaf's run of objects or another node.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Child {
    /// Leaf: the first position in the object array; interior: the node's index.
    pub offset: u32,
    /// Leaf: how many objects; interior: `INTERIOR`.
    pub count: u16,
}

const INTERIOR: u16 = u16::MAX;

impl Child {
    /// No child: an empty leaf, in lane 1 of the root's node.
    pub const NOTHING: Child = Child {
        offset: 0,
        count: 0,
    };

    fn node(index: usize) -> Child {
        Child {
            offset: index as u32,
            count: INTERIOR,
        }
    }

    pub fn is_leaf(self) -> bool {
        self.count != INTERIOR
    }
}

/// The boxes of two children and what they are. An absent child (lane 1 of
/// the root's node) has an empty box, which no ray meets.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
pub(super) struct Node {
    /// Per axis, the children's least coordinates.
    min: [Lanes; 3],
    /// Per axis, the children's greatest coordinates.
    max: [Lanes; 3],
    pub children: [Child; 2],
}

impl Node {
    fn new(boxes: [&Aabb; 2], children: [Child; 2]) -> Node {
        let lanes = |f: fn(&Aabb) -> DVec3, axis: usize| Lanes::new(boxes.map(|b| f(b)[axis]));
        Node {
            min: [0, 1, 2].map(|axis| lanes(|b| b.min, axis)),
            max: [0, 1, 2].map(|axis| lanes(|b| b.max, axis)),
            children,
        }
    }

    /// Child `lane`'s box, as the builder made it.
    #[cfg(test)]
    pub fn bounds(&self, lane: usize) -> Aabb {
        let corner = |l: &[Lanes; 3]| DVec3::from(l.map(|v| v.to_array()[lane]));
        Aabb::new(corner(&self.min), corner(&self.max))
    }
}

/// Lays the builder's tree (depth first, the first child right after its
/// parent, the second at `offset`) out as nodes of child pairs, the root's
/// node first, each interior node's pair numbered in depth-first order.
pub(super) fn pair_up(tree: &[BuildNode]) -> Vec<Node> {
    let Some(root) = tree.first() else {
        return Vec::new();
    };
    let mut nodes = Vec::with_capacity(tree.len() / 2 + 1);
    nodes.push(Node::new([&root.bounds, &Aabb::EMPTY], [Child::NOTHING; 2]));
    nodes[0].children[0] = place(tree, 0, &mut nodes);
    nodes
}

/// The child that stands for `tree[index]`, appending its pair (and all
/// below it) when it is interior.
fn place(tree: &[BuildNode], index: usize, nodes: &mut Vec<Node>) -> Child {
    let node = &tree[index];
    if node.is_leaf() {
        return Child {
            offset: node.offset,
            count: node.count,
        };
    }
    let (a, b) = (index + 1, node.offset as usize);
    let at = nodes.len();
    nodes.push(Node::new(
        [&tree[a].bounds, &tree[b].bounds],
        [Child::NOTHING; 2],
    ));
    let first = place(tree, a, nodes);
    let second = place(tree, b, nodes);
    nodes[at].children = [first, second];
    Child::node(at)
}

/// A ray prepared once for many box tests: per axis its origin and inverse
/// direction in both lanes, and whether it runs towards decreasing coordinates.
#[derive(Clone, Copy, Debug)]
pub(super) struct BoxTest {
    origin: [Lanes; 3],
    inverse: [Lanes; 3],
    negative: [bool; 3],
}

impl BoxTest {
    pub fn new(ray: &Ray) -> BoxTest {
        let inverse = DVec3::ONE / ray.direction;
        BoxTest {
            origin: ray.origin.to_array().map(Lanes::splat),
            inverse: inverse.to_array().map(Lanes::splat),
            // 1 / -0 = -inf: a ray with a -0 component counts as running downwards.
            negative: inverse.to_array().map(f64::is_sign_negative),
        }
    }

    /// Where the ray enters each child's box within (t_min, t_max), if it does.
    #[inline]
    pub fn entries(&self, node: &Node, t_min: f64, t_max: f64) -> [Option<f64>; 2] {
        let mut low = Lanes::splat(t_min);
        let mut high = Lanes::splat(t_max);
        for axis in 0..3 {
            let (near, far) = if self.negative[axis] {
                (node.max[axis], node.min[axis])
            } else {
                (node.min[axis], node.max[axis])
            };
            let t_near = near.sub(self.origin[axis]).mul(self.inverse[axis]);
            let t_far = far.sub(self.origin[axis]).mul(self.inverse[axis]);
            // A NaN (a ray along a face) keeps the bound: the second operand.
            low = t_near.max(low);
            high = t_far.min(high);
        }
        let hit = low.le_mask(high);
        let [a, b] = low.to_array();
        [(hit & 1 != 0).then_some(a), (hit & 2 != 0).then_some(b)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_box() -> Aabb {
        Aabb::new(DVec3::ZERO, DVec3::ONE)
    }

    impl BoxTest {
        /// Whether the ray meets the box within (t_min, t_max), asked in
        /// either lane, with the other lane's box different.
        fn hits(&self, bounds: &Aabb, t_min: f64, t_max: f64) -> bool {
            let leaf = Child {
                offset: 0,
                count: 1,
            };
            let other = Aabb::new(DVec3::splat(-3.0), DVec3::splat(-2.0));
            let [first, _] = self.entries(&Node::new([bounds, &other], [leaf; 2]), t_min, t_max);
            let [_, second] = self.entries(&Node::new([&other, bounds], [leaf; 2]), t_min, t_max);
            assert_eq!(first, second, "both lanes answer alike");
            first.is_some()
        }
    }

    fn test(origin: [f64; 3], direction: [f64; 3]) -> BoxTest {
        BoxTest::new(&Ray::new(DVec3::from(origin), DVec3::from(direction)))
    }

    #[test]
    fn node_is_112_bytes() {
        // Two boxes (96 bytes), two children (12), padded to 16.
        assert_eq!(std::mem::size_of::<Node>(), 112);
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
