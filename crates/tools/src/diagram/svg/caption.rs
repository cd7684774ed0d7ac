//! What a figure says it shows: the scene file, the pixel, the plane and
//! every option it was drawn with (`--mistake`, `--set`, ...), in the SVG's
//! `<title>` and in its heading, so a slide can be drawn again from it.

use std::fmt::Write;

use super::escaping::escape;

/// The heading's largest and smallest font size, and the figures' width.
const HEADING_SIZE: f64 = 15.0;
const SMALLEST: f64 = 9.0;
const FIGURE_WIDTH: f64 = 800.0;

/// How a figure was drawn, as `raystep diagram` was told.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Caption {
    /// The scene file's name.
    pub scene: String,
    /// Each option that changed the figure, as given: `--mistake NAME`,
    /// `--set KEY=VALUE`, `--size WxH`, `--shadows ...`.
    pub options: Vec<String>,
}

impl Caption {
    /// The caption's words for pixel `(x, y)` seen as `view` (the plane,
    /// or the crossing test): the scene first, the options last.
    fn words(&self, (x, y): (u32, u32), view: &str) -> String {
        let mut words = if self.scene.is_empty() {
            format!("Pixel ({x}, {y}), {view}")
        } else {
            format!("{}, pixel ({x}, {y}), {view}", self.scene)
        };
        if !self.options.is_empty() {
            let _ = write!(words, "; drawn with {}", self.options.join(", "));
        }
        words
    }

    /// The `<title>` element (the SVG's first child, as SVG wants) and the
    /// heading's `<text>` starting at `(x, y)` (its baseline), its font
    /// made smaller (down to 9) so its estimated width fits the figure
    /// with the same margin `x` on the right, and squeezed to fit below
    /// that.
    pub(crate) fn elements(
        &self,
        pixel: (u32, u32),
        view: &str,
        (x, y): (f64, f64),
    ) -> (String, String) {
        let room = FIGURE_WIDTH - 2.0 * x;
        let words = escape(&self.words(pixel, view));
        let title = format!("<title>{words}</title>\n");
        // 0.6 em a character, as the label placer estimates text.
        let chars = self.words(pixel, view).chars().count() as f64;
        let size = (room / (0.6 * chars)).clamp(SMALLEST, HEADING_SIZE);
        let size = (size * 2.0).floor() / 2.0;
        let squeeze = if chars * 0.6 * size > room {
            format!(" textLength=\"{room}\" lengthAdjust=\"spacingAndGlyphs\"")
        } else {
            String::new()
        };
        let heading =
            format!("<text x=\"{x}\" y=\"{y}\" font-size=\"{size}\"{squeeze}>{words}</text>\n");
        (title, heading)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_title_names_the_scene_pixel_view_and_options_escaped() {
        let caption = Caption {
            scene: "glass.toml".into(),
            options: vec!["--mistake tir-dropped".into(), "--set a.b=<1&2>".into()],
        };
        let (title, heading) = caption.elements((135, 58), "from above", (40.0, 24.0));
        let words = "glass.toml, pixel (135, 58), from above; drawn with \
                     --mistake tir-dropped, --set a.b=&lt;1&amp;2&gt;";
        assert_eq!(title, format!("<title>{words}</title>\n"));
        // 90 characters unescaped: 720 / (0.6 × 90) = 13.3, down to the half: 13.
        assert_eq!(
            heading,
            format!("<text x=\"40\" y=\"24\" font-size=\"13\">{words}</text>\n")
        );
        // Without a scene (the debugger's figure), as before.
        let bare = Caption::default()
            .elements((1, 2), "from above", (40.0, 24.0))
            .1;
        assert!(bare.contains("font-size=\"15\">Pixel (1, 2), from above</text>"));
    }

    #[test]
    fn a_long_heading_is_squeezed_into_the_figure() {
        // 200 characters of options: 720 / (0.6 × ~250) < 9, so 9 and squeezed.
        let caption = Caption {
            scene: "s.toml".into(),
            options: vec![format!("--set {}", "x".repeat(200))],
        };
        let heading = caption.elements((0, 0), "from above", (40.0, 24.0)).1;
        assert!(
            heading.contains("font-size=\"9\" textLength=\"720\""),
            "{heading}"
        );
    }
}
