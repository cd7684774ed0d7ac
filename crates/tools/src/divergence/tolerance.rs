//! When two numbers of a ray agree: relative on lengths (positions,
//! directions, t), absolute on colours and the factors that scale them.

use std::fmt;

use glam::DVec3;

/// The tolerances of `compare --rays` (docs/RAYLOG.md, "Tolerance").
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    /// Relative, on positions, directions and t: two agree when they are
    /// within `geometry` times the larger length (or times 1, below 1).
    pub geometry: f64,
    /// Absolute, per channel on colours and terms, and on S and weights:
    /// 1/512 by default, half a step of an 8-bit byte.
    pub colour: f64,
}

impl Default for Tolerance {
    fn default() -> Self {
        Self {
            geometry: 1e-4,
            colour: 1.0 / 512.0,
        }
    }
}

impl Tolerance {
    /// `--tolerance GEOMETRY[,COLOUR]`: both non-negative and finite.
    pub fn parse(text: &str) -> Result<Self, String> {
        let bad = || {
            format!(
                "{text:?} is not a tolerance: give GEOMETRY or GEOMETRY,COLOUR, \
                 numbers from 0, such as 1e-4 or 1e-3,0.004"
            )
        };
        let number = |part: &str| match part.trim().parse::<f64>() {
            Ok(x) if x.is_finite() && x >= 0.0 => Ok(x),
            _ => Err(bad()),
        };
        let parts: Vec<&str> = text.split(',').collect();
        match parts[..] {
            [geometry] => Ok(Self {
                geometry: number(geometry)?,
                ..Self::default()
            }),
            [geometry, colour] => Ok(Self {
                geometry: number(geometry)?,
                colour: number(colour)?,
            }),
            _ => Err(bad()),
        }
    }

    /// Two lengths or distances (infinite ones agree with nothing: the
    /// gap is then infinite or NaN).
    pub(crate) fn lengths(&self, yours: f64, ours: f64) -> bool {
        let gap = (yours - ours).abs();
        gap.is_finite() && gap <= self.geometry * yours.abs().max(ours.abs()).max(1.0)
    }

    /// Two positions or directions. Both are first divided by their largest
    /// component, so that no square overflows: (1e200, 1e200, -1e200) once
    /// gave a gap and a bound both infinite, and inf <= inf "agreed".
    pub(crate) fn vectors(&self, yours: DVec3, ours: DVec3) -> bool {
        let scale = (yours.abs().max_element())
            .max(ours.abs().max_element())
            .max(1.0);
        if !scale.is_finite() {
            // An infinite component agrees with nothing (a NaN fails below).
            return false;
        }
        let (yours, ours) = (yours / scale, ours / scale);
        (yours - ours).length()
            <= self.geometry * yours.length().max(ours.length()).max(1.0 / scale)
    }

    /// Two colours, channel by channel.
    pub(crate) fn colours(&self, yours: DVec3, ours: DVec3) -> bool {
        (yours - ours).abs().max_element() <= self.colour
    }

    /// Two factors of a colour (S, a weight).
    pub(crate) fn factors(&self, yours: f64, ours: f64) -> bool {
        (yours - ours).abs() <= self.colour
    }
}

impl fmt::Display for Tolerance {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "relative {:e} on positions, directions and t; {} on colours",
            self.geometry, self.colour
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn huge_numbers_agree_only_when_they_are_close() {
        let t = Tolerance::default();
        let huge = DVec3::new(1e200, 1e200, -1e200);
        // |huge − (0, 0, 1)| ≈ 1.7e200: apart by every measure (its square,
        // 3e400, overflowed, and inf <= 1e-4 × inf held).
        assert!(!t.vectors(huge, DVec3::Z));
        assert!(!t.vectors(DVec3::Z, huge));
        // Equal, and 1e-6 apart relatively (under 1e-4): they agree.
        assert!(t.vectors(huge, huge));
        assert!(t.vectors(huge, huge * (1.0 + 1e-6)));
        // 1e-3 apart relatively: past 1e-4.
        assert!(!t.vectors(huge, huge * (1.0 + 1e-3)));
        // Infinite or NaN components agree with nothing, themselves included.
        let inf = DVec3::new(f64::INFINITY, 0.0, 0.0);
        assert!(!t.vectors(inf, inf));
        assert!(!t.vectors(DVec3::NAN, DVec3::NAN));
        // 1e308 and −1e308 are 2e308 apart, which overflows: not agreeing.
        assert!(!t.lengths(1e308, -1e308));
        assert!(!t.lengths(f64::INFINITY, f64::INFINITY));
        assert!(t.lengths(1e300, 1e300 * (1.0 + 1e-6)));
    }

    #[test]
    fn a_tolerance_reads_one_or_two_numbers() {
        assert_eq!(Tolerance::parse("1e-3").unwrap().geometry, 1e-3);
        assert_eq!(Tolerance::parse("1e-3").unwrap().colour, 1.0 / 512.0);
        assert_eq!(
            Tolerance::parse("0.01, 0.1").unwrap(),
            Tolerance {
                geometry: 0.01,
                colour: 0.1
            }
        );
        for bad in ["", "x", "-1", "nan", "inf", "1,2,3", "1,-2"] {
            assert!(Tolerance::parse(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn lengths_agree_relatively_and_colours_absolutely() {
        let t = Tolerance::default();
        // 1000 and 1000.05 are 5e-5 apart relatively: they agree; 1000.2 does not.
        assert!(t.lengths(1000.05, 1000.0));
        assert!(!t.lengths(1000.2, 1000.0));
        // Below a length of 1 the tolerance is 1e-4 absolute.
        assert!(t.lengths(0.00005, 0.0));
        assert!(!t.lengths(0.0002, 0.0));
        // 1/512 = 0.00195: 0.5 and 0.5019 agree, 0.5 and 0.503 do not.
        assert!(t.colours(DVec3::splat(0.5019), DVec3::splat(0.5)));
        assert!(!t.colours(DVec3::new(0.5, 0.503, 0.5), DVec3::splat(0.5)));
        assert!(!t.lengths(f64::NAN, 1.0));
        assert!(!t.colours(DVec3::new(f64::INFINITY, 0.0, 0.0), DVec3::ZERO));
    }
}
