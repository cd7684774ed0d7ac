//! A row's primary rays traced eight at a time: one walk of the hierarchy
//! for a packet of rays from one origin, the answers each ray's own
//! `closest` would give, to the bit.
//!
//! The eight rays of neighbouring pixels point almost the same way, so they
//! open almost the same nodes. The walk tests each node's four boxes once
//! for the whole packet, with interval arithmetic: per axis, the slab
//! distances (c - o) (1/d) of all eight rays lie between (c - o) times the
//! least and the greatest of their 1/d (rounding is monotone, so this holds
//! for the rounded numbers too). A box the packet misses so, every ray's own
//! box test (the SSE2 test of `node::BoxTest`, same operations) misses too,
//! and that test never misses a box holding a ray's nearest hit
//! (`closest_sse2` answers as brute force); the AVX copy bounds the same
//! way, without fused steps.
//! At a leaf, each ray's own box test, done eight rays at a time, decides
//! which rays test the leaf's objects. So every ray tests every object its
//! own walk would test where the hit could be (and maybe a few more): its
//! nearest hit, by the same tie rule (`Nearest::test`), is the same.
//! A leaf's triangles, and the quads met by two rays or more, are tested
//! across those rays at once (`packet_triangles`, each lane the scalar
//! test's operations); other objects ray by ray.
//!
//! Packets of fewer than eight rays (a row's last pixels), and those whose
//! rays do not share an origin, or whose directions differ in sign along an
//! axis or have a zero component (a 1/d interval would then be unbounded),
//! are traced ray by ray with `closest`.
//!
//! No costs are counted: a render whose recorder counts nodes and
//! primitives (`--stats`, recordings) keeps the per-ray query, so the
//! numbers it shows are those of one ray.

#[cfg(target_arch = "x86_64")]
use std::arch::x86_64::{
    __m256d, _CMP_LE_OQ, _mm_loadu_ps, _mm256_cmp_pd, _mm256_cvtps_pd, _mm256_max_pd,
    _mm256_min_pd, _mm256_movemask_pd, _mm256_mul_pd, _mm256_set1_pd, _mm256_storeu_pd,
    _mm256_sub_pd,
};

use arrayvec::ArrayVec;
use glam::DVec3;

use super::bvh::MAX_DEPTH;
use super::lanes::Lanes;
use super::leaf_shapes::LeafShape;
use super::node::{BoxTesting, Child, Node, WIDTH, nearest_first};
use super::packet_triangles::{Bests, LeafRays, NO_OBJECT, TestQuad, test_triangle};
use super::ray_lanes::{Narrow, RayLanes};
use super::{Accel, Candidate, Cost, NONE_YET, Nearest};
use raystep_model::math::{Interval, Ray};
use raystep_model::object::Object;
use raystep_model::shapes::{Polygon, Shape};

/// Rays per packet.
pub const PACKET: usize = 8;

/// Every ray of a packet, one bit each.
const ALL: u8 = u8::MAX;

/// A packet's rays prepared for its walk: the shared origin, each ray's
/// inverse direction (structure of arrays; unused places repeat the last
/// ray), and per axis the least and greatest of them.
#[derive(Clone, Copy, Debug)]
pub(super) struct Packet {
    origin: [f64; 3],
    /// Each ray's direction and its inverse, axis by axis.
    direction: [[f64; PACKET]; 3],
    inverse: [[f64; PACKET]; 3],
    least: [f64; 3],
    greatest: [f64; 3],
    /// Per axis, whether every ray runs towards decreasing coordinates.
    downwards: [bool; 3],
}

