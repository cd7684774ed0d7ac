//! The app's side of background renders: asking for one, following its
//! progress, and installing what comes back (only the latest generation).

use image::RgbImage;

use crate::math::to_rgb8;

use super::app::{App, View};
use super::job::{Finished, Output, Progress, Request};

impl App {
    /// Whether a render is under way (the loop then polls more often).
    pub fn busy(&self) -> bool {
        self.renderer.busy() || self.reload_due.is_some()
    }

    pub fn progress(&self) -> Option<Progress> {
        self.renderer.progress()
    }

    /// Blocks until every requested render is in (benchmarks and tests).
    pub fn wait_for_renders(&mut self) {
        while let Some(finished) = self.renderer.wait() {
            self.install(finished);
        }
    }

    /// Renders the scene as it is now, as a new generation.
    pub(super) fn request_render(&mut self) {
        self.generation += 1;
        self.request_current();
    }

    /// Renders the current generation again (a term view needs the terms).
    pub(super) fn request_current(&mut self) {
        let terms = matches!(self.view, View::Term(_));
        self.renderer.request(Request {
            generation: self.generation,
            scene: self.scene.clone(),
            terms,
        });
    }

    pub(super) fn collect_renders(&mut self) -> bool {
        let mut any = false;
        while let Some(preview) = self.renderer.poll_preview() {
            if preview.generation == self.generation {
                self.image = Some(preview.image);
                any = true;
            }
        }
        while let Some(finished) = self.renderer.poll() {
            self.install(finished);
            any = true;
        }
        any
    }

    fn install(&mut self, finished: Finished) {
        if finished.generation != self.generation {
            return;
        }
        self.render_time = Some(finished.elapsed);
        match finished.output {
            Ok(Output::Image(image)) => self.image = Some(image),
            Ok(Output::Terms(terms)) => {
                self.image = Some(RgbImage::from_fn(terms.width, terms.height, |x, y| {
                    image::Rgb(to_rgb8(terms.pixels[(y * terms.width + x) as usize].color))
                }));
                self.terms = Some(terms);
                self.terms_generation = Some(finished.generation);
            }
            Err(message) => self.message = Some(message),
        }
    }
}
