//! A packet's rays side by side in SIMD lanes: the few f64 operations the
//! packet's leaf tests (`packet_triangles`) and its per-ray box tests
//! (`Packet::each_meets`) run on them, as a trait with two forms: four lanes
//! of AVX (`Wide`, in the queries' AVX copies) and two of SSE2 (`Narrow`,
//! everywhere else; plain arrays where there is no SSE2). Each operation is
//! the scalar one, lane by lane, with no fused steps, so a lane's numbers
//! are the scalar code's bits.

use super::PACKET;

/// A few f64 lanes and the operations the test needs; comparisons give
/// lanes of all ones or all zeros.
pub(super) trait RayLanes: Copy {
    /// Lanes per value.
    const COUNT: usize;
    /// Reads `COUNT` values from `from[at..]`.
    fn load(from: &[f64; PACKET], at: usize) -> Self;
    fn splat(x: f64) -> Self;
    fn add(self, other: Self) -> Self;
    fn sub(self, other: Self) -> Self;
    fn mul(self, other: Self) -> Self;
    fn div(self, other: Self) -> Self;
    /// SSE2's min and max: `self < other ? self : other` and
    /// `self > other ? self : other` (the second on a tie or a NaN).
    fn min(self, other: Self) -> Self;
    fn max(self, other: Self) -> Self;
    /// self < other (false where either is NaN).
    fn lt(self, other: Self) -> Self;
    /// self >= other (false where either is NaN).
    fn ge(self, other: Self) -> Self;
    fn and(self, other: Self) -> Self;
    fn xor(self, other: Self) -> Self;
    /// Where `mask` is set, `yes`, else `no`.
    fn select(mask: Self, yes: Self, no: Self) -> Self;
    /// The next float up of each lane, for a positive finite one (a best
    /// with an object is a hit, at a finite t > t_min >= 0): its bits plus one.
    fn next_up_positive(self) -> Self;
    /// Bit i set where lane i of the mask is set.
    fn bits(self) -> u32;
    fn to_array(self) -> [f64; 4];
    /// Writes the lanes to `to[at..]`.
    fn store(self, to: &mut [f64; PACKET], at: usize);
}

/// Four lanes of AVX. Its operations run only inside the functions compiled
/// with AVX (`Accel::closest_each_wide`), which run only where
/// `wide::available()` said yes: the `unsafe` blocks rely on that, and on
/// each load reading four f64 inside an array of eight (`at` is 0 or 4).
#[cfg(target_arch = "x86_64")]
#[derive(Clone, Copy, Debug)]
pub(super) struct Wide(std::arch::x86_64::__m256d);

#[cfg(target_arch = "x86_64")]
impl RayLanes for Wide {
    const COUNT: usize = 4;

    #[inline(always)]
    fn load(from: &[f64; PACKET], at: usize) -> Wide {
        use std::arch::x86_64::_mm256_loadu_pd;
        assert!(at + 4 <= PACKET);
        // SAFETY: see the type's comment; four values from `at` are in `from`.
        Wide(unsafe { _mm256_loadu_pd(from.as_ptr().add(at)) })
    }

    #[inline(always)]
    fn splat(x: f64) -> Wide {
        use std::arch::x86_64::_mm256_set1_pd;
        // SAFETY: see the type's comment.
        Wide(unsafe { _mm256_set1_pd(x) })
    }

    #[inline(always)]
    fn add(self, other: Wide) -> Wide {
        use std::arch::x86_64::_mm256_add_pd;
        // SAFETY: see the type's comment.
        Wide(unsafe { _mm256_add_pd(self.0, other.0) })
    }

    #[inline(always)]
    fn sub(self, other: Wide) -> Wide {
        use std::arch::x86_64::_mm256_sub_pd;
        // SAFETY: see the type's comment.
        Wide(unsafe { _mm256_sub_pd(self.0, other.0) })
    }