impl Packet {
    /// `None` when the packet cannot be bounded so: fewer than eight rays
    /// (a row's last pixels), the rays' origins differ or are not finite, or
    /// along some axis a 1/d is not finite and non-zero, or the directions
    /// differ in sign.
    #[inline(always)]
    pub(super) fn new<L: RayLanes>(rays: &[Ray]) -> Option<Packet> {
        let rays: &[Ray; PACKET] = rays.try_into().ok()?;
        let origin = rays[0].origin;
        let mut same_origin = origin.is_finite();
        let mut direction = [[0.0; PACKET]; 3];
        for (i, ray) in rays.iter().enumerate() {
            let o = ray.origin;
            same_origin &= (o.x == origin.x) & (o.y == origin.y) & (o.z == origin.z);
            direction[0][i] = ray.direction.x;
            direction[1][i] = ray.direction.y;
            direction[2][i] = ray.direction.z;
        }
        if !same_origin {
            return None;
        }
        // Axis by axis, `L::COUNT` rays at a time.
        let mut inverse = [[0.0; PACKET]; 3];
        let mut least = [0.0; 3];
        let mut greatest = [0.0; 3];
        let mut downwards = [false; 3];
        let (zero, infinity) = (L::splat(0.0), L::splat(f64::INFINITY));
        for axis in 0..3 {
            let mut low = infinity;
            let mut high = L::splat(f64::NEG_INFINITY);
            // The rays whose 1/d is finite and positive, finite and negative
            // (a NaN is neither).
            let (mut positive, mut negative) = (0, 0);
            for chunk in (0..PACKET).step_by(L::COUNT) {
                let v = L::splat(1.0).div(L::load(&direction[axis], chunk));
                v.store(&mut inverse[axis], chunk);
                positive |= zero.lt(v).and(v.lt(infinity)).bits() << chunk;
                negative |= zero.sub(infinity).lt(v).and(v.lt(zero)).bits() << chunk;
                low = low.min(v);
                high = high.max(v);
            }
            // One sign along the axis, and no 1/d infinite, zero or NaN.
            if positive != u32::from(ALL) && negative != u32::from(ALL) {
                return None;
            }
            // The least and greatest of the eight (in any order: none is NaN).
            let (low, high) = (low.to_array(), high.to_array());
            least[axis] = low[..L::COUNT].iter().fold(f64::INFINITY, |a, &b| a.min(b));
            greatest[axis] = high[..L::COUNT]
                .iter()
                .fold(f64::NEG_INFINITY, |a, &b| a.max(b));
            downwards[axis] = negative == u32::from(ALL);
        }
        Some(Packet {
            origin: origin.to_array(),
            direction,
            inverse,
            least,
            greatest,
            downwards,
        })
    }

    /// The origin, the least and greatest 1/d per axis, and which way the
    /// rays run along each: what the packet tests of four boxes read.
    #[inline(always)]
    pub(super) fn bounds(&self) -> ([f64; 3], [f64; 3], [f64; 3], [bool; 3]) {
        (self.origin, self.least, self.greatest, self.downwards)
    }

    /// Which rays meet child `lane`'s box of `node` within (t_min, t_max[i]),
    /// each by the arithmetic of its own SSE2 box test (`node::BoxTest`),
    /// done for `L::COUNT` rays per instruction: per axis, (c - o) (1/d) to
    /// the near and far corners, the entry the greater of it and the running
    /// one (`max(t_near, low)`, SSE2's max: `t_near > low ? t_near : low`),
    /// the exit the lesser (`min(t_far, high)`), as `Lanes` in `node` does.
    #[inline(always)]
    fn each_meets<L: RayLanes>(
        &self,
        node: &Node,
        lane: usize,
        t_min: f64,
        t_max: &[f64; PACKET],
    ) -> u8 {
        let mut corners = [(0.0, 0.0); 3];
        for (axis, corners) in corners.iter_mut().enumerate() {
            let down = usize::from(self.downwards[axis]);
            let near = f64::from(node.corners[down][axis][lane]);
            let far = f64::from(node.corners[1 - down][axis][lane]);
            *corners = (near - self.origin[axis], far - self.origin[axis]);
        }
        let mut mask = 0;
        for chunk in (0..PACKET).step_by(L::COUNT) {
            let mut low = L::splat(t_min);
            let mut high = L::load(t_max, chunk);
            for (axis, &(near, far)) in corners.iter().enumerate() {
                // No NaN here: 1/d is finite and non-zero, the corners at
                // worst infinite (an absent child's empty box).
                let inverse = L::load(&self.inverse[axis], chunk);
                low = L::splat(near).mul(inverse).max(low);
                high = L::splat(far).mul(inverse).min(high);
            }
            mask |= high.ge(low).bits() << chunk;
        }
        mask as u8
    }
}

/// A packet prepared for testing a node's four boxes at once.
pub(super) trait PacketBoxTesting {
    /// The lanes the leaves' triangles are tested with, across the rays.
    type Rays: RayLanes + TestQuad;

    fn new(packet: &Packet) -> Self;

