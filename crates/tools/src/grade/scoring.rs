//! The scoring rule, as docs/TEACHERS.md states it: a submission that `compare`
//! calls a match scores the scene's points; one that differs scores 0, or
//! with `partial = true` points × max(0, 1 − FLIP mean / max_flip); a
//! refused one scores 0. Points are rounded to hundredths, and a total is
//! the sum of the rounded points, rounded again (so the CSV's columns add
//! up to its total).

/// The points a compared submission scores out of `max`.
pub(crate) fn points(max: f64, matches: bool, flip_mean: f64, max_flip: Option<f64>) -> f64 {
    let share = match (matches, max_flip) {
        (true, _) => 1.0,
        (false, None) => 0.0,
        (false, Some(max_flip)) => (1.0 - flip_mean / max_flip).clamp(0.0, 1.0),
    };
    hundredths(max * share)
}

/// The sum of rounded points, rounded (0.1 + 0.2 is 0.30000000000000004).
pub(crate) fn total(points: impl IntoIterator<Item = f64>) -> f64 {
    hundredths(points.into_iter().sum())
}

pub(crate) fn hundredths(x: f64) -> f64 {
    (x * 100.0).round() / 100.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_match_scores_all_a_difference_nothing_or_its_share_of_flip() {
        // Without partial credit: all or nothing, whatever FLIP says.
        assert_eq!(points(10.0, true, 0.01, None), 10.0);
        assert_eq!(points(10.0, false, 0.01, None), 0.0);
        // A match scores all with partial credit too, FLIP aside.
        assert_eq!(points(10.0, true, 0.05, Some(0.2)), 10.0);
        // 10 × (1 − 0.05 / 0.2) = 7.5; 10 × (1 − 0.123 / 0.2) = 3.85.
        assert_eq!(points(10.0, false, 0.05, Some(0.2)), 7.5);
        assert_eq!(points(10.0, false, 0.123, Some(0.2)), 3.85);
        // FLIP at or past max_flip scores 0, not less.
        assert_eq!(points(10.0, false, 0.2, Some(0.2)), 0.0);
        assert_eq!(points(10.0, false, 0.9, Some(0.2)), 0.0);
        // 3 × (1 − 0.1 / 0.3) = 2 exactly would be 1.9999999999999998 unrounded.
        assert_eq!(points(3.0, false, 0.1, Some(0.3)), 2.0);
        assert_eq!(total([0.1, 0.2]), 0.3);
    }
}