    #[inline(always)]
    fn mul(self, other: Wide) -> Wide {
        use std::arch::x86_64::_mm256_mul_pd;
        // SAFETY: see the type's comment.
        Wide(unsafe { _mm256_mul_pd(self.0, other.0) })
    }

    #[inline(always)]
    fn div(self, other: Wide) -> Wide {
        use std::arch::x86_64::_mm256_div_pd;
        // SAFETY: see the type's comment.
        Wide(unsafe { _mm256_div_pd(self.0, other.0) })
    }

    #[inline(always)]
    fn min(self, other: Wide) -> Wide {
        use std::arch::x86_64::_mm256_min_pd;
        // SAFETY: see the type's comment.
        Wide(unsafe { _mm256_min_pd(self.0, other.0) })
    }

    #[inline(always)]
    fn max(self, other: Wide) -> Wide {
        use std::arch::x86_64::_mm256_max_pd;
        // SAFETY: see the type's comment.
        Wide(unsafe { _mm256_max_pd(self.0, other.0) })
    }

    #[inline(always)]
    fn lt(self, other: Wide) -> Wide {
        use std::arch::x86_64::{_CMP_LT_OQ, _mm256_cmp_pd};
        // SAFETY: see the type's comment.
        Wide(unsafe { _mm256_cmp_pd::<_CMP_LT_OQ>(self.0, other.0) })
    }

    #[inline(always)]
    fn ge(self, other: Wide) -> Wide {
        use std::arch::x86_64::{_CMP_GE_OQ, _mm256_cmp_pd};
        // SAFETY: see the type's comment.
        Wide(unsafe { _mm256_cmp_pd::<_CMP_GE_OQ>(self.0, other.0) })
    }

    #[inline(always)]
    fn and(self, other: Wide) -> Wide {
        use std::arch::x86_64::_mm256_and_pd;
        // SAFETY: see the type's comment.
        Wide(unsafe { _mm256_and_pd(self.0, other.0) })
    }

    #[inline(always)]
    fn xor(self, other: Wide) -> Wide {
        use std::arch::x86_64::_mm256_xor_pd;
        // SAFETY: see the type's comment.
        Wide(unsafe { _mm256_xor_pd(self.0, other.0) })
    }

    #[inline(always)]
    fn select(mask: Wide, yes: Wide, no: Wide) -> Wide {
        use std::arch::x86_64::_mm256_blendv_pd;
        // SAFETY: see the type's comment.
        Wide(unsafe { _mm256_blendv_pd(no.0, yes.0, mask.0) })
    }

    #[inline(always)]
    fn next_up_positive(self) -> Wide {
        use std::arch::x86_64::{
            _mm256_add_epi64, _mm256_castpd_si256, _mm256_castsi256_pd, _mm256_set1_epi64x,
        };
        // SAFETY: see the type's comment (AVX2 is among its features).
        Wide(unsafe {
            _mm256_castsi256_pd(_mm256_add_epi64(
                _mm256_castpd_si256(self.0),
                _mm256_set1_epi64x(1),
            ))
        })
    }

    #[inline(always)]
    fn bits(self) -> u32 {
        use std::arch::x86_64::_mm256_movemask_pd;
        // SAFETY: see the type's comment.
        unsafe { _mm256_movemask_pd(self.0) as u32 }
    }

    #[inline(always)]
    fn to_array(self) -> [f64; 4] {
        use std::arch::x86_64::_mm256_storeu_pd;
        let mut out = [0.0; 4];
        // SAFETY: see the type's comment; the store writes the four of `out`.
        unsafe { _mm256_storeu_pd(out.as_mut_ptr(), self.0) };
        out
    }

    #[inline(always)]
    fn store(self, to: &mut [f64; PACKET], at: usize) {
        use std::arch::x86_64::_mm256_storeu_pd;
        assert!(at + 4 <= PACKET);
        // SAFETY: see the type's comment; four values from `at` are in `to`.
        unsafe { _mm256_storeu_pd(to.as_mut_ptr().add(at), self.0) };
    }
}