    /// Bit i of the mask is set when some ray of the packet may meet child
    /// i's box within (t_min, t_max) (every ray that does is among them),
    /// `entry[i]` at most where any of them enters it.
    fn entries(&self, node: &Node, t_min: f64, t_max: f64) -> (u32, [f64; WIDTH]);
}

/// The packet's box test with SSE2, two boxes per instruction.
pub(super) struct PacketTest {
    origin: [Lanes; 3],
    least: [Lanes; 3],
    greatest: [Lanes; 3],
    downwards: [bool; 3],
}

impl PacketBoxTesting for PacketTest {
    type Rays = Narrow;

    #[inline(always)]
    fn new(packet: &Packet) -> PacketTest {
        let (origin, least, greatest, downwards) = packet.bounds();
        PacketTest {
            origin: origin.map(Lanes::splat),
            least: least.map(Lanes::splat),
            greatest: greatest.map(Lanes::splat),
            downwards,
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
                let down = self.downwards[axis];
                let near = node
                    .corner_lanes(usize::from(down), axis, half)
                    .sub(self.origin[axis]);
                let far = node
                    .corner_lanes(usize::from(!down), axis, half)
                    .sub(self.origin[axis]);
                // The least and the greatest of (c - o) / d over the packet,
                // whatever the sign of c - o.
                let (a, b) = (near.mul(self.least[axis]), near.mul(self.greatest[axis]));
                let (c, d) = (far.mul(self.least[axis]), far.mul(self.greatest[axis]));
                low = a.min(b).max(low);
                high = c.max(d).min(high);
            }
            mask |= low.le_mask(high) << (2 * half);
            let [a, b] = low.to_array();
            entry[2 * half] = a;
            entry[2 * half + 1] = b;
        }
        (mask, entry)
    }
}

/// A packet prepared for the AVX packet test (`packet::PacketTest`'s
/// arithmetic, (c - o) times the least and the greatest 1/d, four boxes per
/// instruction; no fused steps, so the bounds hold for each ray's SSE2 test).
/// Built only where `wide::BoxTest` may be (see its comment).
#[cfg(target_arch = "x86_64")]
#[derive(Clone, Copy, Debug)]
pub(super) struct WidePacketTest {
    origin: [__m256d; 3],
    least: [__m256d; 3],
    greatest: [__m256d; 3],
    downwards: [bool; 3],
}

#[cfg(target_arch = "x86_64")]
impl PacketBoxTesting for WidePacketTest {
    type Rays = super::ray_lanes::Wide;

    #[inline(always)]
    fn new(packet: &Packet) -> WidePacketTest {
        debug_assert!(
            super::wide::available(),
            "the AVX packet test on a CPU without AVX"
        );
        let (origin, least, greatest, downwards) = packet.bounds();
        // SAFETY: as for `wide::BoxTest`: built only inside the functions
        // compiled with AVX, which run only where `wide::available()` said yes.
        unsafe {
            WidePacketTest {
                origin: origin.map(|x| _mm256_set1_pd(x)),
                least: least.map(|x| _mm256_set1_pd(x)),
                greatest: greatest.map(|x| _mm256_set1_pd(x)),
                downwards,
            }
        }
    }

    #[inline(always)]
    fn entries(&self, node: &Node, t_min: f64, t_max: f64) -> (u32, [f64; WIDTH]) {
        let mut entry = [0.0; WIDTH];
        // SAFETY: as above; each load reads one axis's corners of the four
        // children (four f32 side by side), the store the four of `entry`.
        let mask = unsafe {
            let mut low = _mm256_set1_pd(t_min);
            let mut high = _mm256_set1_pd(t_max);
            for axis in 0..3 {
                let down = self.downwards[axis];
                let near = node.corners[usize::from(down)][axis].as_ptr();
                let far = node.corners[usize::from(!down)][axis].as_ptr();
                let near = _mm256_sub_pd(_mm256_cvtps_pd(_mm_loadu_ps(near)), self.origin[axis]);
                let far = _mm256_sub_pd(_mm256_cvtps_pd(_mm_loadu_ps(far)), self.origin[axis]);
                let (least, greatest) = (self.least[axis], self.greatest[axis]);
                let t_near =
                    _mm256_min_pd(_mm256_mul_pd(near, least), _mm256_mul_pd(near, greatest));
                let t_far = _mm256_max_pd(_mm256_mul_pd(far, least), _mm256_mul_pd(far, greatest));
                low = _mm256_max_pd(t_near, low);
                high = _mm256_min_pd(t_far, high);
            }
            _mm256_storeu_pd(entry.as_mut_ptr(), low);
            _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_LE_OQ>(low, high)) as u32
        };
        (mask, entry)
    }
}

