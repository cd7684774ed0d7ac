//! A leaf's triangle tested against all the rays of a packet at once: the
//! steps of `TriangleTest::hit_t_given` (the plane's t, the range check, the
//! hit point projected, the three edges' crossings) done lane by lane,
//! four rays per instruction with AVX (`Wide`), two with SSE2 (`Narrow`; both in `ray_lanes`).
//!
//! Each lane runs the scalar code's operations in the scalar code's order,
//! with no fused multiply-add (the scalar code has none: Rust never fuses),
//! so each ray's t is the scalar t to the bit and each edge's crossing is
//! decided on the same numbers:
//!
//! - v_d = N.d as glam's `dot`, (n_x d_x + n_y d_y) + n_z d_z;
//! - t = v_0 / v_d, v_0 = -(N.o + D) computed once for the packet's origin;
//! - in range when min < t < max, max as `Nearest::test` sets it (the best t
//!   so far, or the float just above it when this object comes earlier in the
//!   file than the best's, so that a tie goes to the earlier object);
//!   v_d = 0 needs no test of its own: t is then infinite or NaN, never
//!   strictly inside the range;
//! - p = o + t d, projected by dropping the triangle's `dropped` axis;
//! - each vertex less p, then per edge (a, b), in `count_crossings`'s order
//!   (C to A, A to B, B to C): `straddles`, (a_v >= 0) != (b_v >= 0), and
//!   `u_at_axis`, a_u - a_v (b_u - a_u) / (b_v - a_v), > 0. The scalar code
//!   computes u only for an edge that straddles; here it is computed for
//!   every edge and ignored where the edge does not straddle (a division by
//!   zero there gives an infinity or a NaN, and no trap).
//! - inside when an odd number of edges cross: the three crossings xor-ed.
//!
//! So a ray's best changes exactly where `Nearest::test_with` with
//! `hit_t_given` would change it (a test checks, bit for bit, with rays
//! through vertices and along edges, ties, and zero components).

use super::PACKET;
use glam::{DVec2, DVec3};

use super::leaf_shapes::TriangleTest;
use super::ray_lanes::Narrow;
use super::ray_lanes::RayLanes;
#[cfg(target_arch = "x86_64")]
use super::ray_lanes::Wide;
use raystep_model::shapes::Axis;
use raystep_model::shapes::Polygon;

/// Each ray's nearest hit so far, side by side: its t (at first the query's
/// range end) and its object as an f64 (exact: objects are counted by a
/// u32), -1 before any hit.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(32))]
pub(super) struct Bests {
    pub(super) t: [f64; PACKET],
    pub(super) object: [f64; PACKET],
}

/// `Bests::object` of a ray without a hit yet.
pub(super) const NO_OBJECT: f64 = -1.0;

/// A packet at a leaf, as each leaf test reads it and writes it: the rays'
/// shared origin and their directions side by side, the query's t_min,
/// the rays that test the leaf (one bit each), and every ray's best so far.
pub(super) struct LeafRays<'a> {
    pub(super) origin: &'a [f64; 3],
    pub(super) direction: &'a [[f64; PACKET]; 3],
    pub(super) t_min: f64,
    pub(super) rays: u8,
    pub(super) bests: &'a mut Bests,
}

