//! Reaching any pixel: the go-to prompt (`:` then `X,Y`), finding the next
//! pixel across the image (`f` then a key), and `--pixel` at the start.

use std::time::Instant;

use super::App;
use crate::record::record_pixel;
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

    /// The cursor to the next pixel in reading order whose recording has
    /// `what`, its first such event current; at most the whole image is
    /// scanned, one `record_pixel` each.
    pub(super) fn find(&mut self, what: Find) {
        self.finding = false;
        let object = match what {
            Find::BreakObject => match self.break_target() {
                Some(object) => {
                    self.break_object = Some(object);
                    object
                }
                None => {
                    self.message =
                        Some("no breakpoint object: press X to choose one, then f x".into());
                    return;
                }
            },
            _ => 0,
        };
        let started = Instant::now();
        let size = (self.scene.width, self.scene.height);
        let found = find::reading_order(self.cursor, size).find_map(|(x, y)| {
            let tree = record_pixel(&self.scene, &self.settings, x, y);
            let event = find::first_event(&tree, &self.scene, &self.settings, what, object)?;
            Some(((x, y), tree, event))
        });
        let what_text = match what {
            Find::BreakObject => format!("a hit on {}", self.scene.object_name(object)),
            _ => what.what().to_string(),
        };
        let Some(((x, y), tree, event)) = found else {
            self.message = Some(format!("none in the image: no pixel has {what_text}"));
            return;
        };
        let wrapped = (y, x) <= (self.cursor.1, self.cursor.0);
        self.cursor = (x, y);
        self.tree = tree;
        self.pick_time = started.elapsed();
        self.current = event;
        self.collapsed.clear();
        self.details_scroll = None;
        let from_top = if wrapped { ", from the top again" } else { "" };
        self.message = Some(format!("pixel ({x}, {y}) has {what_text}{from_top}"));
    }
}