impl Accel {
    /// `closest(objects, ray, range, _)` for each ray of `rays` (at most
    /// eight, primary rays of one row), into `found`: the same candidates,
    /// to the bit. Costs are not counted.
    #[inline]
    pub fn closest_each(
        &self,
        objects: &[Object],
        rays: &[Ray],
        range: Interval,
        found: &mut [Option<Candidate>],
    ) {
        #[cfg(target_arch = "x86_64")]
        if super::wide::available() {
            // SAFETY: the CPU has the features `closest_each_wide` is compiled for.
            return unsafe { self.closest_each_wide(objects, rays, range, found) };
        }
        self.closest_each_sse2(objects, rays, range, found)
    }

    /// `closest_each` with SSE2 box tests (and `closest_sse2`'s per-ray
    /// query where the packet cannot be bounded).
    #[inline(never)]
    pub(crate) fn closest_each_sse2(
        &self,
        objects: &[Object],
        rays: &[Ray],
        range: Interval,
        found: &mut [Option<Candidate>],
    ) {
        self.closest_each_with::<super::node::BoxTest, PacketTest>(objects, rays, range, found)
    }

    /// `closest_each` compiled for CPUs with AVX2, FMA and their companions
    /// (`wide::available`), with the AVX packet test (and `closest_wide`'s
    /// per-ray query where the packet cannot be bounded).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx,avx2,fma,bmi1,bmi2,lzcnt,popcnt,sse3,ssse3,sse4.1,sse4.2")]
    unsafe fn closest_each_wide(
        &self,
        objects: &[Object],
        rays: &[Ray],
        range: Interval,
        found: &mut [Option<Candidate>],
    ) {
        self.closest_each_with::<super::wide::BoxTest, WidePacketTest>(objects, rays, range, found)
    }

    #[inline(always)]
    fn closest_each_with<B: BoxTesting, P: PacketBoxTesting>(
        &self,
        objects: &[Object],
        rays: &[Ray],
        range: Interval,
        found: &mut [Option<Candidate>],
    ) {
        assert!(rays.len() <= PACKET && found.len() == rays.len());
        let packet = match Packet::new::<P::Rays>(rays) {
            Some(packet) if range.min >= 0.0 => packet,
            _ => {
                for (ray, found) in rays.iter().zip(found) {
                    *found = self.closest_with::<B>(objects, ray, range, &mut Cost::default());
                }
                return;
            }
        };
        let mut cost = Cost::default();
        let rays: &[Ray; PACKET] = rays.try_into().expect("a bounded packet is whole");
        let mut nearest: [Nearest; PACKET] = std::array::from_fn(|i| Nearest {
            objects,
            ray: &rays[i],
            range,
            best: Candidate {
                object: NONE_YET,
                t: range.max,
            },
        });
        for &object in &self.unbounded {
            for nearest in &mut nearest {
                nearest.test(object, &LeafShape::Other, &mut cost);
            }
        }
        let mut bests = Bests {
            t: std::array::from_fn(|i| nearest[i].best.t),
            object: std::array::from_fn(|i| match nearest[i].best.object {
                NONE_YET => NO_OBJECT,
                object => object as f64,
            }),
        };
        if !self.nodes.is_empty() {
            self.walk_packet::<P>(objects, rays, &packet, range, &mut bests);
        }
        for (i, found) in found.iter_mut().enumerate() {
            *found = candidate(&bests, i);
        }
    }

