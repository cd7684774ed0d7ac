//! The box test with AVX and FMA: a node's four boxes against one ray in
//! single instructions, where the SSE2 test (`node::BoxTest`) needs two.
//!
//! Each slab distance is one fused multiply-add, c (1/d) - o (1/d), where the
//! SSE2 test subtracts then multiplies, (c - o) (1/d): on the chain every
//! node visit waits on, that is one step instead of two (teapot and tree
//! 2 to 4 % faster). The two round differently, by a few units in the last
//! place of o / d, that is by about 2^-52 |o| along the ray. Every box is
//! padded by more than that (`bvh::padded`: at least 2^-30 of the scene's
//! largest coordinate, for origins within 2^22 times it, where the SSE2
//! test's own rounding is as large), so no box that holds a hit is missed
//! and the answers are exactly the SSE2 copy's: the same hits, the same
//! images. Only the cost can differ, where a ray grazes a box within
//! rounding or two children's entries tie within it; a test checks both.
//!
//! The queries are compiled a second time for CPUs with AVX2, FMA and their
//! companions (`Accel::closest_wide`, `Accel::crossings_wide`), and that copy
//! runs where the CPU has them. Measured on the SPD scenes (BENCHMARKS.md):
//! 8 to 12 % fewer instructions tracing, 3 to 6 % less time, and the fused
//! step 2 to 4 % more. Setting `RAYSTEP_NO_AVX` forces the SSE2 copy, for
//! comparison.

use std::arch::x86_64::{
    __m256d, _CMP_LE_OQ, _mm_loadu_ps, _mm256_cmp_pd, _mm256_cvtps_pd, _mm256_fmsub_pd,
    _mm256_max_pd, _mm256_min_pd, _mm256_movemask_pd, _mm256_set1_pd, _mm256_storeu_pd,
};
use std::sync::OnceLock;

use super::node::{BoxTesting, Node, WIDTH};
use raystep_model::math::Ray;

/// Whether the queries' wide copies may run: the CPU has every feature
/// they are compiled for (the list in their `target_feature` attributes),
/// and `RAYSTEP_NO_AVX` is not set.
#[inline]
pub(super) fn available() -> bool {
    static AVAILABLE: OnceLock<bool> = OnceLock::new();
    *AVAILABLE.get_or_init(|| {
        std::env::var_os("RAYSTEP_NO_AVX").is_none()
            && is_x86_feature_detected!("avx")
            && is_x86_feature_detected!("avx2")
            && is_x86_feature_detected!("fma")
            && is_x86_feature_detected!("bmi1")
            && is_x86_feature_detected!("bmi2")
            && is_x86_feature_detected!("lzcnt")
            && is_x86_feature_detected!("popcnt")
            && is_x86_feature_detected!("sse3")
            && is_x86_feature_detected!("ssse3")
            && is_x86_feature_detected!("sse4.1")
            && is_x86_feature_detected!("sse4.2")
    })
}

/// A ray prepared for the AVX box test.
///
/// Only built inside functions compiled with AVX enabled (the queries' wide
/// copies), which run only where `available()` said yes: the `unsafe` blocks
/// below rely on that, and on nothing else (every pointer read or written
/// is into an array of four f64).
#[derive(Clone, Copy, Debug)]
pub(super) struct BoxTest {
    /// Per axis, 1/d as the slabs use it (see `slab_factor`), and the
    /// origin times it.
    factor: [__m256d; 3],
    origin_times_factor: [__m256d; 3],
    /// As in `node::BoxTest`: per axis, whether the ray meets a box's
    /// greatest corner first.
    downwards: [bool; 3],
}

/// Beyond this, 1/d is taken as this, with its sign.
const LARGEST_FACTOR: f64 = f64::from_bits(0x7830_0000_0000_0000); // 2^900

/// The factor of an axis's slab distances, 1/d, kept finite: a fused
/// c inf - o inf is NaN where (c - o) inf is infinite. With 2^900 instead,
/// the slab of an axis the ray runs along (d = 0) is at distances of at
/// least 2^100 wherever the SSE2 test's are infinite, for every box padded
/// by more than 2^-800 (`bvh::padded` pads every box of a scene larger
/// than 2^-770 so): the same answers, as the box's other slabs end sooner.
/// A ray along one of the box's faces (c = o, where the SSE2 test's 0 inf
/// is NaN and keeps the bound) gets 0 instead, and may miss the box: the
/// padding keeps every hit off its faces. The origin's product is finite
/// for every origin within 2^120 of zero; beyond, it is NaN and the slab
/// is ignored, which only costs boxes.
#[inline(always)]
fn slab_factor(inverse: f64, origin: f64) -> (f64, f64) {
    let factor = if inverse.abs() > LARGEST_FACTOR {
        LARGEST_FACTOR.copysign(inverse)
    } else {
        inverse
    };
    let product = origin * factor;
    let product = if product.is_finite() {
        product
    } else {
        f64::NAN
    };
    (factor, product)
}

