//! The size trap: a log traced at another image size than the one it is
//! read at has every primary ray through another point of the image
//! (`other_pixel` at every pixel). Each primary direction is read back to
//! the image size W' x H' whose pixel (x, y) it is the centre ray of (the
//! same field of view, as `--size` keeps it, MODEL §2); when every one of
//! them gives the same other size, the report says "pass --size W'xH'".

use glam::DVec3;

use crate::raylog::LoggedRay;
use raystep_engine::render::viewport;
use raystep_engine::scene::Scene;
use raystep_model::camera::Viewport;

/// How far from a whole number of pixels a size read back may be.
const WHOLE: f64 = 0.02;

pub(super) struct SizeGuess {
    viewport: Viewport,
    size: (u32, u32),
    guess: Option<(u32, u32)>,
    broken: bool,
    /// The smallest and largest x and y of the primary rays seen: a size
    /// is only told from pixels in two columns and two rows.
    x: (u32, u32),
    y: (u32, u32),
}

impl SizeGuess {
    pub(super) fn new(scene: &Scene) -> Self {
        let size = (scene.width, scene.height);
        Self {
            viewport: viewport(scene, &scene.settings, size),
            size,
            guess: None,
            broken: false,
            x: (u32::MAX, 0),
            y: (u32::MAX, 0),
        }
    }

    /// Takes in one logged ray: a primary ray's direction tells a size.
    pub(super) fn see(&mut self, ray: &LoggedRay) {
        if self.broken || !ray.path.steps.is_empty() {
            return;
        }
        let Some(dir) = ray.dir else { return };
        match self.size_of(ray.pixel, dir) {
            Some(size) if size != self.size && self.guess.is_none_or(|g| g == size) => {
                self.guess = Some(size);
                let (x, y) = ray.pixel;
                self.x = (self.x.0.min(x), self.x.1.max(x));
                self.y = (self.y.0.min(y), self.y.1.max(y));
            }
            _ => self.broken = true,
        }
    }

    /// The image size, W' x H', whose pixel (x, y) has `dir` for its
    /// centre ray with our camera and field of view, if it is whole.
    fn size_of(&self, (x, y): (u32, u32), dir: DVec3) -> Option<(u32, u32)> {
        let (u, v) = self.viewport.image_point(dir)?;
        let (w, h) = (self.size.0 as f64, self.size.1 as f64);
        // py: (1 − 2 v / H) s = (1 − 2 (y + ½) / H') s; px likewise, with
        // the aspect W / H on either side.
        if v <= 0.0 {
            return None;
        }
        let h2 = h * (y as f64 + 0.5) / v;
        let w2 = 2.0 * (x as f64 + 0.5) - h2 * (2.0 * u - w) / h;
        let whole = |a: f64| {
            let r = a.round();
            ((a - r).abs() <= WHOLE && (1.0..=65536.0).contains(&r)).then_some(r as u32)
        };
        let size = (whole(w2)?, whole(h2)?);
        (x < size.0 && y < size.1).then_some(size)
    }

    /// The other size every primary ray fits, from two columns and two
    /// rows of pixels at least.
    pub(super) fn traced_at(&self) -> Option<(u32, u32)> {
        let spread = self.x.1 > self.x.0 && self.y.1 > self.y.0;
        (!self.broken && spread).then_some(self.guess?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raylog::rays_with_nodes;
    use raystep_engine::record::record_pixel;

    /// The primary rays of `pixels` of the ball scene traced at `size`,
    /// seen by a guess that reads them at the scene's own 11x11.
    fn guess(size: (u32, u32), pixels: &[(u32, u32)]) -> Option<(u32, u32)> {
        let (scene, _) = raystep_engine::test_scenes::ball();
        let traced = scene.clone().with_size(size.0, size.1).unwrap();
        let mut guess = SizeGuess::new(&scene);
        for &(x, y) in pixels {
            let tree = record_pixel(&traced, &traced.settings, x, y);
            let (primary, _) = rays_with_nodes(&tree).into_iter().next().unwrap();
            guess.see(&primary);
        }
        guess.traced_at()
    }

    #[test]
    fn primary_rays_of_another_size_tell_it_from_two_rows_and_columns() {
        assert_eq!(guess((16, 12), &[(0, 0), (15, 11), (3, 7)]), Some((16, 12)));
        assert_eq!(guess((33, 5), &[(30, 1), (2, 4)]), Some((33, 5)));
        // One row, or one pixel, does not tell; the scene's own size is
        // no trap, and a log of mixed sizes has no one size.
        assert_eq!(guess((16, 12), &[(0, 3), (9, 3)]), None);
        assert_eq!(guess((11, 11), &[(0, 0), (10, 10)]), None);
        let (scene, _) = raystep_engine::test_scenes::ball();
        let mut mixed = SizeGuess::new(&scene);
        for (size, pixel) in [((16, 12), (0, 0)), ((20, 12), (5, 5))] {
            let traced = scene.clone().with_size(size.0, size.1).unwrap();
            let tree = record_pixel(&traced, &traced.settings, pixel.0, pixel.1);
            mixed.see(&rays_with_nodes(&tree)[0].0);
        }
        assert_eq!(mixed.traced_at(), None);
    }
}
