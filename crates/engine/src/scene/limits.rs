//! The range of every number a scene file may hold, written once for both
//! formats (docs/SCENES.md, MODEL §4 and §5).
//!
//! The ranges are far wider than a teaching scene or an SPD scene needs, and
//! narrow enough that no product the tracer forms can overflow or lose every
//! digit: with coordinates within 1e4 and sizes of at least 1e-3, a hit
//! distance still resolves EPS = 1e-4 and a sphere's normal (p - c) / r stays
//! near unit length; with colours within 1e6 and kd, ks, ka within 100, a
//! pixel lit by one light stays below 1e150 through 64 levels of reflection. Out of range is refused, so every
//! pixel and every recorded number is finite.

use glam::DVec3;

/// An inclusive range `min..=max` and what the numbers in it are.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Bounds {
    pub(crate) min: f64,
    pub(crate) max: f64,
}

/// Every coordinate and every vector component: positions, centres,
/// vertices, cone ends, `eye`, `look_at`, `up`, normals.
pub(crate) const COORDINATE: Bounds = Bounds::new(-1e4, 1e4);
/// A sphere's radius, a cone's non-zero radii (NFF: their absolute values)
/// and the distance between a cone's ends.
pub(crate) const SIZE: Bounds = Bounds::new(1e-3, 1e4);
/// Colours and light intensities: O_d, I_p, I_a, the background.
pub(crate) const COLOR: Bounds = Bounds::new(0.0, 1e6);
/// The material coefficients kd, ks and ka.
pub(crate) const COEFFICIENT: Bounds = Bounds::new(0.0, 100.0);
/// The transmission coefficient kt.
pub(crate) const TRANSMISSION: Bounds = Bounds::new(0.0, 1.0);
/// The specular exponent n (the SPD writes 100000 where Ks = 0).
pub(crate) const SHININESS: Bounds = Bounds::new(0.0, 1e6);
/// The index of refraction (MODEL §5); real materials lie between 1 and about 4.
pub(crate) const IOR: Bounds = Bounds::new(0.1, 10.0);
/// The attenuation coefficients (c1, c2, c3) and (a1, a2, a3).
pub(crate) const ATTENUATION: Bounds = Bounds::new(0.0, 1e6);
/// `min_weight`, the cutoff of a ray's accumulated weight (MODEL §5).
pub(crate) const WEIGHT: Bounds = Bounds::new(0.0, 1.0);

/// A scale factor of a CSE 167 `.test` `scale` (its absolute value; a
/// negative factor mirrors): as narrow as a size, so no factor flattens.
pub(crate) const SCALE: Bounds = Bounds::new(1e-3, 1e4);
/// A rotation angle in degrees (`.test` `rotate`): any turn, a bounded number.
pub(crate) const ANGLE: Bounds = Bounds::new(-1e6, 1e6);
/// Any entry of a composed `.test` transform: a product of many scales may
/// not grow past this, so every point it places stays finite.
pub(crate) const TRANSFORM_ENTRY: Bounds = Bounds::new(-1e8, 1e8);
/// The most vertices (or vertex-normal pairs) a `.test` file may define or
/// declare with `maxverts` / `maxvertnorms`: a million-triangle mesh's worth.
pub(crate) const MAX_TEST_VERTICES: usize = 1 << 22;
/// The deepest `pushTransform` nesting of a `.test` file.
pub(crate) const MAX_TRANSFORM_DEPTH: usize = 1024;

impl Bounds {
    pub(crate) const fn new(min: f64, max: f64) -> Self {
        Self { min, max }
    }

    /// `Ok` when `min <= value <= max` (never for NaN), else why not:
    /// "must be between MIN and MAX".
    pub(crate) fn check(&self, value: f64) -> Result<(), String> {
        if (self.min..=self.max).contains(&value) {
            Ok(())
        } else {
            Err(format!(
                "must be between {} and {}",
                show(self.min),
                show(self.max)
            ))
        }
    }
}

/// A cone radius: 0 (a pointed end) or within `SIZE`.
pub(crate) fn check_cone_radius(radius: f64) -> Result<(), String> {
    if radius == 0.0 {
        return Ok(());
    }
    SIZE.check(radius)
        .map_err(|reason| format!("{reason} (or be 0)"))
}

/// The distance between a cone's ends, within `SIZE`; ends that coincide
/// are left to the shape, which names them.
pub(crate) fn check_cone_length(base: DVec3, apex: DVec3) -> Result<(), String> {
    let length = (apex - base).length();
    if length == 0.0 {
        return Ok(());
    }
    SIZE.check(length).map_err(|reason| {
        format!(
            "the distance between the ends is {}; it {reason}",
            show(length)
        )
    })
}

/// A number as short as it can be read: `10000`, `0.5`, `1e300`, `1e-7`.
pub(crate) fn show(value: f64) -> String {
    let magnitude = value.abs();
    if magnitude == 0.0 || (1e-4..1e5).contains(&magnitude) || !value.is_finite() {
        format!("{value}")
    } else {
        format!("{value:e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_are_inclusive_and_refuse_nan() {
        assert_eq!(IOR.check(0.1), Ok(()));
        assert_eq!(IOR.check(10.0), Ok(()));
        assert_eq!(
            IOR.check(10.0f64.next_up()),
            Err("must be between 0.1 and 10".into())
        );
        assert!(COLOR.check(f64::NAN).is_err());
    }

    #[test]
    fn cone_radius_zero_or_a_size() {
        assert_eq!(check_cone_radius(0.0), Ok(()));
        assert_eq!(
            check_cone_radius(1e-4),
            Err("must be between 0.001 and 10000 (or be 0)".into())
        );
        // (0, 0, 0) to (3e4, 4e4, 0) is 5e4 long: over 1e4.
        assert_eq!(
            check_cone_length(DVec3::ZERO, DVec3::new(3e4, 4e4, 0.0)),
            Err(
                "the distance between the ends is 50000; it must be between 0.001 and 10000".into()
            )
        );
    }

    #[test]
    fn numbers_are_shown_short() {
        assert_eq!(show(1e300), "1e300");
        assert_eq!(show(-1e4), "-10000");
        assert_eq!(show(0.5), "0.5");
        assert_eq!(show(1e-300), "1e-300");
        assert_eq!(show(1e6), "1e6");
    }
}
