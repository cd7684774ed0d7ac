//! Panning and zooming the ray diagram: the window shown, worked out from
//! the window that fits the whole figure. A step pans a quarter of what is
//! shown, a zoom step shows 1.5 times less (or more), about a focus (the
//! primary ray's first hit, as `raystep diagram --zoom` magnifies); the
//! fitted window is zoom 0, no pan.

use glam::DVec2;

use raystep_tools::diagram::magnified_centre;

/// How far the diagram is panned and zoomed from the fitted window.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PanZoom {
    /// The window's centre from the fitted one's, in halves of the fitted
    /// window (1 = half of it to the right or up).
    pan: (f64, f64),
    /// Zoom steps: positive shows less, bigger.
    zoom: i32,
}

/// How much one zoom step magnifies.
const FACTOR: f64 = 1.5;
/// The zoom steps allowed, out and in.
const ZOOM_OUT: i32 = -4;
const ZOOM_IN: i32 = 12;

impl PanZoom {
    /// The fitted window: the whole figure.
    pub(crate) fn fit() -> PanZoom {
        PanZoom::default()
    }

    pub fn is_fit(&self) -> bool {
        *self == PanZoom::fit()
    }

    /// The zoom steps, positive when zoomed in.
    pub fn zoom(&self) -> i32 {
        self.zoom
    }

    /// How many times bigger than the fitted window the figure is shown.
    pub(crate) fn magnification(&self) -> f64 {
        FACTOR.powi(self.zoom)
    }

    /// The magnification for a title ("zoom 2.25×"), none when 1.
    pub(crate) fn label(&self) -> Option<String> {
        (self.zoom != 0).then(|| {
            let factor = format!("{:.3}", self.magnification());
            let factor = factor.trim_end_matches('0').trim_end_matches('.');
            format!("zoom {factor}×")
        })
    }

    /// Moves the window by (dx, dy) quarters of what it shows: dx > 0 to
    /// the right, dy > 0 down (as the arrow keys point).
    pub(crate) fn pan(&mut self, dx: i32, dy: i32) {
        let step = 0.5 / self.magnification();
        self.pan.0 += f64::from(dx) * step;
        self.pan.1 -= f64::from(dy) * step;
    }

    /// Zooms in (steps > 0) or out, within the allowed steps.
    pub(crate) fn zoom_by(&mut self, steps: i32) {
        self.zoom = (self.zoom + steps).clamp(ZOOM_OUT, ZOOM_IN);
    }

    /// The window shown, from the fitted window's x and y ranges,
    /// magnified about `focus`. Zoomed in, the focus moves toward the
    /// middle as the SVG figure's does (its offset from the middle divided
    /// by the magnification squared: shown magnified, it is divided by the
    /// magnification), so a hit near the edge stays in view; zoomed out,
    /// the window keeps its centre.
    pub(crate) fn window(
        &self,
        x: [f64; 2],
        y: [f64; 2],
        focus: (f64, f64),
    ) -> ([f64; 2], [f64; 2]) {
        let m = self.magnification();
        let half = DVec2::new(x[1] - x[0], y[1] - y[0]) / 2.0;
        let middle = DVec2::new(x[0] + x[1], y[0] + y[1]) / 2.0;
        let centre = magnified_centre(middle, DVec2::from(focus), m) + DVec2::from(self.pan) * half;
        let (lo, hi) = (centre - half / m, centre + half / m);
        ([lo.x, hi.x], [lo.y, hi.y])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const X: [f64; 2] = [-4.0, 4.0];
    const Y: [f64; 2] = [0.0, 2.0];
    /// The fitted window's middle: zoom about it keeps the centre.
    const MIDDLE: (f64, f64) = (0.0, 1.0);

    #[test]
    fn the_fitted_window_is_the_whole_figure() {
        assert_eq!(PanZoom::fit().window(X, Y, MIDDLE), (X, Y));
    }

    #[test]
    fn a_step_right_moves_a_quarter_of_the_window() {
        // x shows 8 units: a quarter is 2. Down moves y by a quarter of 2.
        let mut view = PanZoom::fit();
        view.pan(1, 0);
        assert_eq!(view.window(X, Y, MIDDLE), ([-2.0, 6.0], Y));
        view.pan(-1, 1);
        assert_eq!(view.window(X, Y, MIDDLE), (X, [-0.5, 1.5]));
        assert!(!view.is_fit());
    }

    #[test]
    fn zooming_shows_less_around_the_centre_and_pans_less() {
        // Zoom 2: 2.25 times bigger, x shows 8 / 2.25 around 0; a step
        // right then moves a quarter of that.
        let mut view = PanZoom::fit();
        view.zoom_by(2);
        let (x, _) = view.window(X, Y, MIDDLE);
        assert!((x[1] - 4.0 / 2.25).abs() < 1e-12, "{x:?}");
        view.pan(1, 0);
        let (panned, _) = view.window(X, Y, MIDDLE);
        assert!((panned[0] - x[0] - 8.0 / 2.25 / 4.0).abs() < 1e-12);
        // Zooming stops at its limits.
        view.zoom_by(100);
        assert_eq!(view.zoom(), ZOOM_IN);
        view.zoom_by(-100);
        assert_eq!(view.zoom(), ZOOM_OUT);
    }

    #[test]
    fn zooming_magnifies_about_the_focus_and_keeps_it_in_view() {
        // Focus (3, 0) in x -4..4: zoom 2 (m = 2.25) puts the window's
        // centre at 3 + (0 - 3) / 2.25² = 3 - 0.5926 = 2.4074, half-width
        // 4 / 2.25 = 1.7778: x 0.6296..4.1852, holding 3 where the fitted
        // window's centre would have shown -1.78..1.78 (3 out of view).
        let mut view = PanZoom::fit();
        view.zoom_by(2);
        let (x, _) = view.window(X, Y, (3.0, 0.0));
        let centre = 3.0 - 3.0 / (2.25 * 2.25);
        assert!((x[0] - (centre - 4.0 / 2.25)).abs() < 1e-12, "{x:?}");
        assert!((x[1] - (centre + 4.0 / 2.25)).abs() < 1e-12, "{x:?}");
        assert!(x[0] < 3.0 && 3.0 < x[1]);
        assert_eq!(view.label().as_deref(), Some("zoom 2.25×"));
        view.zoom_by(-3);
        assert_eq!(view.label().as_deref(), Some("zoom 0.667×"));
        assert_eq!(PanZoom::fit().label(), None);
    }
}
