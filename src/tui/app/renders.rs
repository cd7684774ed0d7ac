//! The renders of the whole image: asking for one, following its progress,
//! and keeping what comes back (only the latest generation's).

use std::sync::Arc;
use std::time::Duration;

use image::RgbImage;

use crate::tui::render_job::{Finished, Output, Progress, Renderer, Request};
use raystep_engine::scene::{Scene, Settings};
use raystep_engine::terms::{Term, TermImages};

pub struct Renders {
    renderer: Renderer,
    /// Each change of the scene or settings is a new generation; results
    /// of older ones are dropped.
    generation: u64,
    /// The latest finished render (or preview), and the term images when a
    /// term picture asked for them.
    image: Option<RgbImage>,
    terms: Option<TermImages>,
    /// The generation the term images are of.
    terms_generation: Option<u64>,
    /// The term images' largest ray and cost counts, worked out once when
    /// they arrive: a redraw then costs the cells shown, not the image.
    count_max: (u32, u32),
    /// How long the last finished render took.
    render_time: Option<Duration>,
}

impl Renders {
    /// With `sync`, renders finish on the caller's thread (tests).
    pub(super) fn new(sync: bool) -> Renders {
        Renders {
            renderer: Renderer::new(sync),
            generation: 0,
            image: None,
            terms: None,
            terms_generation: None,
            count_max: (0, 0),
            render_time: None,
        }
    }

    /// Renders the scene as it is now, as a new generation (`terms`: every
    /// term image too).
    pub(super) fn request(&mut self, scene: Arc<Scene>, settings: Settings, terms: bool) {
        self.generation += 1;
        self.request_again(scene, settings, terms);
    }

    /// Renders the current generation again (a term picture needs the terms).
    pub(super) fn request_again(&mut self, scene: Arc<Scene>, settings: Settings, terms: bool) {
        self.renderer.request(Request {
            generation: self.generation,
            scene,
            settings,
            terms,
        });
    }

    /// Whether the term images are of the current generation.
    pub(super) fn terms_are_current(&self) -> bool {
        self.terms_generation == Some(self.generation)
    }

    /// Takes in the previews and renders that came back; why the last one
    /// failed, if it did.
    pub(super) fn collect(&mut self) -> Option<String> {
        while let Some(preview) = self.renderer.poll_preview() {
            if preview.generation == self.generation {
                self.image = Some(preview.image);
            }
        }
        let mut failed = None;
        while let Some(finished) = self.renderer.poll() {
            if let Err(message) = self.install(finished) {
                failed = Some(message);
            }
        }
        failed
    }

    fn install(&mut self, finished: Finished) -> Result<(), String> {
        if finished.generation != self.generation
            || matches!(finished.output, Ok(Output::Cancelled))
        {
            return Ok(());
        }
        self.render_time = Some(finished.elapsed);
        match finished.output? {
            Output::Image(image) => self.image = Some(image),
            Output::Terms(terms) => {
                self.image = Some(terms.color_image());
                self.count_max = (terms.max_count(Term::Rays), terms.max_count(Term::Cost));
                self.terms = Some(terms);
                self.terms_generation = Some(finished.generation);
            }
            Output::Cancelled => {} // dropped above
        }
        Ok(())
    }

    /// Stops every render at once (on quit: nothing waits for them).
    pub(super) fn cancel(&mut self) {
        self.renderer.cancel();
    }

    /// Whether a render is under way.
    pub(crate) fn busy(&self) -> bool {
        self.renderer.busy()
    }

    /// How far the running render is.
    pub(crate) fn progress(&self) -> Option<Progress> {
        self.renderer.progress()
    }

    /// The latest render (or preview) of the current settings.
    pub fn image(&self) -> Option<&RgbImage> {
        self.image.as_ref()
    }

    /// The term images, once a term picture asked for them.
    pub fn terms(&self) -> Option<&TermImages> {
        self.terms.as_ref()
    }

    /// The scale of a count picture (rays or cost): its largest count, as
    /// `TermImages::max_count` has it, but without a scan of the image.
    pub fn count_max(&self, term: Term) -> u32 {
        match term {
            Term::Rays => self.count_max.0,
            _ => self.count_max.1,
        }
    }

    /// How long the last finished render took.
    pub fn render_time(&self) -> Option<Duration> {
        self.render_time
    }
}

#[cfg(test)]
mod tests {
    use std::collections::VecDeque;
    use std::time::{Duration, Instant};

    use ratatui::Terminal;
    use ratatui::backend::TestBackend;

    use super::*;
    use crate::tui::source::SceneSource;
    use crate::tui::{Action, App, run_loop};

    #[test]
    fn quitting_cancels_a_long_render_instead_of_waiting_for_it() {
        // 4000 x 3000 = 12 million pixels: seconds of work on this machine,
        // against a row (4000 pixels, about a millisecond) once cancelled.
        let source = SceneSource {
            path: None,
            size: None,
        };
        let big = source.load().unwrap().with_size(4000, 3000).unwrap();
        let mut app = App::new(source, big, None, false);
        let deadline = Instant::now() + Duration::from_secs(30);
        while !app
            .renders()
            .progress()
            .is_some_and(|p| p.rows == 3000 && p.rows_done > 0)
        {
            assert!(Instant::now() < deadline, "the big render never started");
            app.update(Action::Tick);
            std::thread::sleep(Duration::from_millis(5));
        }
        let mut terminal = Terminal::new(TestBackend::new(120, 40)).unwrap();
        // No scripted events: the loop is asked to quit at once.
        run_loop(&mut terminal, &mut app, &mut VecDeque::new()).unwrap();
        let quit = Instant::now();
        let finished = app
            .renders
            .renderer
            .wait()
            .expect("the big render was running");
        assert!(matches!(finished.output, Ok(Output::Cancelled)));
        assert!(
            quit.elapsed() < Duration::from_secs(5),
            "{:?}",
            quit.elapsed()
        );
    }
}