impl BoxTesting for BoxTest {
    #[inline(always)]
    fn new(ray: &Ray) -> BoxTest {
        debug_assert!(available(), "the AVX box test on a CPU without AVX");
        let (o, d) = (ray.origin, ray.direction);
        let inverse = [1.0 / d.x, 1.0 / d.y, 1.0 / d.z];
        let slabs = [
            slab_factor(inverse[0], o.x),
            slab_factor(inverse[1], o.y),
            slab_factor(inverse[2], o.z),
        ];
        // SAFETY: see the type's comment.
        unsafe {
            BoxTest {
                factor: slabs.map(|(f, _)| _mm256_set1_pd(f)),
                origin_times_factor: slabs.map(|(_, p)| _mm256_set1_pd(p)),
                // 1 / -0 = -inf: a ray with a -0 component counts as running downwards.
                downwards: inverse.map(f64::is_sign_negative),
            }
        }
    }

    #[inline(always)]
    fn entries(&self, node: &Node, t_min: f64, t_max: f64) -> (u32, [f64; WIDTH]) {
        let mut entry = [0.0; WIDTH];
        // SAFETY: see the type's comment. Each load reads one axis's corners
        // of the four children (four f32 side by side), widened exactly to
        // f64; the store writes the four of `entry`.
        let mask = unsafe {
            let mut low = _mm256_set1_pd(t_min);
            let mut high = _mm256_set1_pd(t_max);
            for axis in 0..3 {
                let downwards = self.downwards[axis];
                let near = _mm256_cvtps_pd(_mm_loadu_ps(
                    node.corners[usize::from(downwards)][axis].as_ptr(),
                ));
                let far = _mm256_cvtps_pd(_mm_loadu_ps(
                    node.corners[usize::from(!downwards)][axis].as_ptr(),
                ));
                let (factor, origin) = (self.factor[axis], self.origin_times_factor[axis]);
                let t_near = _mm256_fmsub_pd(near, factor, origin);
                let t_far = _mm256_fmsub_pd(far, factor, origin);
                // A NaN (only where `slab_factor` gave up on the origin)
                // keeps the bound: the second operand.
                low = _mm256_max_pd(t_near, low);
                high = _mm256_min_pd(t_far, high);
            }
            _mm256_storeu_pd(entry.as_mut_ptr(), low);
            _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_LE_OQ>(low, high)) as u32
        };
        (mask, entry)
    }
}

#[cfg(test)]
mod tests {
    use std::ops::ControlFlow;

    use glam::DVec3;

    use super::super::node::{self, Child};
    use super::super::{Accel, Cost, Numbers};
    use super::*;
    use raystep_model::math::{EPS, Interval};
    use raystep_model::object::Object;
    use raystep_model::shapes::{Aabb, Polygon, Shape, Sphere};

    #[target_feature(enable = "avx,fma")]
    fn wide_entries(ray: &Ray, node: &Node, t_min: f64, t_max: f64) -> (u32, [f64; WIDTH]) {
        BoxTest::new(ray).entries(node, t_min, t_max)
    }

    impl Numbers {
        /// Mostly in [-2, 2], sometimes exactly 0, -0, 1 or -1 (axis-parallel
        /// rays, rays along faces, origins on faces).
        fn coordinate(&mut self) -> f64 {
            match (self.next() * 12.0) as u32 {
                0 => 0.0,
                1 => -0.0,
                2 => 1.0,
                3 => -1.0,
                _ => self.next() * 4.0 - 2.0,
            }
        }

        fn vector(&mut self) -> DVec3 {
            DVec3::new(self.coordinate(), self.coordinate(), self.coordinate())
        }
    }

