//! The app's side of background renders: asking for one, following its
//! progress, and installing what comes back (only the latest generation).

use super::{App, View};
use crate::terms::Term;
use crate::tui::job::{Finished, Output, Progress, Request};

impl App {
    /// Whether a render is under way (the loop then polls more often).
    pub fn busy(&self) -> bool {
        self.renderer.busy() || self.reload_due.is_some() || self.searching.is_some()
    }

    pub fn progress(&self) -> Option<Progress> {
        self.renderer.progress()
    }

    /// Stops every render at once (on quit: nothing waits for them).
    pub(super) fn cancel_renders(&mut self) {
        self.renderer.cancel();
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
            settings: self.settings,
            terms,
        });
    }

    /// Takes in the previews and renders that came back.
    pub(super) fn collect_renders(&mut self) {
        while let Some(preview) = self.renderer.poll_preview() {
            if preview.generation == self.generation {
                self.image = Some(preview.image);
            }
        }
        while let Some(finished) = self.renderer.poll() {
            self.install(finished);
        }
    }

    fn install(&mut self, finished: Finished) {
        if finished.generation != self.generation
            || matches!(finished.output, Ok(Output::Cancelled))
        {
            return;
        }
        self.render_time = Some(finished.elapsed);
        match finished.output {
            Ok(Output::Image(image)) => self.image = Some(image),
            Ok(Output::Terms(terms)) => {
                self.image = Some(terms.color_image());
                self.count_max = (terms.max_count(Term::Rays), terms.max_count(Term::Cost));
                self.terms = Some(terms);
                self.terms_generation = Some(finished.generation);
            }
            Ok(Output::Cancelled) => {} // dropped above
            Err(message) => self.message = Some(message),
        }
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
    use crate::tui::{Action, run_loop};

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
        let finished = app.renderer.wait().expect("the big render was running");
        assert!(matches!(finished.output, Ok(Output::Cancelled)));
        assert!(
            quit.elapsed() < Duration::from_secs(5),
            "{:?}",
            quit.elapsed()
        );
    }
}
