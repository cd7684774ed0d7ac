//! Terminal events become `Action`s here and nowhere else. Which input means
//! what comes from the one table in `keymap.rs`; this file only decides what
//! a command does in the pane it acts on.

use crossterm::event::{Event, KeyCode, KeyEvent, KeyEventKind, MouseButton, MouseEventKind};

use super::action::{Action, Pane};
use super::app::App;
use super::keymap::{self, Command, Input, Mode};
use raystep_engine::record::stepping::Step;

/// The action for a terminal event, if it means one.
pub fn action(event: &Event, app: &App) -> Option<Action> {
    match event {
        Event::Key(key) if key.kind != KeyEventKind::Release => {
            key_action(key, app.overlay().mode(), app.screen().focus())
        }
        Event::Mouse(mouse) => {
            let input = match mouse.kind {
                MouseEventKind::Down(MouseButton::Left) => Input::Click,
                MouseEventKind::ScrollUp => Input::WheelUp,
                MouseEventKind::ScrollDown => Input::WheelDown,
                _ => return None,
            };
            match keymap::mouse_command(input, app.overlay().mode())? {
                Command::Click => Some(Action::Click(mouse.column, mouse.row)),
                command => in_pane(command, app.panes().pane_at(mouse.column, mouse.row)?),
            }
        }
        Event::Resize(width, height) => Some(Action::Resize(*width, *height)),
        _ => None,
    }
}

/// A key's action in `mode` (help or menu open or not) with `focus` the
/// focused pane.
pub(crate) fn key_action(key: &KeyEvent, mode: Mode, focus: Pane) -> Option<Action> {
    match (keymap::key_command(key, mode)?, key.code) {
        (Command::Type, KeyCode::Char(c)) => Some(Action::PromptChar(c)),
        (Command::Type, _) => None,
        (command, _) => in_pane(command, focus),
    }
}

/// What `command` does in `pane` (the focused one for keys, the one under
/// the mouse for the wheel).
fn in_pane(command: Command, pane: Pane) -> Option<Action> {
    let step = |d: i32| Action::Step(if d > 0 { Step::Next } else { Step::Previous });
    Some(match (command, pane) {
        (Command::Do(action), _) => action,
        (Command::Arrow(0, dy), Pane::Tree) => Action::SelectRow(dy),
        (Command::Arrow(..), Pane::Tree) => Action::ToggleCollapse,
        (Command::Arrow(d, 0) | Command::Arrow(0, d), Pane::Steps) => step(d),
        (Command::Arrow(0, dy), Pane::Details) => Action::ScrollDetails(dy),
        (Command::Arrow(dx, dy), Pane::Diagram) => Action::PanDiagram(dx, dy),
        (Command::Arrow(dx, dy), _) => Action::Move(dx, dy),
        (Command::Home, Pane::Diagram) => Action::FitDiagram,
        (Command::Home, _) => Action::Step(Step::Start),
        (Command::Zoom(d), Pane::Diagram) => Action::ZoomDiagram(d),
        (Command::Zoom(d), _) if d > 0 => Action::ZoomIn,
        (Command::Zoom(_), _) => Action::ZoomOut,
        (Command::Page(lines), Pane::Details) => Action::ScrollDetails(lines),
        (Command::Wheel(d), Pane::Steps) => step(d),
        (Command::Wheel(d), Pane::Tree) => Action::SelectRow(d),
        (Command::Wheel(d), Pane::Details) => Action::ScrollDetails(3 * d),
        (Command::Wheel(d), Pane::Diagram) => Action::ZoomDiagram(-d),
        (Command::Wheel(d), Pane::Image) if d < 0 => Action::ZoomIn,
        (Command::Wheel(_), Pane::Image) => Action::ZoomOut,
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    //! What every key does in every mode and pane is pinned by the key
    //! table's snapshot (`tests/suite/tui_screens.rs`, `tui_screens__key_table`).

    use crossterm::event::KeyModifiers;

    use super::*;

    #[test]
    fn the_mistakes_menu_has_the_keys_while_open() {
        let key = |code| KeyEvent::new(code, KeyModifiers::NONE);
        let menu = |code| key_action(&key(code), Mode::Menu, Pane::Image);
        assert_eq!(menu(KeyCode::Down), Some(Action::MenuMove(1)));
        assert_eq!(menu(KeyCode::Char('k')), Some(Action::MenuMove(-1)));
        assert_eq!(menu(KeyCode::Char(' ')), Some(Action::MenuToggle));
        assert_eq!(menu(KeyCode::Enter), Some(Action::MenuToggle));
        assert_eq!(menu(KeyCode::Esc), Some(Action::CloseMistakeMenu));
        assert_eq!(menu(KeyCode::Char('M')), Some(Action::ToggleMistakeMenu));
        // The panes' keys wait until the menu closes.
        assert_eq!(menu(KeyCode::Char('s')), None);
        assert_eq!(menu(KeyCode::Char('q')), None);
    }

    #[test]
    fn a_key_the_table_does_not_name_does_nothing() {
        let f5 = KeyEvent::new(KeyCode::F(5), KeyModifiers::NONE);
        for pane in Pane::ALL {
            assert_eq!(key_action(&f5, Mode::Browsing, pane), None);
            assert_eq!(key_action(&f5, Mode::Menu, pane), None);
        }
        // Typed into the prompt, a key that is no character is dropped.
        assert_eq!(key_action(&f5, Mode::Prompt, Pane::Image), None);
    }
}
