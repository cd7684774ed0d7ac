//! What is open over the panes and has the keys: the help, the mistakes
//! menu, the go-to prompt or the wait for `f`'s second key. One at a time,
//! by type: opening one closes the other.

use crate::tui::action::Action;
use crate::tui::keymap::Mode;
use crate::tui::view::help;
use raystep_model::mistakes::Mistake;

/// The one thing open over the panes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Overlay {
    /// The `?` help, scrolled by this many lines.
    Help { scroll: u16 },
    /// The `M` menu of classic mistakes.
    MistakesMenu,
    /// The go-to prompt (`:`) in the status line, with the text typed.
    Prompt(String),
    /// `f` was pressed: the next key says what to find.
    Find,
}

/// The overlay open, if any, the mistakes menu's rows and its selected
/// row, which stays between openings.
#[derive(Debug)]
pub struct Overlays {
    open: Option<Overlay>,
    /// The menu's mistakes in its order: every one the scene's profile
    /// offers once (`Profile::offers`).
    menu: Vec<Mistake>,
    /// An index into `menu`.
    menu_row: usize,
}

impl Default for Overlays {
    /// The menu in the catalogue's order (the lecture's: all of it).
    fn default() -> Overlays {
        Overlays::with_menu(Mistake::ALL.to_vec())
    }
}

/// What `f` asks for in the status line.
const FIND_WHAT: &str = "find the next pixel with: b blocked shadow, p partly blocked, t TIR, D depth limit, x object X, n near miss";

impl Overlays {
    /// Nothing open; the menu lists `menu` (every offered mistake once,
    /// e.g. the ranked ones first) and opens on its first row.
    pub(super) fn with_menu(menu: Vec<Mistake>) -> Overlays {
        Overlays {
            open: None,
            menu,
            menu_row: 0,
        }
    }

    /// The menu's rows replaced (a reload changed the profile): the
    /// selected mistake stays selected if it is still there, else the
    /// first row is.
    pub(super) fn set_menu(&mut self, menu: Vec<Mistake>) {
        let selected = self.menu.get(self.menu_row).copied();
        self.menu = menu;
        self.menu_row = 0;
        if let Some(mistake) = selected {
            self.select(mistake);
        }
    }

    /// Opens, closes, scrolls, moves or types into an overlay; the status
    /// line's message, when the action has one. `screen_height` bounds the
    /// help's scroll.
    pub(super) fn update(&mut self, action: Action, screen_height: u16) -> Option<String> {
        match (action, &mut self.open) {
            (Action::ToggleHelp, Some(Overlay::Help { .. })) => self.open = None,
            (Action::ToggleHelp, _) => self.open = Some(Overlay::Help { scroll: 0 }),
            (Action::CloseHelp, Some(Overlay::Help { .. })) => self.open = None,
            (Action::ScrollHelp(delta), Some(Overlay::Help { scroll })) => {
                let most = help::hidden_lines(screen_height) as i32;
                *scroll = (*scroll as i32 + delta).clamp(0, most) as u16;
            }
            (Action::ToggleMistakeMenu, Some(Overlay::MistakesMenu)) => self.open = None,
            (Action::ToggleMistakeMenu, _) => self.open = Some(Overlay::MistakesMenu),
            (Action::CloseMistakeMenu, Some(Overlay::MistakesMenu)) => self.open = None,
            (Action::MenuMove(delta), _) => {
                // Wraps: up from the first row is the last.
                let rows = self.menu.len().max(1) as i64;
                self.menu_row = (self.menu_row as i64 + delta as i64).rem_euclid(rows) as usize;
            }
            (Action::OpenPrompt, _) => self.open = Some(Overlay::Prompt(String::new())),
            (Action::PromptChar(c), Some(Overlay::Prompt(text))) => text.push(c),
            (Action::PromptBackspace, Some(Overlay::Prompt(text))) => {
                text.pop();
            }
            (Action::PromptCancel, Some(Overlay::Prompt(_))) => self.open = None,
            (Action::StartFind, _) => {
                self.open = Some(Overlay::Find);
                return Some(FIND_WHAT.into());
            }
            (Action::CancelFind | Action::Find(_), Some(Overlay::Find)) => self.open = None,
            _ => {}
        }
        None
    }

