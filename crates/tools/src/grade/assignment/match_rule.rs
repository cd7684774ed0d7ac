//! The match rule's knobs in the assignment file (issue 40): how far a
//! channel may differ (`tolerance`, for lossy images), how many far-off
//! pixels a match allows (`far_off_allowed`), and whether anti-aliased
//! edges match (`antialiasing`); or CSE 167's pass rule, at most N hot
//! pixels (`hot_pixels_allowed`, issue 42). Each may be given at the top, for every
//! scene, and in a `[[scene]]`, for that scene; a scene's own wins.
//!
//! ```toml
//! tolerance = 3          # steps of 255 a channel may differ: 0 to 31
//! far_off_allowed = 0    # far-off pixels a match allows: 0 or more
//! antialiasing = true    # anti-aliased edges match
//! # or, in place of the share, far-off and edge rules, CSE 167's:
//! # hot_pixels_allowed = 20   # at most 20 pixels past the tolerance
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
    pub(super) antialiasing: Option<Spanned<bool>>,
    pub(super) hot_pixels_allowed: Option<Spanned<i64>>,
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
        if let Some(antialiasing) = &self.antialiasing {
            rule.antialiasing = *antialiasing.get_ref();
        }
        if let Some(allowed) = &self.hot_pixels_allowed {
            let value = *allowed.get_ref();
            rule.hot_pixels_allowed = Some(usize::try_from(value).map_err(|_| {
                (
                    allowed.span(),
                    format!("hot_pixels_allowed must be a whole number of pixels of at least 0, got {value}"),
                )
            })?);
        }
        // The hot-pixel rule excuses no pixel: a knob that says which
        // pixels to excuse would be silently ignored beside it.
        if rule.hot_pixels_allowed.is_some() {
            let spans = [
                (
                    "far_off_allowed",
                    self.far_off_allowed.as_ref().map(Spanned::span),
                ),
                (
                    "antialiasing",
                    self.antialiasing.as_ref().map(Spanned::span),
                ),
            ];
            if let Some((knob, Some(span))) = spans.into_iter().find(|(_, span)| span.is_some()) {
                return Err((
                    span,
                    format!(
                        "{knob} has no meaning beside hot_pixels_allowed: the hot-pixel rule counts every pixel more than the tolerance apart and excuses none: leave one of the two out"
                    ),
                ));
            }
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
                antialiasing: true,
                hot_pixels_allowed: None
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
                    antialiasing: false,
                    hot_pixels_allowed: None
                },
                MatchRule {
                    tolerance_steps: 0,
                    far_off_allowed: 2,
                    antialiasing: true,
                    hot_pixels_allowed: None
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

    #[test]
    fn the_hot_pixel_rule_is_set_at_the_top_or_in_a_scene_and_stands_alone() {
        // At the top: every scene counts hot pixels, at most 20, with the
        // top's tolerance; the other knobs keep their defaults (unused).
        let text = format!("tolerance = 6\nhot_pixels_allowed = 20\n{GLASS}");
        let rule = parsed(&text).unwrap().scenes[0].rule;
        assert_eq!(
            rule,
            MatchRule {
                tolerance_steps: 6,
                hot_pixels_allowed: Some(20),
                ..MatchRule::default()
            }
        );
        // In one scene only: the other keeps the share rule.
        let text = format!(
            "{GLASS}hot_pixels_allowed = 0\n\
             [[scene]]\nfile = \"shadows.toml\"\nsubmit = \"shadows.png\"\npoints = 5\n"
        );
        let rules: Vec<Option<usize>> = (parsed(&text).unwrap().scenes.iter())
            .map(|s| s.rule.hot_pixels_allowed)
            .collect();
        assert_eq!(rules, [Some(0), None]);
        // A negative count, at its value (line 1, column 22).
        let message = refused(&format!("hot_pixels_allowed = -1\n{GLASS}"));
        assert!(
            message.starts_with(&format!("{}:1:22: ", here().display())),
            "{message}"
        );
        assert!(message.contains("at least 0, got -1"), "{message}");
        // Beside a knob that excuses pixels, in the same table or in a
        // scene under the top's rule: refused at that knob, which the
        // hot-pixel rule would silently ignore.
        for (text, line_col, knob) in [
            (
                format!("hot_pixels_allowed = 5\nfar_off_allowed = 1\n{GLASS}"),
                "2:19",
                "far_off_allowed",
            ),
            (
                format!("hot_pixels_allowed = 5\n{GLASS}antialiasing = false\n"),
                "6:16",
                "antialiasing",
            ),
            (
                format!("{GLASS}antialiasing = true\nhot_pixels_allowed = 5\n"),
                "5:16",
                "antialiasing",
            ),
        ] {
            let message = refused(&text);
            assert!(
                message.starts_with(&format!("{}:{line_col}: ", here().display())),
                "{message}"
            );
            assert!(
                message.contains(&format!("{knob} has no meaning beside hot_pixels_allowed")),
                "{message}"
            );
        }
    }
}
