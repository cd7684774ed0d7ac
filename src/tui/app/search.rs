//! A find across the image under way (`f` then a key): the background job,
//! and what the status line and the result say about it.

use std::time::Instant;

use crate::tui::action::Find;
use crate::tui::find_job::{FindJob, Found};
use raystep_engine::record::NEAR_MISS_SCENE_LIMIT;

use super::pixel::TracedPixel;
use super::session::Session;

pub(crate) struct Search {
    job: FindJob,
    /// "a total internal reflection", "a hit on glass" ...
    what: String,
    /// The cursor when the find started (the result says if it wrapped).
    from: (u32, u32),
    started: Instant,
}

impl Search {
    /// Looks for the next pixel after the cursor whose recording has
    /// `find` (its first such event current when found). The `x` object, when
    /// the find needs one, becomes the breakpoint object; why not, when
    /// there is nothing to look for.
    pub(super) fn start(
        find: Find,
        pixel: &mut TracedPixel,
        session: &Session,
        sync: bool,
    ) -> Result<Search, String> {
        let scene = session.scene();
        let object = match find {
            Find::BreakObject => Some(
                pixel
                    .choose_break_target()
                    .ok_or("no breakpoint object: press X to choose one, then f x".to_string())?,
            ),
            Find::NearMiss if scene.objects.len() > NEAR_MISS_SCENE_LIMIT => {
                // Not recorded on big scenes: "none in the image" would mislead.
                return Err(format!(
                    "near misses are recorded only in scenes of at most {NEAR_MISS_SCENE_LIMIT} objects; this one has {}",
                    scene.objects.len()
                ));
            }
            Find::NearMiss => pixel.break_object(),
            _ => None,
        };
        let what = match (find, object) {
            (Find::BreakObject, Some(object)) => format!("a hit on {}", scene.object_name(object)),
            (Find::NearMiss, Some(object)) => {
                format!("a near miss of {}", scene.object_name(object))
            }
            _ => find.what().to_string(),
        };
        let from = pixel.cursor();
        let job = (session.shared_scene(), *session.settings());
        Ok(Search {
            job: FindJob::start(job.0, job.1, (find, object), from, sync),
            what,
            from,
            started: Instant::now(),
        })
    }

    /// What it looks for and the row it is on, from 0.
    pub(crate) fn progress(&self) -> (&str, u32) {
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