    /// Closes whatever is open (the prompt, once its pixel is gone to).
    pub(super) fn close(&mut self) {
        self.open = None;
    }

    /// What is open over the panes, if anything.
    pub(crate) fn open(&self) -> Option<&Overlay> {
        self.open.as_ref()
    }

    /// What has the keys: the overlay open, else the panes.
    pub fn mode(&self) -> Mode {
        match self.open {
            None => Mode::Browsing,
            Some(Overlay::Help { .. }) => Mode::Help,
            Some(Overlay::MistakesMenu) => Mode::Menu,
            Some(Overlay::Prompt(_)) => Mode::Prompt,
            Some(Overlay::Find) => Mode::Find,
        }
    }

    /// Selects `mistake`'s row of the menu (where it opens next).
    pub(super) fn select(&mut self, mistake: Mistake) {
        if let Some(row) = self.menu.iter().position(|&m| m == mistake) {
            self.menu_row = row;
        }
    }

    /// The mistakes menu's selected mistake, open or not.
    pub(crate) fn menu_mistake(&self) -> Mistake {
        self.menu[self.menu_row]
    }

    /// The mistakes menu's rows, in order.
    pub fn menu_mistakes(&self) -> &[Mistake] {
        &self.menu
    }

    /// The menu's selected row when it is open.
    pub fn menu_row(&self) -> Option<usize> {
        (self.open == Some(Overlay::MistakesMenu)).then_some(self.menu_row)
    }

    /// The prompt's text while it is open.
    pub fn prompt(&self) -> Option<&str> {
        match &self.open {
            Some(Overlay::Prompt(text)) => Some(text),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_overlay_at_a_time() {
        // Before the overlay was one value, help and menu were two flags:
        // the menu opened under the help, which kept the keys (Mode::Help)
        // and, once closed, left the menu open.
        let mut overlays = Overlays::default();
        overlays.update(Action::ToggleHelp, 40);
        assert_eq!(overlays.mode(), Mode::Help);
        overlays.update(Action::ToggleMistakeMenu, 40);
        assert_eq!(overlays.open(), Some(&Overlay::MistakesMenu));
        assert_eq!(overlays.mode(), Mode::Menu);
        overlays.update(Action::CloseHelp, 40);
        assert_eq!(overlays.mode(), Mode::Menu, "no help was open to close");
        overlays.update(Action::OpenPrompt, 40);
        assert_eq!(overlays.prompt(), Some(""));
        assert_eq!(overlays.menu_row(), None, "the prompt closed the menu");
        overlays.update(Action::StartFind, 40);
        assert_eq!(overlays.mode(), Mode::Find);
        assert_eq!(overlays.prompt(), None, "f closed the prompt");
    }

    #[test]
    fn the_menu_keeps_its_row_between_openings() {
        let mut overlays = Overlays::default();
        overlays.update(Action::ToggleMistakeMenu, 40);
        overlays.update(Action::MenuMove(3), 40);
        overlays.update(Action::CloseMistakeMenu, 40);
        assert_eq!(overlays.menu_row(), None);
        overlays.update(Action::ToggleMistakeMenu, 40);
        assert_eq!(overlays.menu_row(), Some(3));
        assert_eq!(overlays.menu_mistake(), Mistake::ALL[3]);
    }

    #[test]
    fn a_new_menu_keeps_the_selected_mistake_if_it_is_still_offered() {
        let mut overlays = Overlays::default();
        overlays.update(Action::MenuMove(3), 40);
        assert_eq!(overlays.menu_mistake(), Mistake::TirDropped);
        let without = |gone: Mistake| -> Vec<Mistake> {
            Mistake::ALL.into_iter().filter(|&m| m != gone).collect()
        };
        // tir-dropped is gone: the first row.
        overlays.set_menu(without(Mistake::TirDropped));
        assert_eq!(overlays.menu_mistake(), Mistake::ShadowAcne);
        overlays.update(Action::MenuMove(4), 40);
        assert_eq!(overlays.menu_mistake(), Mistake::OpaqueShadows);
        // opaque-shadows is row 5 of the whole catalogue, and still there.
        overlays.set_menu(Mistake::ALL.to_vec());
        assert_eq!(overlays.menu_mistake(), Mistake::OpaqueShadows);
        assert_eq!(overlays.menu_mistakes()[5], Mistake::OpaqueShadows);
    }
}