    /// The packet's walk: nodes met by the packet, nearest (by the packet's
    /// least entry) first; at each leaf, the rays whose own box test meets
    /// it test its objects: each triangle across those rays at once
    /// (`packet_triangles`), any other object ray by ray (`Nearest::test`).
    #[inline(always)]
    fn walk_packet<P: PacketBoxTesting>(
        &self,
        objects: &[Object],
        rays: &[Ray; PACKET],
        packet: &Packet,
        range: Interval,
        bests: &mut Bests,
    ) {
        let t_min = range.min;
        let test = P::new(packet);
        let origin = DVec3::from(packet.origin);
        // The greatest of the rays' bests so far.
        let mut packet_max = greatest(&bests.t);
        // Children waiting, with the packet's entry, and for leaves the rays
        // that meet them.
        let mut stack = ArrayVec::<(Child, f64, u8), { MAX_DEPTH * (WIDTH - 1) }>::new();
        let mut node = &self.nodes[0];
        'walk: loop {
            let (mask, entry) = test.entries(node, t_min, packet_max);
            // The child to visit next, the nearest met (by the packet's
            // entry, ties in child order, as `walk` does); the others wait
            // on the stack, the farthest pushed first.
            let next = match mask {
                0 => None,
                1 | 2 | 4 | 8 => Some(mask.trailing_zeros() as usize),
                _ => {
                    let keys = nearest_first(mask, entry);
                    for &key in keys[1..mask.count_ones() as usize].iter().rev() {
                        let i = (key & 3) as usize;
                        let child = node.child(i);
                        let rays = if child.is_leaf() {
                            packet.each_meets::<P::Rays>(node, i, t_min, &bests.t)
                        } else {
                            ALL
                        };
                        if rays != 0 {
                            stack.push((child, f64::from_bits(key & !3), rays));
                        }
                    }
                    Some((keys[0] & 3) as usize)
                }
            };
            let mut next = next.map(|i| {
                let child = node.child(i);
                let rays = if child.is_leaf() {
                    packet.each_meets::<P::Rays>(node, i, t_min, &bests.t)
                } else {
                    ALL
                };
                (child, rays)
            });
            loop {
                match next {
                    // A leaf none of the rays meets is skipped.
                    Some((child, meeting)) if child.is_leaf() && meeting != 0 => {
                        let first = child.offset as usize;
                        let leaf = &self.objects[first..first + usize::from(child.count)];
                        let mut leaf_rays = LeafRays {
                            origin: &packet.origin,
                            direction: &packet.direction,
                            t_min,
                            rays: meeting,
                            bests: &mut *bests,
                        };
                        for (&object, shape) in leaf.iter().zip(&self.shapes[first..]) {
                            if let LeafShape::Triangle(triangle) = shape {
                                // The plane's v_0 once for the packet's origin.
                                let v_0 = triangle.v_0(origin);
                                test_triangle::<P::Rays>(triangle, object, v_0, &mut leaf_rays);
                                continue;
                            }
                            // A quad met by two rays or more: across them
                            // (for one ray the per-ray test, which stops at
                            // the plane when that is out of range, cost less:
                            // gears' quads, 2 % of its instructions).
                            let quad = quad(shape, &objects[object as usize].shape);
                            if let Some(quad) = quad.filter(|_| meeting & (meeting - 1) != 0) {
                                P::Rays::test_quad(quad, object, &mut leaf_rays);
                                continue;
                            }
                            // Ray by ray, `Nearest::test`'s steps on `bests`:
                            // the range closed at the best t when this
                            // object comes earlier in the file (never
                            // before a hit, when the best's object is -1).
                            let object_f = f64::from(object);
                            let bests = &mut *leaf_rays.bests;
                            let mut left = meeting;
                            while left != 0 {
                                let i = left.trailing_zeros() as usize;
                                left &= left - 1;
                                let best = bests.t[i];
                                let max = if object_f < bests.object[i] {
                                    best.next_up()
                                } else {
                                    best
                                };
                                let range = Interval::new(t_min, max);
                                let hit =
                                    shape.intersect(objects, object as usize, &rays[i], range);
                                if let Some(t) = hit {
                                    bests.t[i] = t;
                                    bests.object[i] = object_f;
                                }
                            }
                        }
                        packet_max = greatest(&bests.t);
                    }
                    Some((child, _)) if !child.is_leaf() => {
                        node = &self.nodes[child.offset as usize];
                        break;
                    }
                    _ => {}
                }
                next = loop {
                    let Some((child, entry, rays)) = stack.pop() else {
                        break 'walk;
                    };
                    if entry <= packet_max {
                        break Some((child, rays));
                    }
                };
            }
        }
    }
}

/// The polygon of four vertices whose record `shape` is, tested through its
/// object (`LeafShape::Other`): a polygon or a patch (whose hit is its
/// polygon's, `Shape::intersect`).
#[inline(always)]
fn quad<'a>(shape: &LeafShape, object: &'a Shape) -> Option<&'a Polygon> {
    let LeafShape::Other = shape else {
        return None;
    };
    let polygon = match object {
        Shape::Polygon(polygon) => polygon,
        Shape::Patch(patch) => &patch.polygon,
        _ => return None,
    };
    (polygon.vertices.len() == 4).then_some(polygon)
}