/// `TriangleTest::hit_t_given(v_0, ray, range)` for each ray i of the packet
/// whose bit is set in `leaf.rays`, with the range `Nearest::test_with`
/// gives it (from `t_min` to its best so far, closed there when `object`
/// comes earlier in the file); where it hits, the ray's best becomes
/// (object, t).
///
/// The same steps as `test_polygon` with N = 3, spelt out: written as
/// `test_polygon::<L, 3>`, the same answers cost a fifth more instructions
/// (callgrind, tetra's primary rays at 256 x 256: 69.7 M -> 83.7 M).
#[inline(always)]
pub(super) fn test_triangle<L: RayLanes>(
    triangle: &TriangleTest,
    object: u32,
    v_0: f64,
    leaf: &mut LeafRays,
) {
    let (origin, direction, t_min, rays) = (leaf.origin, leaf.direction, leaf.t_min, leaf.rays);
    let bests = &mut *leaf.bests;
    let normal = triangle.plane.normal;
    // The axes kept by `Axis::project`: (U, V) in x-y-z order.
    let (u, v) = match triangle.dropped {
        Axis::X => (1, 2),
        Axis::Y => (0, 2),
        Axis::Z => (0, 1),
    };
    let object_f = f64::from(object);
    let mut chunk = 0;
    while chunk < PACKET {
        let lanes = (u32::from(rays) >> chunk) & ((1 << L::COUNT) - 1);
        if lanes != 0 {
            let d = [
                L::load(&direction[0], chunk),
                L::load(&direction[1], chunk),
                L::load(&direction[2], chunk),
            ];
            // glam's dot: (x x' + y y') + z z'.
            let v_d = L::splat(normal.x)
                .mul(d[0])
                .add(L::splat(normal.y).mul(d[1]))
                .add(L::splat(normal.z).mul(d[2]));
            let t = L::splat(v_0).div(v_d);
            let best_t = L::load(&bests.t, chunk);
            let best_object = L::load(&bests.object, chunk);
            // `Nearest::test`'s max: object < best.object (never true
            // before a hit, when it is -1) takes the float just above.
            let earlier = L::splat(object_f).lt(best_object);
            let max = L::select(earlier, best_t.next_up_positive(), best_t);
            let in_range = L::splat(t_min).lt(t).and(t.lt(max));
            let mut hits = in_range.bits() & lanes;
            if hits != 0 {
                // p = o + t d (`Ray::at`), the two kept coordinates.
                let p_u = L::splat(origin[u]).add(t.mul(d[u]));
                let p_v = L::splat(origin[v]).add(t.mul(d[v]));
                let corner = |i: usize| {
                    let q = triangle.projected[i];
                    (L::splat(q.x).sub(p_u), L::splat(q.y).sub(p_v))
                };
                let (a, b, c) = (corner(0), corner(1), corner(2));
                let zero = L::splat(0.0);
                let above = (a.1.ge(zero), b.1.ge(zero), c.1.ge(zero));
                // `crosses(a, b)`: straddles and u_at_axis > 0.
                let crosses = |a: (L, L), a_above: L, b: (L, L), b_above: L| {
                    let u_at = a.0.sub(a.1.mul(b.0.sub(a.0)).div(b.1.sub(a.1)));
                    a_above.xor(b_above).and(zero.lt(u_at))
                };
                let inside = crosses(c, above.2, a, above.0)
                    .xor(crosses(a, above.0, b, above.1))
                    .xor(crosses(b, above.1, c, above.2));
                hits &= inside.bits();
                if hits != 0 {
                    let t = t.to_array();
                    while hits != 0 {
                        let i = hits.trailing_zeros() as usize;
                        hits &= hits - 1;
                        bests.t[chunk + i] = t[i];
                        bests.object[chunk + i] = object_f;
                    }
                }
            }
        }
        chunk += L::COUNT;
    }
}

