//! One node of the flat hierarchy, and the ray/box slab test.
//!
//! Bounds are f64, like the tracing: a node is 56 bytes. Nodes with f32
//! bounds (rounded outward, 32 bytes) were measured too: on rays replayed from
//! 200 x 200 renders of the seven SPD scenes, closest-hit queries took about
//! 15 % longer and shadow queries about 5 % (the conversions cost more than
//! the smaller nodes save, the whole tree fitting in cache either way).

use glam::DVec3;

use crate::math::Ray;
use crate::shapes::Aabb;

/// A box and what is under it: a range of primitives (a leaf, `count > 0`)
/// or two children (`count == 0`): the first right after this node in the
/// array, the second at `offset`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub(super) struct Node {
    min: [f64; 3],
    max: [f64; 3],
    /// Leaf: the first position in the primitive index array; interior: the second child.
    pub offset: u32,
    /// Leaf: how many primitives (at least 1); interior: 0.
    pub count: u16,
    /// Interior: the axis the children were split on (0, 1, 2 for x, y, z).
    pub axis: u16,
}

impl Node {
    pub fn leaf(bounds: &Aabb, first: u32, count: u16) -> Node {
        debug_assert!(count > 0);
        Node::with_bounds(bounds, first, count, 0)
    }

    /// An interior node; its second child is filled in once it is placed.
    pub fn interior(bounds: &Aabb, axis: usize) -> Node {
        Node::with_bounds(bounds, 0, 0, axis as u16)
    }

    fn with_bounds(bounds: &Aabb, offset: u32, count: u16, axis: u16) -> Node {
        Node {
            min: bounds.min.to_array(),
            max: bounds.max.to_array(),
            offset,
            count,
            axis,
        }
    }

    pub fn is_leaf(&self) -> bool {
        self.count > 0
    }

    #[cfg(test)]
    pub fn bounds(&self) -> Aabb {
        Aabb::new(DVec3::from(self.min), DVec3::from(self.max))
    }
}

/// A ray prepared once for many box tests: its inverse direction and, per
/// axis, whether it runs towards decreasing coordinates.
#[derive(Clone, Copy, Debug)]
pub(super) struct BoxTest {
    origin: [f64; 3],
    inverse: [f64; 3],
    negative: [bool; 3],
}

impl BoxTest {
    pub fn new(ray: &Ray) -> BoxTest {
        let inverse = DVec3::ONE / ray.direction;
        BoxTest {
            origin: ray.origin.to_array(),
            inverse: inverse.to_array(),
            // 1 / -0 = -inf: a ray with a -0 component counts as running downwards.
            negative: inverse.to_array().map(f64::is_sign_negative),
        }
    }

    /// Whether the ray meets the box within (t_min, t_max).
    #[cfg(test)]
    pub fn hits(&self, node: &Node, t_min: f64, t_max: f64) -> bool {
        self.entry(node, t_min, t_max).is_some()
    }

    /// Where the ray enters the box within (t_min, t_max), if it does.
    #[inline]
    pub fn entry(&self, node: &Node, mut t_min: f64, mut t_max: f64) -> Option<f64> {
        for axis in 0..3 {
            let (near, far) = if self.negative[axis] {
                (node.max[axis], node.min[axis])
            } else {
                (node.min[axis], node.max[axis])
            };
            let t_near = (near - self.origin[axis]) * self.inverse[axis];
            let t_far = (far - self.origin[axis]) * self.inverse[axis];
            if t_near > t_min {
                t_min = t_near;
            }
            if t_far < t_max {
                t_max = t_far;
            }
        }
        (t_min <= t_max).then_some(t_min)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_box() -> Node {
        Node::leaf(&Aabb::new(DVec3::ZERO, DVec3::ONE), 0, 1)
    }

    fn test(origin: [f64; 3], direction: [f64; 3]) -> BoxTest {
        BoxTest::new(&Ray::new(DVec3::from(origin), DVec3::from(direction)))
    }

    #[test]
    fn node_is_56_bytes() {
        assert_eq!(std::mem::size_of::<Node>(), 56);
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
        let flat = Node::leaf(&Aabb::new(DVec3::ZERO, DVec3::new(1.0, 1.0, 0.0)), 0, 1);
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
