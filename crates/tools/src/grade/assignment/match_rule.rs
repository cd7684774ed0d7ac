//! The match rule's knobs in the assignment file (issue 40): how far a
//! channel may differ (`tolerance`, for lossy images), how many far-off
//! pixels a match allows (`far_off_allowed`), and whether anti-aliased
//! edges match (`antialiasing`). Each may be given at the top, for every
//! scene, and in a `[[scene]]`, for that scene; a scene's own wins.
//!
//! ```toml
//! tolerance = 3          # steps of 255 a channel may differ: 0 to 31
//! far_off_allowed = 0    # far-off pixels a match allows: 0 or more
//! antialiasing = true    # anti-aliased edges match
//!
//! [[scene]]
//! file = "glass.toml"
//! submit = "glass.jpg.png"
//! points = 10
//! tolerance = 12         # this scene's images went through JPEG
//! ```

use std::ops::Range;

use toml::Spanned;

use crate::compare::{MATCH_GAP, MatchRule};

/// The knobs as written, at the top or in a `[[scene]]`.
#[derive(Default)]
pub(super) struct Knobs {
    pub(super) tolerance: Option<Spanned<i64>>,
    pub(super) far_off_allowed: Option<Spanned<i64>>,
    pub(super) antialiasing: Option<bool>,
}

impl Knobs {
    /// `defaults` (the top's rule) changed by what these knobs say; a
    /// value out of range is told at its span.
    pub(super) fn rule(&self, defaults: MatchRule) -> Result<MatchRule, (Range<usize>, String)> {
        let mut rule = defaults;
        if let Some(tolerance) = &self.tolerance {
            let value = *tolerance.get_ref();
            rule.tolerance_steps = u8::try_from(value)
                .ok()
                .filter(|&steps| steps < MATCH_GAP)
                .ok_or_else(|| {
                    (
                        tolerance.span(),
                        format!(
                            "tolerance must be a whole number of steps of 255 from 0 to {}, below the {MATCH_GAP} steps of a far-off pixel, got {value}",
                            MATCH_GAP - 1
                        ),
                    )
                })?;
        }
        if let Some(allowed) = &self.far_off_allowed {
            let value = *allowed.get_ref();
            rule.far_off_allowed = usize::try_from(value).map_err(|_| {
                (
                    allowed.span(),
                    format!("far_off_allowed must be a whole number of pixels of at least 0, got {value}"),
                )
            })?;
        }
        if let Some(antialiasing) = self.antialiasing {
            rule.antialiasing = antialiasing;
        }
        Ok(rule)
    }
}

#[cfg(test)]
mod tests {
    use crate::compare::MatchRule;
    use crate::grade::assignment::{test_parsed as parsed, test_path as here};

    fn refused(text: &str) -> String {
        match parsed(text) {
            Ok(_) => panic!("accepted: {text}"),
            Err(message) => message,
        }
    }

    const GLASS: &str = "[[scene]]\nfile = \"glass.toml\"\nsubmit = \"glass.png\"\npoints = 10\n";

    #[test]
    fn the_top_sets_every_scene_and_a_scene_its_own() {
        // No knob: the default rule (3 steps, no far-off pixel, anti-aliasing).
        let plain = parsed(GLASS).unwrap();
        assert_eq!(plain.scenes[0].rule, MatchRule::default());
        assert_eq!(
            MatchRule::default(),
            MatchRule {
                tolerance_steps: 3,
                far_off_allowed: 0,
                antialiasing: true
            }
        );
        // The top's for every scene; shadows.png says otherwise for two.
        let text = format!(
            "tolerance = 8\nfar_off_allowed = 2\nantialiasing = false\n{GLASS}\
             [[scene]]\nfile = \"shadows.toml\"\nsubmit = \"shadows.png\"\npoints = 5\n\
             tolerance = 0\nantialiasing = true\n"
        );
        let both = parsed(&text).unwrap();
        let rules: Vec<MatchRule> = both.scenes.iter().map(|s| s.rule).collect();
        assert_eq!(
            rules,
            [
                MatchRule {
                    tolerance_steps: 8,
                    far_off_allowed: 2,
                    antialiasing: false
                },
                MatchRule {
                    tolerance_steps: 0,
                    far_off_allowed: 2,
                    antialiasing: true
                },
            ]
        );
    }

    #[test]
    fn bad_knobs_are_told_at_their_line_and_column() {
        let at = |line_col: &str| format!("{}:{line_col}: ", here().display());
        // At the top, line 1, the value from column 13.
        for (bad, words) in [
            (
                "32",
                "tolerance must be a whole number of steps of 255 from 0 to 31",
            ),
            (
                "-1",
                "from 0 to 31, below the 32 steps of a far-off pixel, got -1",
            ),
        ] {
            let message = refused(&format!("tolerance = {bad}\n{GLASS}"));
            assert!(message.starts_with(&at("1:13")), "{message}");
            assert!(message.contains(words), "{message}");
        }
        // Not a whole number: TOML's own words, at the value.
        let message = refused(&format!("tolerance = 3.5\n{GLASS}"));
        assert!(message.starts_with(&at("1:13")), "{message}");
        // In a scene: line 5 of the scene's block.
        let message = refused(&format!("{GLASS}far_off_allowed = -2\n"));
        assert!(message.starts_with(&at("5:19")), "{message}");
        assert!(
            message
                .contains("far_off_allowed must be a whole number of pixels of at least 0, got -2"),
            "{message}"
        );
        let message = refused(&format!("{GLASS}antialiasing = \"yes\"\n"));
        assert!(message.starts_with(&at("5:16")), "{message}");
        // A misspelt knob is an unknown key.
        let message = refused(&format!("{GLASS}anti_aliasing = false\n"));
        assert!(message.starts_with(&at("5:1")), "{message}");
        assert!(
            message.contains("unknown field `anti_aliasing`"),
            "{message}"
        );
    }
}
