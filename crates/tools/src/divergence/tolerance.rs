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

    /// Two lengths or distances.
    pub(crate) fn lengths(&self, yours: f64, ours: f64) -> bool {
        (yours - ours).abs() <= self.geometry * yours.abs().max(ours.abs()).max(1.0)
    }

    /// Two positions or directions.
    pub(crate) fn vectors(&self, yours: DVec3, ours: DVec3) -> bool {
        (yours - ours).length() <= self.geometry * yours.length().max(ours.length()).max(1.0)
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
