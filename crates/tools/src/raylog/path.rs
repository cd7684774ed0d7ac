//! A ray's path in a ray log: `P` is the primary ray, and each child appends
//! `/R` (reflected), `/T` (transmitted) or `/S<i>` (the shadow ray to light
//! i, from 0 in the scene's order of lights). Shadow rays are leaves.
//!
//! A path's steps are shared, not copied, when it is cloned: the same
//! path is held by a log's ray, by ours found by path and by every
//! alignment of the two (once cloned per alignment and per mistake of the
//! catalogue, a log of paths 8000 steps deep took 2.6 GB).

use std::fmt;
use std::sync::Arc;

/// One step down the tree from a ray to its child.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Step {
    Reflected,
    Transmitted,
    /// The shadow ray to light i.
    Shadow(usize),
}

/// A ray's place in its pixel's tree: the steps from the primary ray,
/// shared by its clones.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct RayPath {
    pub steps: Arc<[Step]>,
}

impl RayPath {
    /// The primary ray, `P`.
    pub fn primary() -> Self {
        Self::default()
    }

    /// The path of these steps.
    pub fn of(steps: Vec<Step>) -> Self {
        Self {
            steps: steps.into(),
        }
    }

    /// This path with `step` appended.
    pub fn child(&self, step: Step) -> Self {
        let mut steps = self.steps.to_vec();
        steps.push(step);
        Self::of(steps)
    }

    /// The parent's path and the last step; `None` for the primary ray.
    pub fn parent(&self) -> Option<(Self, Step)> {
        let (&last, rest) = self.steps.split_last()?;
        Some((Self::of(rest.to_vec()), last))
    }

    /// How many reflected and transmitted steps: the ray's depth less one
    /// (MODEL §5: the primary ray has depth 1).
    pub fn branches(&self) -> usize {
        self.steps.len() - usize::from(self.is_shadow())
    }

    /// Whether the path ends in a shadow ray.
    pub fn is_shadow(&self) -> bool {
        matches!(self.steps.last(), Some(Step::Shadow(_)))
    }

    /// Reads `text` for a scene with `lights` lights; the error says what
    /// is wrong in words.
    pub fn parse(text: &str, lights: usize) -> Result<Self, String> {
        let mut parts = text.split('/');
        match parts.next() {
            Some("P") => {}
            _ => {
                return Err(format!(
                    "path {text:?} does not start with P, the primary ray \
                     (a path is P, then /R, /T or /S<i> per step, e.g. P/T/S1)"
                ));
            }
        }
        let mut steps = Vec::new();
        for part in parts {
            if let Some(Step::Shadow(i)) = steps.last() {
                return Err(format!(
                    "path {text:?}: S{i} is a shadow ray, a leaf: nothing follows it"
                ));
            }
            let step = match part {
                "R" => Step::Reflected,
                "T" => Step::Transmitted,
                _ => shadow_step(text, part, lights)?,
            };
            steps.push(step);
        }
        Ok(Self::of(steps))
    }
}

/// `S<i>`, light i of `lights`.
fn shadow_step(text: &str, part: &str, lights: usize) -> Result<Step, String> {
    let digits = part.strip_prefix('S').unwrap_or_default();
    let is_number = !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit());
    if !part.starts_with('S') || !is_number {
        return Err(format!(
            "path {text:?}: {part:?} is not a step: R (reflected), T (transmitted) \
             or S<i> (the shadow ray to light i)"
        ));
    }
    match digits.parse::<usize>() {
        Ok(i) if i < lights => Ok(Step::Shadow(i)),
        _ => Err(format!(
            "path {text:?}: there is no light {digits}: the scene has {lights} light{}{}",
            if lights == 1 { "" } else { "s" },
            match lights {
                0 => String::new(),
                1 => " (S0)".to_string(),
                _ => format!(" (S0 to S{})", lights - 1),
            }
        )),
    }
}

impl fmt::Display for RayPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("P")?;
        for step in self.steps.iter() {
            match step {
                Step::Reflected => f.write_str("/R")?,
                Step::Transmitted => f.write_str("/T")?,
                Step::Shadow(i) => write!(f, "/S{i}")?,
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_read_back_as_they_print() {
        for text in ["P", "P/R", "P/T/R", "P/T/S1", "P/S0", "P/R/R/T/S1"] {
            assert_eq!(RayPath::parse(text, 2).unwrap().to_string(), text);
        }
        let path = RayPath::parse("P/T/S1", 2).unwrap();
        assert_eq!(*path.steps, [Step::Transmitted, Step::Shadow(1)]);
        assert!(path.is_shadow());
    }

    #[test]
    fn malformed_paths_say_what_is_wrong() {
        let error = |text| RayPath::parse(text, 2).unwrap_err();
        assert!(
            error("P/X").contains("\"X\" is not a step"),
            "{}",
            error("P/X")
        );
        assert!(error("R").contains("does not start with P"));
        assert!(error("").contains("does not start with P"));
        assert!(error("p").contains("does not start with P"));
        assert!(error("P/").contains("\"\" is not a step"));
        assert!(error("P/S").contains("\"S\" is not a step"));
        assert!(error("P/S-1").contains("is not a step"));
        assert!(error("P/S7").contains("no light 7: the scene has 2 lights (S0 to S1)"));
        assert!(error("P/S0/R").contains("S0 is a shadow ray, a leaf"));
        assert!(
            RayPath::parse("P/S0", 0)
                .unwrap_err()
                .contains("has 0 lights")
        );
        assert!(RayPath::parse("P/S99999999999999999999999", 1).is_err());
    }
}
