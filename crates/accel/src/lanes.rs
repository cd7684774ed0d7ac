//! Two f64 values worked on together: the two child boxes of a node tested
//! against one ray in the same instructions. SSE2, which every x86-64 has,
//! on x86-64; plain arrays with the same results elsewhere.
//!
//! `max` and `min` follow SSE2: when the values are unordered (a NaN) or
//! equal, the answer is the second operand. The slab test relies on it: a NaN
//! distance, from a ray running along a box face, leaves the running bound.
//! (The `wide` crate's `max` gives the same answers with extra instructions
//! per call, and its `fast_max` leaves NaNs unspecified, hence these few lines.)

// SAFETY, for every `unsafe` block below: the intrinsics only need SSE2,
// which the cfg guarantees is enabled for the whole build (every x86-64 CPU
// has it), and none of them touches memory through a pointer.
#[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
mod imp {
    use std::arch::x86_64::{
        __m128d, _mm_castpd_ps, _mm_cmple_pd, _mm_cvtps_pd, _mm_cvtsd_f64, _mm_load_sd, _mm_max_pd,
        _mm_min_pd, _mm_movemask_pd, _mm_mul_pd, _mm_set1_pd, _mm_sub_pd, _mm_unpackhi_pd,
    };

    #[derive(Clone, Copy, Debug)]
    #[repr(transparent)]
    pub(crate) struct Lanes(__m128d);

    impl Lanes {
        #[cfg(test)]
        pub(crate) fn new([a, b]: [f64; 2]) -> Lanes {
            Lanes(unsafe { std::arch::x86_64::_mm_set_pd(b, a) })
        }

        #[inline]
        pub(crate) fn splat(x: f64) -> Lanes {
            Lanes(unsafe { _mm_set1_pd(x) })
        }

        /// Two f32 side by side, widened (exactly) to f64.
        #[inline]
        pub(crate) fn widen(pair: &[f32; 2]) -> Lanes {
            // SAFETY (beyond the module's): the load reads the 8 bytes of `pair`.
            Lanes(unsafe {
                _mm_cvtps_pd(_mm_castpd_ps(_mm_load_sd(
                    (pair as *const [f32; 2]).cast::<f64>(),
                )))
            })
        }

        #[inline]
        pub(crate) fn to_array(self) -> [f64; 2] {
            unsafe {
                [
                    _mm_cvtsd_f64(self.0),
                    _mm_cvtsd_f64(_mm_unpackhi_pd(self.0, self.0)),
                ]
            }
        }

        #[inline]
        pub(crate) fn sub(self, other: Lanes) -> Lanes {
            Lanes(unsafe { _mm_sub_pd(self.0, other.0) })
        }

        #[inline]
        pub(crate) fn mul(self, other: Lanes) -> Lanes {
            Lanes(unsafe { _mm_mul_pd(self.0, other.0) })
        }

        #[inline]
        pub(crate) fn max(self, other: Lanes) -> Lanes {
            Lanes(unsafe { _mm_max_pd(self.0, other.0) })
        }

        #[inline]
        pub(crate) fn min(self, other: Lanes) -> Lanes {
            Lanes(unsafe { _mm_min_pd(self.0, other.0) })
        }

        /// Bit i set where lane i of self <= lane i of other.
        #[inline]
        pub(crate) fn le_mask(self, other: Lanes) -> u32 {
            unsafe { _mm_movemask_pd(_mm_cmple_pd(self.0, other.0)) as u32 }
        }
    }
}

#[cfg(not(all(target_arch = "x86_64", target_feature = "sse2")))]
mod imp {
    #[derive(Clone, Copy, Debug)]
    #[repr(C, align(16))]
    pub(crate) struct Lanes([f64; 2]);

    impl Lanes {
        #[cfg(test)]
        pub(crate) fn new(values: [f64; 2]) -> Lanes {
            Lanes(values)
        }

        #[inline]
        pub(crate) fn splat(x: f64) -> Lanes {
            Lanes([x, x])
        }

        #[inline]
        pub(crate) fn widen(pair: &[f32; 2]) -> Lanes {
            Lanes(pair.map(f64::from))
        }

        #[inline]
        pub(crate) fn to_array(self) -> [f64; 2] {
            self.0
        }

        #[inline]
        pub(crate) fn sub(self, other: Lanes) -> Lanes {
            Lanes([self.0[0] - other.0[0], self.0[1] - other.0[1]])
        }

        #[inline]
        pub(crate) fn mul(self, other: Lanes) -> Lanes {
            Lanes([self.0[0] * other.0[0], self.0[1] * other.0[1]])
        }

        #[inline]
        pub(crate) fn max(self, other: Lanes) -> Lanes {
            let pick = |a: f64, b: f64| if a > b { a } else { b };
            Lanes([pick(self.0[0], other.0[0]), pick(self.0[1], other.0[1])])
        }

        #[inline]
        pub(crate) fn min(self, other: Lanes) -> Lanes {
            let pick = |a: f64, b: f64| if a < b { a } else { b };
            Lanes([pick(self.0[0], other.0[0]), pick(self.0[1], other.0[1])])
        }

        #[inline]
        pub(crate) fn le_mask(self, other: Lanes) -> u32 {
            u32::from(self.0[0] <= other.0[0]) | u32::from(self.0[1] <= other.0[1]) << 1
        }
    }
}

pub(super) use imp::Lanes;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arithmetic_works_lane_by_lane() {
        let a = Lanes::new([1.0, -2.0]);
        let b = Lanes::new([0.5, 4.0]);
        assert_eq!(a.sub(b).to_array(), [0.5, -6.0]);
        assert_eq!(a.mul(b).to_array(), [0.5, -8.0]);
        assert_eq!(a.max(b).to_array(), [1.0, 4.0]);
        assert_eq!(a.min(b).to_array(), [0.5, -2.0]);
        assert_eq!(Lanes::splat(3.0).to_array(), [3.0, 3.0]);
        // 1 <= 0.5 no, -2 <= 4 yes: bit 1 only.
        assert_eq!(a.le_mask(b), 0b10);
    }

    #[test]
    fn a_nan_or_a_tie_gives_the_second_operand() {
        let nan = Lanes::new([f64::NAN, 0.0]);
        let bound = Lanes::new([7.0, -0.0]);
        let max = nan.max(bound).to_array();
        let min = nan.min(bound).to_array();
        assert_eq!(max[0], 7.0);
        assert_eq!(min[0], 7.0);
        // 0 and -0 are equal: the second, -0, comes back.
        assert!(max[1] == 0.0 && max[1].is_sign_negative());
        assert!(min[1] == 0.0 && min[1].is_sign_negative());
        assert_eq!(nan.le_mask(bound), 0b10);
    }
}
