//! Reaching any pixel: the go-to prompt (`:` then `X,Y`), finding the next
//! pixel across the image (`f` then a key), and `--pixel` at the start.

use std::time::Instant;

use super::App;
use crate::record::NEAR_MISS_SCENE_LIMIT;
use crate::tui::find_job::FindJob;
use crate::tui::view::find::{self, Find};

impl App {
    /// The app on `pixel` instead of the centre (`--pixel X,Y`); refused
    /// when the pixel is outside the image.
    pub fn at_pixel(mut self, pixel: (u32, u32)) -> Result<App, String> {
        let size = (self.scene.width, self.scene.height);
        if pixel.0 >= size.0 || pixel.1 >= size.1 {
            return Err(find::outside(pixel, size));
        }
        self.pick(pixel.0, pixel.1);
        Ok(self)
    }

    /// The go-to prompt's text while it is open.
    pub fn prompt(&self) -> Option<&str> {
        self.prompt.as_deref()
    }

    /// Whether `f` waits for the key that says what to find.
    pub fn finding(&self) -> bool {
        self.finding
    }

    pub(super) fn prompt_char(&mut self, c: char) {
        if let Some(text) = &mut self.prompt {
            text.push(c);
        }
    }

    pub(super) fn prompt_backspace(&mut self) {
        if let Some(text) = &mut self.prompt {
            text.pop();
        }
    }

    /// Enter: go to the pixel typed, or say why not and keep the prompt
    /// open so the text can be corrected.
    pub(super) fn prompt_submit(&mut self) {
        let Some(text) = self.prompt.clone() else {
            return;
        };
        match find::parse_goto(&text, (self.scene.width, self.scene.height)) {
            Ok((x, y)) => {
                self.prompt = None;
                self.pick(x, y);
                self.message = Some(format!("went to pixel ({x}, {y})"));
            }
            Err(why) => self.message = Some(why),
        }
    }

    /// Starts looking for the next pixel in reading order whose recording
    /// has `what` (its first such event current when found), in the
    /// background: a pick, a toggle, another find or quitting cancels it.
    pub(super) fn find(&mut self, what: Find) {
        self.finding = false;
        self.cancel_find();
        let object = match what {
            Find::BreakObject => match self.break_target() {
                Some(object) => {
                    self.break_object = Some(object);
                    Some(object)
                }
                None => {
                    self.message =
                        Some("no breakpoint object: press X to choose one, then f x".into());
                    return;
                }
            },
            Find::NearMiss if self.scene.objects.len() > NEAR_MISS_SCENE_LIMIT => {
                // Not recorded on big scenes: "none in the image" would mislead.
                self.message = Some(format!(
                    "near misses are recorded only in scenes of at most {NEAR_MISS_SCENE_LIMIT} objects; this one has {}",
                    self.scene.objects.len()
                ));
                return;
            }
            Find::NearMiss => self.break_object,
            _ => None,
        };
        let what_text = match (what, object) {
            (Find::BreakObject, Some(object)) => {
                format!("a hit on {}", self.scene.object_name(object))
            }
            (Find::NearMiss, Some(object)) => {
                format!("a near miss of {}", self.scene.object_name(object))
            }
            _ => what.what().to_string(),
        };
        let job = FindJob::start(
            self.scene.clone(),
            self.settings,
            (what, object),
            self.cursor,
            self.sync,
        );
        self.searching = Some(Searching {
            job,
            what: what_text,
            from: self.cursor,
            started: Instant::now(),
        });
    }

    /// What the running find looks for and the row it is on (from 1), of
    /// the image's rows: "finding {what}… (row N of H)".
    pub fn finding_progress(&self) -> Option<(&str, u32, u32)> {
        let searching = self.searching.as_ref()?;
        Some((&searching.what, searching.job.row() + 1, self.scene.height))
    }

    /// Drops the running find, if any: its result can no longer arrive.
    pub(super) fn cancel_find(&mut self) {
        self.searching = None;
    }

    /// Takes in the running find's result once it has one.
    pub(super) fn collect_find(&mut self) {
        let Some(searching) = &self.searching else {
            return;
        };
        let Some(found) = searching.job.poll() else {
            return;
        };
        let Some(Searching {
            what,
            from,
            started,
            ..
        }) = self.searching.take()
        else {
            return;
        };
        let Some(found) = found else {
            self.message = Some(format!("none in the image: no pixel has {what}"));
            return;
        };
        let (x, y) = found.pixel;
        let wrapped = (y, x) <= (from.1, from.0);
        self.cursor = (x, y);
        self.tree = found.tree;
        self.pick_time = started.elapsed();
        self.current = found.event;
        self.what_if = None;
        self.collapsed.clear();
        self.details_scroll = None;
        let from_top = if wrapped { ", from the top again" } else { "" };
        self.message = Some(format!("pixel ({x}, {y}) has {what}{from_top}"));
    }
}

/// A find under way: the job, and what the status line and the result say.
pub(super) struct Searching {
    job: FindJob,
    /// "a total internal reflection", "a hit on glass" ...
    what: String,
    /// The cursor when the find started (the result says if it wrapped).
    from: (u32, u32),
    started: Instant,
}
