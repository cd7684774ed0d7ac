//! A find across the image under way (`f` then a key): the background job,
//! and what the status line and the result say about it.

use std::sync::Arc;
use std::time::Instant;

use crate::scene::{Scene, Settings};
use crate::tui::action::Find;
use crate::tui::find_job::{FindJob, Found};

pub struct Search {
    job: FindJob,
    /// "a total internal reflection", "a hit on glass" ...
    what: String,
    /// The cursor when the find started (the result says if it wrapped).
    from: (u32, u32),
    started: Instant,
}

impl Search {
    /// Looks for the next pixel after `from` whose recording has `find`
    /// (of `object`, see `find::first_event`), said as `what`.
    pub(super) fn start(
        (scene, settings): (Arc<Scene>, Settings),
        (find, object): (Find, Option<usize>),
        what: String,
        from: (u32, u32),
        sync: bool,
    ) -> Search {
        Search {
            job: FindJob::start(scene, settings, (find, object), from, sync),
            what,
            from,
            started: Instant::now(),
        }
    }

    /// What it looks for and the row it is on, from 0.
    pub fn progress(&self) -> (&str, u32) {
        (&self.what, self.job.row())
    }

    /// `Some` once the scan has ended: the pixel found, or `None`.
    pub(super) fn poll(&self) -> Option<Option<Found>> {
        self.job.poll()
    }

    /// What the status line says of the scan's result.
    pub(super) fn result_message(&self, found: Option<(u32, u32)>) -> String {
        let what = &self.what;
        let Some((x, y)) = found else {
            return format!("none in the image: no pixel has {what}");
        };
        let wrapped = (y, x) <= (self.from.1, self.from.0);
        let from_top = if wrapped { ", from the top again" } else { "" };
        format!("pixel ({x}, {y}) has {what}{from_top}")
    }

    /// How long the scan took, for the pick's time.
    pub(super) fn elapsed(&self) -> std::time::Duration {
        self.started.elapsed()
    }
}
