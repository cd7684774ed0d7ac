//! The classic mistakes as switches: the `M` menu's selection and turning
//! one on or off, which retraces the pixel and re-renders like the other
//! teaching toggles.

use super::App;
use crate::mistakes::Mistake;

impl App {
    pub(super) fn menu_move(&mut self, delta: i32) {
        let last = Mistake::ALL.len() as i64 - 1;
        self.menu_row = (self.menu_row as i64 + delta as i64).clamp(0, last) as usize;
    }

    pub(super) fn toggle_mistake(&mut self, mistake: Mistake) {
        let mut settings = self.settings;
        settings.mistakes = settings.mistakes.toggled(mistake);
        let state = if settings.mistakes.contains(mistake) {
            "on"
        } else {
            "off"
        };
        self.apply_settings(settings);
        self.message = Some(format!("mistake {mistake} {state}"));
    }
}