/// Two lanes of SSE2, which every x86-64 has.
#[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
#[derive(Clone, Copy, Debug)]
pub(super) struct Narrow(std::arch::x86_64::__m128d);

// SAFETY, for every `unsafe` block of `Narrow`: the intrinsics need only
// SSE2, which the cfg guarantees; each load reads two f64 inside an array
// of eight (`at` is at most 6, asserted).
#[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
impl RayLanes for Narrow {
    const COUNT: usize = 2;

    #[inline(always)]
    fn load(from: &[f64; PACKET], at: usize) -> Narrow {
        use std::arch::x86_64::_mm_loadu_pd;
        assert!(at + 2 <= PACKET);
        Narrow(unsafe { _mm_loadu_pd(from.as_ptr().add(at)) })
    }

    #[inline(always)]
    fn splat(x: f64) -> Narrow {
        use std::arch::x86_64::_mm_set1_pd;
        Narrow(unsafe { _mm_set1_pd(x) })
    }

    #[inline(always)]
    fn add(self, other: Narrow) -> Narrow {
        use std::arch::x86_64::_mm_add_pd;
        Narrow(unsafe { _mm_add_pd(self.0, other.0) })
    }

    #[inline(always)]
    fn sub(self, other: Narrow) -> Narrow {
        use std::arch::x86_64::_mm_sub_pd;
        Narrow(unsafe { _mm_sub_pd(self.0, other.0) })
    }

    #[inline(always)]
    fn mul(self, other: Narrow) -> Narrow {
        use std::arch::x86_64::_mm_mul_pd;
        Narrow(unsafe { _mm_mul_pd(self.0, other.0) })
    }

    #[inline(always)]
    fn div(self, other: Narrow) -> Narrow {
        use std::arch::x86_64::_mm_div_pd;
        Narrow(unsafe { _mm_div_pd(self.0, other.0) })
    }

    #[inline(always)]
    fn min(self, other: Narrow) -> Narrow {
        use std::arch::x86_64::_mm_min_pd;
        Narrow(unsafe { _mm_min_pd(self.0, other.0) })
    }

    #[inline(always)]
    fn max(self, other: Narrow) -> Narrow {
        use std::arch::x86_64::_mm_max_pd;
        Narrow(unsafe { _mm_max_pd(self.0, other.0) })
    }

    #[inline(always)]
    fn lt(self, other: Narrow) -> Narrow {
        use std::arch::x86_64::_mm_cmplt_pd;
        Narrow(unsafe { _mm_cmplt_pd(self.0, other.0) })
    }

    #[inline(always)]
    fn ge(self, other: Narrow) -> Narrow {
        use std::arch::x86_64::_mm_cmpge_pd;
        Narrow(unsafe { _mm_cmpge_pd(self.0, other.0) })
    }

    #[inline(always)]
    fn and(self, other: Narrow) -> Narrow {
        use std::arch::x86_64::_mm_and_pd;
        Narrow(unsafe { _mm_and_pd(self.0, other.0) })
    }

    #[inline(always)]
    fn xor(self, other: Narrow) -> Narrow {
        use std::arch::x86_64::_mm_xor_pd;
        Narrow(unsafe { _mm_xor_pd(self.0, other.0) })
    }

    #[inline(always)]
    fn select(mask: Narrow, yes: Narrow, no: Narrow) -> Narrow {
        use std::arch::x86_64::{_mm_and_pd, _mm_andnot_pd, _mm_or_pd};
        Narrow(unsafe { _mm_or_pd(_mm_and_pd(mask.0, yes.0), _mm_andnot_pd(mask.0, no.0)) })
    }

    #[inline(always)]
    fn next_up_positive(self) -> Narrow {
        use std::arch::x86_64::{
            _mm_add_epi64, _mm_castpd_si128, _mm_castsi128_pd, _mm_set1_epi64x,
        };
        Narrow(unsafe {
            _mm_castsi128_pd(_mm_add_epi64(_mm_castpd_si128(self.0), _mm_set1_epi64x(1)))
        })
    }