/// `test_triangle` for a polygon of N vertices (`projected`, as
/// `Polygon::projected` gives them) in the plane of normal `plane.0`, which
/// drops axis `plane.1`: `Polygon::solve(ray, range).hit_t()`'s steps, the
/// crossings counted over its N edges in `count_crossings`'s order (from
/// the last vertex to the first, then each to the next). Used for the
/// quads tested through their object (`LeafShape::Other`), whose records
/// hold no vertices.
#[inline(always)]
pub(super) fn test_polygon<L: RayLanes, const N: usize>(
    (normal, dropped): (DVec3, Axis),
    projected: &[DVec2; N],
    object: u32,
    v_0: f64,
    leaf: &mut LeafRays,
) {
    let (origin, direction, t_min, rays) = (leaf.origin, leaf.direction, leaf.t_min, leaf.rays);
    let bests = &mut *leaf.bests;
    // The axes kept by `Axis::project`: (U, V) in x-y-z order.
    let (u, v) = match dropped {
        Axis::X => (1, 2),
        Axis::Y => (0, 2),
        Axis::Z => (0, 1),
    };
    let object_f = f64::from(object);
    let mut chunk = 0;
    while chunk < PACKET {
        let lanes = (u32::from(rays) >> chunk) & ((1 << L::COUNT) - 1);
        if lanes != 0 {
            let d = [
                L::load(&direction[0], chunk),
                L::load(&direction[1], chunk),
                L::load(&direction[2], chunk),
            ];
            // glam's dot: (x x' + y y') + z z'.
            let v_d = L::splat(normal.x)
                .mul(d[0])
                .add(L::splat(normal.y).mul(d[1]))
                .add(L::splat(normal.z).mul(d[2]));
            let t = L::splat(v_0).div(v_d);
            let best_t = L::load(&bests.t, chunk);
            let best_object = L::load(&bests.object, chunk);
            // `Nearest::test`'s max: object < best.object (never true
            // before a hit, when it is -1) takes the float just above.
            let earlier = L::splat(object_f).lt(best_object);
            let max = L::select(earlier, best_t.next_up_positive(), best_t);
            let in_range = L::splat(t_min).lt(t).and(t.lt(max));
            let mut hits = in_range.bits() & lanes;
            if hits != 0 {
                // p = o + t d (`Ray::at`), the two kept coordinates.
                let p_u = L::splat(origin[u]).add(t.mul(d[u]));
                let p_v = L::splat(origin[v]).add(t.mul(d[v]));
                // Each vertex less p, and whether its V is >= 0.
                let zero = L::splat(0.0);
                let corners = projected.map(|q| {
                    let (u, v) = (L::splat(q.x).sub(p_u), L::splat(q.y).sub(p_v));
                    (u, v, v.ge(zero))
                });
                // `crosses(a, b)`: straddles and u_at_axis > 0, over the
                // edges from the last vertex on; inside on an odd count.
                let mut a = corners[N - 1];
                let mut inside = zero;
                for b in corners {
                    let u_at = a.0.sub(a.1.mul(b.0.sub(a.0)).div(b.1.sub(a.1)));
                    inside = inside.xor(a.2.xor(b.2).and(zero.lt(u_at)));
                    a = b;
                }
                hits &= inside.bits();
                if hits != 0 {
                    let t = t.to_array();
                    while hits != 0 {
                        let i = hits.trailing_zeros() as usize;
                        hits &= hits - 1;
                        bests.t[chunk + i] = t[i];
                        bests.object[chunk + i] = object_f;
                    }
                }
            }
        }
        chunk += L::COUNT;
    }
}

/// `test_polygon` for a quad tested through its object (`quad` of
/// `packet`), with its v_0 (`Plane::solve`'s, for the packet's origin) and
/// its vertices projected here, out of line: inlined beside the triangles'
/// test it made the walk 30 % slower on triangle scenes without quads
/// (callgrind, tetra), its code and registers spread over the walk's.
#[inline(never)]
pub(super) fn test_quad_narrow(quad: &Polygon, object: u32, leaf: &mut LeafRays) {
    quad_with::<Narrow>(quad, object, leaf)
}

/// `test_polygon` of a four-vertex `quad` across the rays, out of line and
/// compiled for each form of lanes (`P::Rays` of the packet's walk).
pub(super) trait TestQuad {
    fn test_quad(quad: &Polygon, object: u32, leaf: &mut LeafRays);
}

#[cfg(target_arch = "x86_64")]
impl TestQuad for Wide {
    #[inline(always)]
    fn test_quad(quad: &Polygon, object: u32, leaf: &mut LeafRays) {
        // SAFETY: `Wide` lanes exist only inside the AVX copies of the
        // queries, which run only where `wide::available()` said yes.
        unsafe { test_quad_wide(quad, object, leaf) }
    }
}

impl TestQuad for Narrow {
    #[inline(always)]
    fn test_quad(quad: &Polygon, object: u32, leaf: &mut LeafRays) {
        test_quad_narrow(quad, object, leaf)
    }
}

/// `test_quad_narrow` with AVX: only called where `wide::available()`.
#[cfg(target_arch = "x86_64")]
#[inline(never)]
#[target_feature(enable = "avx,avx2,fma,bmi1,bmi2,lzcnt,popcnt,sse3,ssse3,sse4.1,sse4.2")]
unsafe fn test_quad_wide(quad: &Polygon, object: u32, leaf: &mut LeafRays) {
    quad_with::<Wide>(quad, object, leaf)
}