/// Ray i's nearest hit in `bests`, if it has one.
#[inline(always)]
fn candidate(bests: &Bests, i: usize) -> Option<Candidate> {
    let object = bests.object[i];
    (object != NO_OBJECT).then_some(Candidate {
        object: object as usize,
        t: bests.t[i],
    })
}

/// The greatest of `values` (none is NaN).
#[inline(always)]
fn greatest(values: &[f64; PACKET]) -> f64 {
    let mut pairs = [0.0; PACKET / 2];
    for i in 0..PACKET / 2 {
        let (a, b) = (values[i], values[i + PACKET / 2]);
        pairs[i] = if a > b { a } else { b };
    }
    pairs
        .iter()
        .fold(f64::NEG_INFINITY, |a, &b| if b > a { b } else { a })
}

#[cfg(test)]
mod tests {
    use super::super::{Numbers, brute, node};
    use super::*;
    use raystep_model::math::EPS;
    use raystep_model::shapes::{Plane, Polygon, Shape, Sphere};

    /// A point of the cube [-1, 1]^3.
    fn vector(numbers: &mut Numbers) -> DVec3 {
        DVec3::new(numbers.next(), numbers.next(), numbers.next()) * 2.0 - 1.0
    }

    fn object(shape: Shape) -> Object {
        Object {
            name: "".into(),
            shape,
            material: 0,
        }
    }

    /// Spheres, triangles, quads (tested through their object), some
    /// repeated exactly (ties, decided by file order), and a plane.
    fn scene(numbers: &mut Numbers) -> Vec<Object> {
        let mut objects = Vec::new();
        for i in 0..400 {
            let at = vector(numbers) * 3.0;
            let shape = match i % 4 {
                0 | 1 => Shape::Sphere(Sphere::new(at, 0.05 + 0.3 * numbers.next()).unwrap()),
                2 => {
                    let (a, b) = (vector(numbers) * 0.5, vector(numbers) * 0.5);
                    Shape::Polygon(Polygon::new(vec![at, at + a, at + b]).unwrap())
                }
                _ => {
                    let (a, b) = (vector(numbers) * 0.4, vector(numbers) * 0.4);
                    Shape::Polygon(Polygon::new(vec![at, at + a, at + a + b, at + b]).unwrap())
                }
            };
            objects.push(object(shape));
            if i % 50 == 0 {
                objects.push(objects[objects.len() - 1].clone());
            }
        }
        objects.push(object(Shape::Plane(
            Plane::new(DVec3::new(0.1, 0.2, 1.0), DVec3::new(0.0, 0.0, -3.5)).unwrap(),
        )));
        objects
    }

    /// Up to eight rays: mostly a camera's neighbouring pixels (one origin,
    /// directions a pixel apart), sometimes spread wide (directions of
    /// both signs), with zero components (such packets take the per-ray
    /// query), from two origins, or with the first ray aimed at a
    /// triangle's or quad's vertex or the middle of one of its edges.
    fn packet(numbers: &mut Numbers, objects: &[Object]) -> Vec<Ray> {
        let count = if numbers.next() < 0.8 {
            PACKET
        } else {
            1 + (numbers.next() * PACKET as f64) as usize
        };
        let origin = vector(numbers) * 6.0;
        // Mostly towards the scene's middle, so that most rays hit.
        let mut aim = (vector(numbers) * 2.0 - origin).normalize();
        if numbers.next() < 0.3 {
            let object = (numbers.next() * objects.len() as f64) as usize;
            if let Shape::Polygon(polygon) = &objects[object].shape {
                let v = &polygon.vertices;
                let i = (numbers.next() * v.len() as f64) as usize;
                let j = (i + 1) % v.len();
                let target = if numbers.next() < 0.5 {
                    v[i]
                } else {
                    (v[i] + v[j]) / 2.0
                };
                aim = (target - origin).normalize();
            }
        }
        let step = [1e-3, 1e-2, 0.3][(numbers.next() * 3.0) as usize];
        let across = vector(numbers).cross(aim).normalize() * step;
        let kind = (numbers.next() * 10.0) as u32;
        (0..count)
            .map(|i| {
                let mut direction = (aim + across * i as f64).normalize();
                let mut from = origin;
                match kind {
                    0 => direction[i % 3] = 0.0,
                    1 if i == 3 => from += DVec3::X * 1e-3,
                    _ => {}
                }
                Ray::new(from, direction)
            })
            .collect()
    }

