//! Text made safe for the SVG figure: an object's or a light's name is
//! anything the scene file says.

/// `text` for SVG's element text or a quoted attribute: markup characters
/// as entities, and control characters (which XML 1.0 cannot carry, not
/// even as `&#1b;`) spelled out as `raystep_engine::printable` does.
pub(crate) fn escape(text: &str) -> String {
    raystep_engine::printable::printable(text)
        .replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_escaped() {
        assert_eq!(escape("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
    }
}