#[inline(always)]
fn quad_with<L: RayLanes>(quad: &Polygon, object: u32, leaf: &mut LeafRays) {
    let plane = &quad.plane;
    let v_0 = -(plane.normal.dot(DVec3::from_array(*leaf.origin)) + plane.d);
    let projected: [DVec2; 4] = std::array::from_fn(|i| quad.dropped.project(quad.vertices[i]));
    test_polygon::<L, 4>((plane.normal, quad.dropped), &projected, object, v_0, leaf);
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::super::{Candidate, NONE_YET, Nearest, Numbers};
    use super::*;
    use raystep_model::math::{EPS, Interval, Ray};
    use raystep_model::shapes::Polygon;

    /// The scalar answer: `Nearest::test_with` (the tie rule) around
    /// `hit_t_given`, from the best (t, object) given.
    fn scalar(
        hit: &dyn Fn(&Ray, Interval) -> Option<f64>,
        object: u32,
        ray: &Ray,
        t_min: f64,
        best: (f64, f64),
    ) -> (u64, f64) {
        let mut nearest = Nearest {
            objects: &[],
            ray,
            range: Interval::new(t_min, f64::INFINITY),
            best: Candidate {
                object: if best.1 == NO_OBJECT {
                    NONE_YET
                } else {
                    best.1 as usize
                },
                t: best.0,
            },
        };
        nearest.test_with(object, hit);
        let object = match nearest.best.object {
            NONE_YET => NO_OBJECT,
            object => object as f64,
        };
        (nearest.best.t.to_bits(), object)
    }

    /// One packet's test: `object` tested by the rays (all from one
    /// origin) whose bit is set in `active`, from `t_min`, their bests
    /// `start` before.
    struct Case<'a> {
        object: u32,
        rays: &'a [Ray; PACKET],
        t_min: f64,
        active: u8,
        start: &'a Bests,
    }

    /// Runs `test_triangle` with lanes `L` on a packet and checks each ray
    /// against `scalar`; returns how many rays hit and how many were ties
    /// decided by the object order.
    fn check<L: RayLanes>(triangle: &TriangleTest, case: &Case, what: &str) -> (usize, usize) {
        let v_0 = triangle.v_0(case.rays[0].origin);
        let run = |leaf: &mut LeafRays| test_triangle::<L>(triangle, case.object, v_0, leaf);
        let hit = |ray: &Ray, range| triangle.hit_t_given(v_0, ray, range);
        check_with(&run, &hit, case, what)
    }

    /// A lanes' test of a packet at a leaf.
    type RunLanes<'a> = dyn Fn(&mut LeafRays) + 'a;

    /// `check` with the lanes' test run by `run` and the scalar test `hit`.
    fn check_with(
        run: &RunLanes<'_>,
        hit: &dyn Fn(&Ray, Interval) -> Option<f64>,
        case: &Case,
        what: &str,
    ) -> (usize, usize) {
        let Case {
            object,
            rays,
            t_min,
            active,
            start,
        } = *case;
        let origin = rays[0].origin;
        let direction = [0, 1, 2].map(|axis| rays.map(|ray| ray.direction[axis]));
        let mut bests = *start;
        run(&mut LeafRays {
            origin: &origin.to_array(),
            direction: &direction,
            t_min,
            rays: active,
            bests: &mut bests,
        });
        let (mut hits, mut ties) = (0, 0);
        for (i, ray) in rays.iter().enumerate() {
            let before = (start.t[i], start.object[i]);
            let expected = if active & (1 << i) != 0 {
                scalar(hit, object, ray, t_min, before)
            } else {
                // A ray not in the packet's mask keeps its best.
                (before.0.to_bits(), before.1)
            };
            let got = (bests.t[i].to_bits(), bests.object[i]);
            assert_eq!(got, expected, "{what}, ray {i}: {ray:?}, best {before:?}");
            if got != (before.0.to_bits(), before.1) {
                hits += 1;
                ties += usize::from(got.0 == before.0.to_bits());
            }
        }
        (hits, ties)
    }

    /// Both copies, where the CPU has AVX.
    fn check_both(triangle: &TriangleTest, case: &Case) -> (usize, usize) {
        let narrow = check::<Narrow>(triangle, case, "SSE2");
        #[cfg(target_arch = "x86_64")]
        if super::super::wide::available() {
            let wide = check::<Wide>(triangle, case, "AVX");
            assert_eq!(wide, narrow);
        }
        narrow
    }

    fn triangle(points: [[f64; 3]; 3]) -> (Polygon, TriangleTest) {
        let polygon = Polygon::new(points.iter().map(|p| DVec3::from_array(*p)).collect())
            .expect("a triangle");
        let test = TriangleTest::of(&polygon).expect("three vertices");
        (polygon, test)
    }

    /// Rays that land exactly on vertices, on edges and on the line V = 0
    /// through a vertex: triangles in the planes x = 0, y = 0 and z = 0
    /// (each axis dropped once), an origin at height 4 above the plane, and
    /// directions (integer offsets, -4 along the normal) so that t = 1 and
    /// the hit point is exact. Some directions have zero components, two
    /// run parallel to the plane (v_d = 0). Each packet is tested from no
    /// hit, from a farther hit, and from a hit at exactly the same t by
    /// an object just before and just after (the tie rule both ways).
    #[test]
    fn rays_through_vertices_and_edges_and_ties_answer_as_the_scalar_test() {
        let flat = [[0.0, 0.0], [4.0, 0.0], [0.0, 4.0]];
        let mut totals = (0, 0);
        for normal_axis in 0..3 {
            let lift = |[a, b]: [f64; 2], h: f64| {
                let mut p = [0.0; 3];
                let (u, v) = [(1, 2), (0, 2), (0, 1)][normal_axis];
                p[u] = a;
                p[v] = b;
                p[normal_axis] = h;
                p
            };
            let (polygon, test) = triangle(flat.map(|q| lift(q, 0.0)));
            assert_eq!(polygon.dropped as usize, normal_axis);
            for origin in [[0.0, 0.0], [1.0, 1.0], [4.0, 0.0], [2.0, -1.0]] {
                let o = DVec3::from_array(lift(origin, 4.0));
                // Targets: the three vertices, edge points, inside, outside.
                let targets = [
                    [0.0, 0.0],
                    [4.0, 0.0],
                    [0.0, 4.0],
                    [2.0, 0.0],
                    [2.0, 2.0],
                    [0.0, 2.0],
                    [1.0, 1.0],
                    [5.0, 0.0],
                    [-1.0, 0.0],
                    [3.0, 1.0],
                ];
                let mut directions: Vec<DVec3> = targets
                    .iter()
                    .map(|&q| DVec3::from_array(lift(q, 0.0)) - o)
                    .collect();
                // Parallel to the plane: v_d = 0 exactly.
                directions.push(DVec3::from_array(lift([1.0, 0.0], 0.0)));
                directions.push(DVec3::from_array(lift([-1.0, 2.0], 0.0)));
                for shift in 0..directions.len() {
                    let rays: [Ray; PACKET] = std::array::from_fn(|i| {
                        Ray::new(o, directions[(i + shift) % directions.len()])
                    });
                    let exact: [f64; PACKET] = std::array::from_fn(|i| {
                        test.hit_t_given(test.v_0(o), &rays[i], Interval::new(EPS, 1e9))
                            .unwrap_or(1.0)
                    });
                    let starts = [
                        Bests {
                            t: [f64::INFINITY; PACKET],
                            object: [NO_OBJECT; PACKET],
                        },
                        Bests {
                            t: [7.5; PACKET],
                            object: [3.0; PACKET],
                        },
                        // The same t, by an object after (5 wins) and before (4 loses).
                        Bests {
                            t: exact,
                            object: [6.0; PACKET],
                        },
                        Bests {
                            t: exact,
                            object: [4.0; PACKET],
                        },
                    ];
                    for start in &starts {
                        for active in [u8::MAX, 0b1010_0110] {
                            let case = Case {
                                object: 5,
                                rays: &rays,
                                t_min: EPS,
                                active,
                                start,
                            };
                            let (hits, ties) = check_both(&test, &case);
                            totals.0 += hits;
                            totals.1 += ties;
                        }
                    }
                }
            }
        }
        // Not vacuous: many rays hit (vertices and edges among them), and
        // many ties go to the earlier object.
        assert!(totals.0 > 300 && totals.1 > 100, "{totals:?}");
    }

    /// Random triangles against packets of rays aimed at their vertices,
    /// along their edges and around them, directions with zero components,
    /// ranges starting at 0 or EPS, bests before and after the hit, one ulp
    /// either side of it, and ties: every lane as the scalar test, bit for
    /// bit, on both copies.
    #[test]
    fn random_triangles_answer_as_the_scalar_test_to_the_bit() {
        let mut numbers = Numbers(2626);
        let vector = |numbers: &mut Numbers| {
            DVec3::new(numbers.next(), numbers.next(), numbers.next()) * 2.0 - 1.0
        };
        let (mut hits, mut ties, mut misses) = (0, 0, 0);
        for _ in 0..3000 {
            let corners = [
                vector(&mut numbers),
                vector(&mut numbers),
                vector(&mut numbers),
            ];
            let Ok(polygon) = Polygon::new(corners.to_vec()) else {
                continue;
            };
            let test = TriangleTest::of(&polygon).unwrap();
            let o = vector(&mut numbers) * 4.0;
            let rays: [Ray; PACKET] = std::array::from_fn(|i| {
                let (a, b) = (corners[i % 3], corners[(i + 1) % 3]);
                let along =
                    [0.0, 1.0, 0.5, numbers.next(), -0.01, 1.01][(numbers.next() * 6.0) as usize];
                let mut target = a + (b - a) * along;
                if numbers.next() < 0.3 {
                    target += vector(&mut numbers) * 0.3;
                }
                let mut d = target - o;
                if numbers.next() < 0.15 {
                    d[(numbers.next() * 3.0) as usize] = 0.0;
                }
                if numbers.next() < 0.5 {
                    d = d.normalize();
                }
                Ray::new(o, d)
            });
            let t_min = if numbers.next() < 0.5 { 0.0 } else { EPS };
            // The reference itself: `hit_t_given` with the packet's v_0 is
            // `hit_t`, which is `Polygon::solve`'s answer (leaf_shapes' tests).
            for ray in &rays {
                let range = Interval::new(t_min, f64::INFINITY);
                assert_eq!(
                    test.hit_t_given(test.v_0(o), ray, range).map(f64::to_bits),
                    test.hit_t(ray, range).map(f64::to_bits)
                );
            }
            let exact: [f64; PACKET] = std::array::from_fn(|i| {
                test.hit_t_given(test.v_0(o), &rays[i], Interval::new(t_min, f64::INFINITY))
                    .unwrap_or(1.0)
            });
            let object = 10;
            let mut start = Bests {
                t: std::array::from_fn(|i| match (numbers.next() * 6.0) as u32 {
                    0 => f64::INFINITY,
                    1 => exact[i] * 2.0,
                    2 => exact[i] * 0.5,
                    3 => exact[i].next_up(),
                    4 => exact[i].next_down(),
                    _ => exact[i],
                }),
                object: std::array::from_fn(|_| {
                    [NO_OBJECT, 9.0, 11.0][(numbers.next() * 3.0) as usize]
                }),
            };
            // A best with an object is a hit, at a finite t.
            for i in 0..PACKET {
                if start.t[i] == f64::INFINITY {
                    start.object[i] = NO_OBJECT;
                }
            }
            let active = (numbers.next() * 256.0) as u8 | 1;
            let case = Case {
                object,
                rays: &rays,
                t_min,
                active,
                start: &start,
            };
            let (h, t) = check_both(&test, &case);
            hits += h;
            ties += t;
            misses += active.count_ones() as usize - h;
        }
        // Not vacuous: (with this seed) about 1400 hits, 150 of them ties
        // decided by the object order, and 12,000 misses.
        assert!(
            hits > 1000 && ties > 100 && misses > 3000,
            "{hits} {ties} {misses}"
        );
    }

    /// Quads (parallelograms, and kites with a vertex on V = 0 through
    /// another) through the polygon's own test: `test_quad` (so
    /// `test_polygon` with four vertices) against `Polygon::solve`, which the quads tested through
    /// their object use, with rays aimed at vertices, edge midpoints and
    /// around, ties and zero components, on both copies.
    #[test]
    fn quads_answer_as_the_polygon_does_to_the_bit() {
        let mut numbers = Numbers(4);
        let vector = |numbers: &mut Numbers| {
            DVec3::new(numbers.next(), numbers.next(), numbers.next()) * 2.0 - 1.0
        };
        let (mut hits, mut ties, mut misses) = (0, 0, 0);
        for round in 0..3000 {
            let (a, b, c) = (
                vector(&mut numbers),
                vector(&mut numbers),
                vector(&mut numbers),
            );
            let corners = if round % 2 == 0 {
                vec![a, b, b + c - a, c]
            } else {
                // A kite in z = 0.5: (0, -1), (2, 0), (0, 1), (-2, 0) scaled.
                let s = 0.2 + numbers.next();
                [[0.0, -1.0], [2.0, 0.0], [0.0, 1.0], [-2.0, 0.0]]
                    .map(|[x, y]| DVec3::new(x * s, y * s, 0.5))
                    .to_vec()
            };
            let Ok(polygon) = Polygon::new(corners.clone()) else {
                continue;
            };
            let o = if round % 2 == 0 {
                vector(&mut numbers) * 4.0
            } else {
                // On the kite's axis, so that rays along it meet V = 0 exactly.
                DVec3::new(numbers.next() - 0.5, 0.0, 3.0)
            };
            let rays: [Ray; PACKET] = std::array::from_fn(|i| {
                let (a, b) = (corners[i % 4], corners[(i + 1) % 4]);
                let along = [0.0, 1.0, 0.5, numbers.next(), -0.01][(numbers.next() * 5.0) as usize];
                let mut d = a + (b - a) * along - o;
                if numbers.next() < 0.15 {
                    d[(numbers.next() * 3.0) as usize] = 0.0;
                }
                Ray::new(o, d)
            });
            let t_min = EPS;
            let hit = |ray: &Ray, range| polygon.solve(ray, range).hit_t();
            let exact: [f64; PACKET] = std::array::from_fn(|i| {
                hit(&rays[i], Interval::new(t_min, f64::INFINITY)).unwrap_or(1.0)
            });
            let object = 10;
            let mut start = Bests {
                t: std::array::from_fn(|i| match (numbers.next() * 4.0) as u32 {
                    0 => f64::INFINITY,
                    1 => exact[i] * 2.0,
                    2 => exact[i].next_up(),
                    _ => exact[i],
                }),
                object: std::array::from_fn(|_| {
                    [NO_OBJECT, 9.0, 11.0][(numbers.next() * 3.0) as usize]
                }),
            };
            for i in 0..PACKET {
                if start.t[i] == f64::INFINITY {
                    start.object[i] = NO_OBJECT;
                }
            }
            let active = (numbers.next() * 256.0) as u8 | 1;
            // Through `test_quad`, as the walk calls it (v_0 and the
            // projected vertices computed there).
            let narrow = |leaf: &mut LeafRays| Narrow::test_quad(&polygon, object, leaf);
            let case = Case {
                object,
                rays: &rays,
                t_min,
                active,
                start: &start,
            };
            let (h, t) = check_with(&narrow, &hit, &case, "SSE2");
            #[cfg(target_arch = "x86_64")]
            if super::super::wide::available() {
                let wide = |leaf: &mut LeafRays| Wide::test_quad(&polygon, object, leaf);
                let got = check_with(&wide, &hit, &case, "AVX");
                assert_eq!(got, (h, t));
            }
            hits += h;
            ties += t;
            misses += active.count_ones() as usize - h;
        }
        // Not vacuous: many hits, ties and misses (counts printed on failure).
        assert!(
            hits > 1000 && ties > 100 && misses > 1000,
            "{hits} {ties} {misses}"
        );
    }
}
