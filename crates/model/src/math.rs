//! Small value types shared by every part of the tracer: rays, colours and
//! the open interval of accepted hit distances.

use glam::DVec3;

/// An RGB colour with linear channels; 1.0 is full intensity before clamping.
pub type Color = DVec3;

/// Hits closer than this (in scene units) are ignored, for every kind of ray,
/// so that secondary rays starting on a surface do not hit it again (MODEL §3).
pub const EPS: f64 = 1e-4;

/// A half-line `origin + t * direction`. The direction of a primary or shadow
/// ray is unit length; secondary directions are used as computed (MODEL §5).
#[derive(Clone, Copy, Debug)]
pub struct Ray {
    pub origin: DVec3,
    pub direction: DVec3,
}

impl Ray {
    #[inline]
    pub fn new(origin: DVec3, direction: DVec3) -> Self {
        Self { origin, direction }
    }

    #[inline]
    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + t * self.direction
    }
}

/// The open interval `(min, max)` of ray distances a query accepts.
#[derive(Clone, Copy, Debug)]
pub struct Interval {
    pub min: f64,
    pub max: f64,
}

impl Interval {
    pub const fn new(min: f64, max: f64) -> Self {
        Self { min, max }
    }

    /// Every hit in front of a ray's origin: `(EPS, inf)`.
    pub const fn in_front() -> Self {
        Self::new(EPS, f64::INFINITY)
    }

    /// Its lower end: distances must exceed it.
    #[inline]
    pub fn min(&self) -> f64 {
        self.min
    }

    /// Its upper end: distances must stay below it.
    #[inline]
    pub fn max(&self) -> f64 {
        self.max
    }

    /// True when `min < t < max`.
    #[inline]
    pub fn surrounds(&self, t: f64) -> bool {
        self.min < t && t < self.max
    }
}

/// `value > bound`, false when either is NaN: validation reads
/// `!exceeds(radius, 0.0)` to refuse NaN along with non-positive values.
#[inline]
pub fn exceeds(value: f64, bound: f64) -> bool {
    value > bound
}

/// Attenuation `min(1, 1 / (c1 + c2 d + c3 d^2))`, used for lights and for
/// secondary rays (MODEL §4, §5). A non-positive denominator means no attenuation.
#[inline]
pub fn attenuation([c1, c2, c3]: [f64; 3], distance: f64) -> f64 {
    let denominator = c1 + c2 * distance + c3 * distance * distance;
    if denominator <= 0.0 {
        1.0
    } else {
        (1.0 / denominator).min(1.0)
    }
}

/// An 8-bit channel value: clamp to [0, 1], then floor(255 c + 0.5) (MODEL §6).
pub(crate) fn to_byte(channel: f64) -> u8 {
    // The cast does the clamp: a float cast to u8 saturates (below 0 to 0,
    // above 255 to 255, NaN to 0), and 255 c + 0.5 leaves [0.5, 255.5]
    // exactly when c leaves [0, 1]. Within, truncating is the floor, without
    // the libm call that `floor` is on baseline x86-64.
    (255.0 * channel + 0.5) as u8
}

/// A colour as stored in the PNG.
pub fn to_rgb8(color: Color) -> [u8; 3] {
    [to_byte(color.x), to_byte(color.y), to_byte(color.z)]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn attenuation_is_capped_at_one() {
        // 1 / (0.5 + 0 + 0) = 2, capped to 1.
        assert_eq!(attenuation([0.5, 0.0, 0.0], 3.0), 1.0);
        // 1 / (1 + 0.5 * 2 + 0.25 * 4) = 1 / 3.
        assert!((attenuation([1.0, 0.5, 0.25], 2.0) - 1.0 / 3.0).abs() < 1e-15);
    }

    #[test]
    fn bytes_round_half_up_and_clamp() {
        assert_eq!(to_byte(-0.2), 0);
        assert_eq!(to_byte(1.7), 255);
        // Out of range by far, and not a number: clamped like the rest.
        assert_eq!(to_byte(-1e300), 0);
        assert_eq!(to_byte(f64::NEG_INFINITY), 0);
        assert_eq!(to_byte(f64::INFINITY), 255);
        assert_eq!(to_byte(f64::NAN), 0);
        // Just outside [0, 1]: 255 (1 + 2^-52) + 0.5 is still 255.5 -> 255;
        // -2^-1074 (the least negative f64) gives 0.5 -> 0.
        assert_eq!(to_byte(1.0f64.next_up()), 255);
        assert_eq!(to_byte(-f64::from_bits(1)), 0);
        // 255 * 0.5 = 127.5, + 0.5 = 128.0 -> 128.
        assert_eq!(to_byte(0.5), 128);
        // 255 * 0.2 = 51.0 -> 51.
        assert_eq!(to_byte(0.2), 51);
    }

    #[test]
    fn truncation_is_the_floor_of_model_6() {
        // Every channel value near each rounding boundary k + 0.5 of 255 c.
        for k in 0..255 {
            let boundary = (k as f64 + 0.5) / 255.0;
            let mut c = boundary;
            for _ in 0..8 {
                c = c.next_down();
            }
            for _ in 0..16 {
                assert_eq!(f64::from(to_byte(c)), (255.0 * c + 0.5).floor(), "{c:e}");
                c = c.next_up();
            }
        }
    }
}