    #[inline(always)]
    fn bits(self) -> u32 {
        use std::arch::x86_64::_mm_movemask_pd;
        unsafe { _mm_movemask_pd(self.0) as u32 }
    }

    #[inline(always)]
    fn to_array(self) -> [f64; 4] {
        use std::arch::x86_64::_mm_storeu_pd;
        let mut out = [0.0; 4];
        // The store writes the first two of `out`.
        unsafe { _mm_storeu_pd(out.as_mut_ptr(), self.0) };
        out
    }

    #[inline(always)]
    fn store(self, to: &mut [f64; PACKET], at: usize) {
        use std::arch::x86_64::_mm_storeu_pd;
        assert!(at + 2 <= PACKET);
        unsafe { _mm_storeu_pd(to.as_mut_ptr().add(at), self.0) };
    }
}

/// Two plain lanes, where SSE2 is not there: the same operations on arrays.
#[cfg(not(all(target_arch = "x86_64", target_feature = "sse2")))]
#[derive(Clone, Copy, Debug)]
pub(super) struct Narrow([f64; 2]);

#[cfg(not(all(target_arch = "x86_64", target_feature = "sse2")))]
impl Narrow {
    fn each(self, other: Narrow, f: impl Fn(f64, f64) -> f64) -> Narrow {
        Narrow([f(self.0[0], other.0[0]), f(self.0[1], other.0[1])])
    }

    fn mask(set: bool) -> f64 {
        f64::from_bits(if set { u64::MAX } else { 0 })
    }
}

#[cfg(not(all(target_arch = "x86_64", target_feature = "sse2")))]
impl RayLanes for Narrow {
    const COUNT: usize = 2;

    fn load(from: &[f64; PACKET], at: usize) -> Narrow {
        Narrow([from[at], from[at + 1]])
    }

    fn splat(x: f64) -> Narrow {
        Narrow([x, x])
    }

    fn add(self, other: Narrow) -> Narrow {
        self.each(other, |a, b| a + b)
    }

    fn sub(self, other: Narrow) -> Narrow {
        self.each(other, |a, b| a - b)
    }

    fn mul(self, other: Narrow) -> Narrow {
        self.each(other, |a, b| a * b)
    }

    fn div(self, other: Narrow) -> Narrow {
        self.each(other, |a, b| a / b)
    }

    fn min(self, other: Narrow) -> Narrow {
        self.each(other, |a, b| if a < b { a } else { b })
    }

    fn max(self, other: Narrow) -> Narrow {
        self.each(other, |a, b| if a > b { a } else { b })
    }

    fn lt(self, other: Narrow) -> Narrow {
        self.each(other, |a, b| Narrow::mask(a < b))
    }

    fn ge(self, other: Narrow) -> Narrow {
        self.each(other, |a, b| Narrow::mask(a >= b))
    }

    fn and(self, other: Narrow) -> Narrow {
        self.each(other, |a, b| f64::from_bits(a.to_bits() & b.to_bits()))
    }

    fn xor(self, other: Narrow) -> Narrow {
        self.each(other, |a, b| f64::from_bits(a.to_bits() ^ b.to_bits()))
    }

    fn select(mask: Narrow, yes: Narrow, no: Narrow) -> Narrow {
        let pick = |i: usize| {
            if mask.0[i].to_bits() != 0 {
                yes.0[i]
            } else {
                no.0[i]
            }
        };
        Narrow([pick(0), pick(1)])
    }

    fn next_up_positive(self) -> Narrow {
        Narrow(self.0.map(|x| f64::from_bits(x.to_bits() + 1)))
    }

    fn bits(self) -> u32 {
        u32::from(self.0[0].to_bits() >> 63 != 0) | u32::from(self.0[1].to_bits() >> 63 != 0) << 1
    }

    fn to_array(self) -> [f64; 4] {
        [self.0[0], self.0[1], 0.0, 0.0]
    }

    fn store(self, to: &mut [f64; PACKET], at: usize) {
        to[at..at + 2].copy_from_slice(&self.0);
    }
}
