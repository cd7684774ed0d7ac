//! How points and FLIP read on the pages: as few digits as say them.

/// Points to at most two decimals, without trailing zeros: 10, 7.5, 6.67.
pub(super) fn points(value: f64) -> String {
    let text = format!("{value:.2}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    // -0.001 rounds to "-0"; no one scored less than nothing.
    if text == "-0" {
        "0".into()
    } else {
        text.into()
    }
}

/// FLIP's mean error, three decimals as `compare` prints it.
pub(super) fn flip(value: f64) -> String {
    format!("{value:.3}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_say_no_more_digits_than_they_have() {
        assert_eq!(points(10.0), "10");
        assert_eq!(points(7.5), "7.5");
        assert_eq!(points(20.0 / 3.0), "6.67");
        assert_eq!(points(0.0), "0");
        assert_eq!(points(-0.001), "0");
        assert_eq!(flip(0.15664), "0.157");
    }
}