    fn same(a: Option<Candidate>, b: Option<Candidate>) -> bool {
        a.map(|c| (c.object, c.t.to_bits())) == b.map(|c| (c.object, c.t.to_bits()))
    }

    /// Each ray's answer from a packet, by both copies, is the per-ray
    /// query's (the SSE2 `closest_with`, itself tested against brute force
    /// elsewhere) and brute force's, to the bit. Brute force tests every
    /// object in file order: an answer independent of any tree.
    #[test]
    fn each_ray_of_a_packet_gets_its_own_closest_hit_to_the_bit() {
        let mut numbers = Numbers(26);
        let (mut hits, mut rays, mut ties, mut bounded) = (0, 0, 0, 0);
        for round in 0..6 {
            let objects = scene(&mut numbers);
            let accel = Accel::build(&objects);
            for _ in 0..1500 {
                let rays_here = packet(&mut numbers, &objects);
                bounded += usize::from(Packet::new::<Narrow>(&rays_here).is_some());
                let range = if numbers.next() < 0.25 {
                    Interval::new(EPS, 1.0 + 8.0 * numbers.next())
                } else {
                    Interval::in_front()
                };
                let mut sse2 = vec![None; rays_here.len()];
                accel.closest_each_sse2(&objects, &rays_here, range, &mut sse2);
                let mut wide = sse2.clone();
                #[cfg(target_arch = "x86_64")]
                if super::super::wide::available() {
                    // SAFETY: the CPU has the features.
                    unsafe { accel.closest_each_wide(&objects, &rays_here, range, &mut wide) };
                }
                for (i, ray) in rays_here.iter().enumerate() {
                    let mut cost = Cost::default();
                    let one = accel.closest_with::<node::BoxTest>(&objects, ray, range, &mut cost);
                    let plain = brute::closest(&objects, ray, range, &mut cost);
                    assert!(same(one, plain), "round {round}: {ray:?}");
                    assert!(same(sse2[i], one), "SSE2, round {round}: {ray:?}");
                    assert!(same(wide[i], one), "AVX, round {round}: {ray:?}");
                    hits += usize::from(one.is_some());
                    // A copy of the object just before it is at the same t:
                    // the tie goes to the first in the file.
                    ties += usize::from(one.is_some_and(|c| {
                        c.object + 1 < objects.len()
                            && objects[c.object + 1].shape == objects[c.object].shape
                    }));
                }
                rays += rays_here.len();
            }
        }
        // Not vacuous: a good part of the packets take the packet walk (the
        // others, short, spread or from two origins, the per-ray query),
        // most rays hit something, and some hit a tie.
        assert!(bounded > 6 * 1500 / 3, "{bounded} packets bounded");
        assert!(hits * 2 > rays, "{hits} hits of {rays} rays");
        assert!(ties > 20, "{ties} ties");
    }

    #[test]
    fn packets_that_cannot_be_bounded_are_told_apart() {
        let ray = |o: [f64; 3], d: [f64; 3]| Ray::new(DVec3::from(o), DVec3::from(d));
        let fine: Vec<Ray> = (0..PACKET)
            .map(|i| ray([0.0; 3], [1.0, 0.5 - 0.01 * i as f64, -0.5]))
            .collect();
        assert!(Packet::new::<Narrow>(&fine).is_some());
        let with = |i: usize, other: Ray| {
            let mut rays = fine.clone();
            rays[i] = other;
            Packet::new::<Narrow>(&rays).is_none()
        };
        // Signs differ along y.
        assert!(with(3, ray([0.0; 3], [1.0, -0.1, -0.5])));
        // A zero component, either sign; a NaN.
        assert!(with(0, ray([0.0; 3], [1.0, 0.0, -0.5])));
        assert!(with(7, ray([0.0; 3], [1.0, -0.0, -0.5])));
        assert!(with(7, ray([0.0; 3], [1.0, f64::NAN, -0.5])));
        // Two origins.
        assert!(with(5, ray([0.0, 0.0, 1e-9], [1.0, 0.4, -0.6])));
        // Fewer than eight rays (a row's last pixels).
        assert!(Packet::new::<Narrow>(&fine[..PACKET - 1]).is_none());
        assert!(Packet::new::<Narrow>(&[]).is_none());
    }
}