    #[test]
    fn the_wide_test_agrees_with_the_sse2_test_within_rounding() {
        if !available() {
            eprintln!("skipped: this CPU has no AVX2 and FMA");
            return;
        }
        let mut numbers = Numbers(7);
        let leaf = Child {
            offset: 0,
            count: 1,
        };
        // Far larger than the rounding of the nodes' f32 corners (one f32
        // step, 2^-23 of coordinates within 4: 5e-7) and of either test's
        // arithmetic (2^-52 of them), far smaller than the boxes.
        let margin = 1e-6;
        let (mut met, mut tested, mut same) = (0, 0, 0);
        for _ in 0..20_000 {
            // Boxes with corners on the same grid as the rays, some flat,
            // some absent (empty), in nodes of one to four children.
            let arity = 1 + (numbers.next() * 4.0) as usize;
            let boxes: Vec<Aabb> = (0..arity)
                .map(|_| {
                    let (a, b) = (numbers.vector(), numbers.vector());
                    Aabb::new(a.min(b), a.max(b))
                })
                .collect();
            let grown: Vec<Aabb> = boxes
                .iter()
                .map(|b| Aabb::new(b.min - margin, b.max + margin))
                .collect();
            let shrunk: Vec<Aabb> = boxes
                .iter()
                .map(|b| Aabb::new(b.min + margin, b.max - margin))
                .collect();
            let ray = Ray::new(numbers.vector(), numbers.vector());
            let (t_min, t_max) = (
                1e-4,
                [1.0, 3.0, f64::INFINITY][(numbers.next() * 3.0) as usize],
            );
            let sse2 = |boxes: &[Aabb]| {
                let node = Node::new(boxes, &vec![leaf; arity]);
                <node::BoxTest as BoxTesting>::new(&ray).entries(&node, t_min, t_max)
            };
            let node = Node::new(&boxes, &vec![leaf; arity]);
            // SAFETY: `available()` said the CPU has the features.
            let wide = unsafe { wide_entries(&ray, &node, t_min, t_max) };
            let exact = sse2(&boxes);
            // Every box the SSE2 test meets even shrunk, the wide test
            // meets; every box it misses even grown, the wide test misses.
            // (Met at t = inf does not count: a ray without direction
            // "meets" such boxes, where the wide test's distances are finite.)
            let inner = sse2(&shrunk);
            let surely_met = (0..WIDTH)
                .filter(|&i| inner.0 & 1 << i != 0 && inner.1[i] < f64::INFINITY)
                .fold(0, |m, i| m | 1 << i);
            let surely_missed = !sse2(&grown).0 & 0b1111;
            assert_eq!(wide.0 & surely_met, surely_met, "{ray:?} {boxes:?}");
            assert_eq!(wide.0 & surely_missed, 0, "{ray:?} {boxes:?}");
            for i in 0..arity {
                if wide.0 & exact.0 & 1 << i != 0 {
                    let (a, b) = (exact.1[i], wide.1[i]);
                    assert!(
                        (a - b).abs() <= 1e-12 * (1.0 + a.abs()),
                        "{ray:?} {boxes:?}"
                    );
                }
            }
            met += exact.0.count_ones();
            tested += arity as u32;
            same += u32::from(exact.0 == wide.0);
        }
        // Not a vacuous comparison: thousands of boxes met, and more missed;
        // and the masks differ only on the grid's grazing cases.
        assert!(met > 2_000 && tested - met > 2_000, "{met} of {tested}");
        assert!(same > 19_000, "{same} of 20000 nodes answered alike");
    }

    #[test]
    fn both_copies_of_the_queries_answer_alike_at_the_same_cost() {
        if !available() {
            eprintln!("skipped: this CPU has no AVX2 and FMA");
            return;
        }
        let mut numbers = Numbers(11);
        let objects: Vec<Object> = (0..300)
            .map(|i| {
                let at = numbers.vector() * 3.0;
                let shape = if i % 2 == 0 {
                    Shape::Sphere(Sphere::new(at, 0.05 + 0.3 * numbers.next()).unwrap())
                } else {
                    let mut corner = || DVec3::new(numbers.next(), numbers.next(), numbers.next());
                    let (a, b) = (corner(), corner());
                    Shape::Polygon(Polygon::new(vec![at, at + a, at + b]).unwrap())
                };
                Object {
                    name: "".into(),
                    shape,
                    material: 0,
                }
            })
            .collect();
        let accel = Accel::build(&objects);
        let (mut hits, mut crossed) = (0, 0);
        for _ in 0..3000 {
            let ray = Ray::new(numbers.vector() * 4.0, numbers.vector());
            let range = Interval::new(EPS, 2.0 + 6.0 * numbers.next());
            let (mut cost_sse2, mut cost_wide) = (Cost::default(), Cost::default());
            let sse2 = accel.closest_with::<node::BoxTest>(&objects, &ray, range, &mut cost_sse2);
            // `closest` runs the wide copy: `available()` said yes.
            let wide = accel.closest(&objects, &ray, range, &mut cost_wide);
            assert_eq!(sse2, wide, "{ray:?}");
            // The costs could differ only for a ray grazing a box within
            // rounding; none of these random rays does.
            assert_eq!(cost_sse2, cost_wide, "{ray:?}");
            hits += usize::from(wide.is_some());
            let crossings = |through_wide: bool| {
                let (mut seen, mut cost) = (Vec::new(), Cost::default());
                let visit = |object, t: f64| {
                    seen.push((object, t.to_bits()));
                    ControlFlow::Continue(())
                };
                if through_wide {
                    accel.crossings(&objects, &ray, range, &mut cost, visit);
                } else {
                    accel.crossings_with::<node::BoxTest>(&objects, &ray, range, &mut cost, visit);
                }
                (seen, cost)
            };
            let (sse2, wide) = (crossings(false), crossings(true));
            assert_eq!(sse2, wide, "{ray:?}");
            crossed += wide.0.len();
        }
        assert!(
            hits > 300 && crossed > 300,
            "{hits} hits, {crossed} crossings"
        );
    }
}
