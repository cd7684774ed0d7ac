//! Terminal events become `Action`s here and nowhere else. Which input means
//! what comes from the one table in `keymap.rs`; this file only decides what
//! a command does in the pane it acts on.

use crossterm::event::{Event, KeyCode, KeyEvent, KeyEventKind, MouseButton, MouseEventKind};

use super::app::{Action, App};
use super::keymap::{self, Command, Input, Mode};
use super::view::layout::Pane;
use super::view::stepper::Step;

/// The action for a terminal event, if it means one.
pub fn action(event: &Event, app: &App) -> Option<Action> {
    match event {
        Event::Key(key) if key.kind != KeyEventKind::Release => {
            key_action(key, app.mode(), app.focus())
        }
        Event::Mouse(mouse) => {
            let input = match mouse.kind {
                MouseEventKind::Down(MouseButton::Left) => Input::Click,
                MouseEventKind::ScrollUp => Input::WheelUp,
                MouseEventKind::ScrollDown => Input::WheelDown,
                _ => return None,
            };
            match keymap::mouse_command(input, app.mode())? {
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
pub fn key_action(key: &KeyEvent, mode: Mode, focus: Pane) -> Option<Action> {
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
    //! The dispatch before the table (commit fc0f12c), kept as the oracle:
    //! every key, modifier, pane and help state must still do what it did.
    //! Since then: `M` (the mistakes menu), `w` (next region), `:` (go to)
    //! and `f` (find across the image) are new, and Ctrl+Z (suspend), help
    //! open or not; with the diagram focused,
    //! the arrows pan it and + - and the wheel zoom it, and `0` fits it
    //! (as does Home there: `since_then`).

    use crossterm::event::KeyModifiers;

    use super::*;
    use crate::scene::Switch;
    use crate::tui::view::stepper::Breakpoint;

    const BIG_STEP: i32 = 10;

    fn old_key_action(key: &KeyEvent, help: bool, focus: Pane) -> Option<Action> {
        let ctrl = key.modifiers.contains(KeyModifiers::CONTROL);
        if ctrl && key.code == KeyCode::Char('c') {
            return Some(Action::Quit);
        }
        if help {
            return Some(match key.code {
                KeyCode::Char('q') => Action::Quit,
                KeyCode::Down | KeyCode::Char('j') => Action::ScrollHelp(1),
                KeyCode::Up | KeyCode::Char('k') => Action::ScrollHelp(-1),
                _ => Action::CloseHelp,
            });
        }
        let shift = key.modifiers.contains(KeyModifiers::SHIFT);
        if let Some(action) = old_arrow_action(key.code, shift, focus) {
            return Some(action);
        }
        Some(match key.code {
            KeyCode::Char('q') | KeyCode::Esc => Action::Quit,
            KeyCode::Char('?') => Action::ToggleHelp,
            KeyCode::Tab => Action::FocusNext,
            KeyCode::BackTab => Action::FocusPrevious,
            KeyCode::Enter | KeyCode::Char(' ') => Action::ToggleCollapse,
            KeyCode::Char('+' | '=') => Action::ZoomIn,
            KeyCode::Char('-' | '_') => Action::ZoomOut,
            KeyCode::Char('H') => Action::Move(-BIG_STEP, 0),
            KeyCode::Char('L') => Action::Move(BIG_STEP, 0),
            KeyCode::Char('K') => Action::Move(0, -BIG_STEP),
            KeyCode::Char('J') => Action::Move(0, BIG_STEP),
            KeyCode::Char('n') => Action::Step(Step::Next),
            KeyCode::Char('p') => Action::Step(Step::Previous),
            KeyCode::Char('i') => Action::Step(Step::Into),
            KeyCode::Char('o') => Action::Step(Step::Over),
            KeyCode::Char('u') => Action::Step(Step::Out),
            KeyCode::Char('g') | KeyCode::Home => Action::Step(Step::Start),
            KeyCode::Char('e') | KeyCode::End => Action::Step(Step::End),
            KeyCode::Char('b') => Action::RunTo(Breakpoint::BlockedShadow),
            KeyCode::Char('x') => Action::RunToObject,
            KeyCode::Char('X') => Action::CycleBreakObject,
            KeyCode::Char('T') => Action::RunTo(Breakpoint::Tir),
            KeyCode::Char('s') => Action::Toggle(Switch::Shadows),
            KeyCode::Char('r') => Action::Toggle(Switch::Reflection),
            KeyCode::Char('t') => Action::Toggle(Switch::Transmission),
            KeyCode::Char('a') => Action::Toggle(Switch::Ambient),
            KeyCode::Char('m') => Action::ToggleSpecular,
            KeyCode::Char('[') => Action::Depth(-1),
            KeyCode::Char(']') => Action::Depth(1),
            KeyCode::Char('v') => Action::CycleView,
            KeyCode::Char('d') => Action::CyclePlane,
            KeyCode::Char('R') => Action::Reload,
            KeyCode::Char('M') => Action::ToggleMistakeMenu,
            KeyCode::Char('w') => Action::NextRegion,
            KeyCode::Char(':') => Action::OpenPrompt,
            KeyCode::Char('f') => Action::StartFind,
            KeyCode::PageDown if focus == Pane::Details => Action::ScrollDetails(10),
            KeyCode::PageUp if focus == Pane::Details => Action::ScrollDetails(-10),
            _ => return None,
        })
    }

    /// What changed since the oracle: Ctrl+Z suspends; `q` closes the help
    /// (a newcomer's guess, as in `less`); the diagram's pan and zoom.
    fn since_then(key: &KeyEvent, old: Option<Action>, help: bool, focus: Pane) -> Option<Action> {
        let code = key.code;
        if code == KeyCode::Char('z') && key.modifiers.contains(KeyModifiers::CONTROL) {
            return Some(Action::Suspend);
        }
        if help {
            return match code {
                KeyCode::Char('q') => Some(Action::CloseHelp),
                _ => old,
            };
        }
        if code == KeyCode::Char('0') && old.is_none() {
            return Some(Action::FitDiagram);
        }
        if focus != Pane::Diagram {
            return old;
        }
        if code == KeyCode::Home {
            return Some(Action::FitDiagram);
        }
        Some(match old? {
            Action::Move(dx, dy) if dx.abs() + dy.abs() == 1 => Action::PanDiagram(dx, dy),
            Action::ZoomIn => Action::ZoomDiagram(1),
            Action::ZoomOut => Action::ZoomDiagram(-1),
            other => other,
        })
    }

    fn old_arrow_action(code: KeyCode, shift: bool, focus: Pane) -> Option<Action> {
        let (dx, dy) = match code {
            KeyCode::Left | KeyCode::Char('h') => (-1, 0),
            KeyCode::Right | KeyCode::Char('l') => (1, 0),
            KeyCode::Up | KeyCode::Char('k') => (0, -1),
            KeyCode::Down | KeyCode::Char('j') => (0, 1),
            _ => return None,
        };
        if shift {
            return Some(Action::Move(dx * BIG_STEP, dy * BIG_STEP));
        }
        Some(match (focus, dx, dy) {
            (Pane::Tree, 0, dy) => Action::SelectRow(dy),
            (Pane::Tree, _, _) => Action::ToggleCollapse,
            (Pane::Steps, d, 0) | (Pane::Steps, 0, d) => {
                Action::Step(if d > 0 { Step::Next } else { Step::Previous })
            }
            (Pane::Details, 0, dy) => Action::ScrollDetails(dy),
            _ => Action::Move(dx, dy),
        })
    }

    fn old_wheel_action(kind: MouseEventKind, pane: Pane) -> Option<Action> {
        match (kind, pane) {
            (MouseEventKind::ScrollDown, Pane::Steps) => Some(Action::Step(Step::Next)),
            (MouseEventKind::ScrollUp, Pane::Steps) => Some(Action::Step(Step::Previous)),
            (MouseEventKind::ScrollDown, Pane::Tree) => Some(Action::SelectRow(1)),
            (MouseEventKind::ScrollUp, Pane::Tree) => Some(Action::SelectRow(-1)),
            (MouseEventKind::ScrollDown, Pane::Details) => Some(Action::ScrollDetails(3)),
            (MouseEventKind::ScrollUp, Pane::Details) => Some(Action::ScrollDetails(-3)),
            (MouseEventKind::ScrollUp, Pane::Image) => Some(Action::ZoomIn),
            // Since then: the wheel zooms the diagram too.
            (MouseEventKind::ScrollUp, Pane::Diagram) => Some(Action::ZoomDiagram(1)),
            (MouseEventKind::ScrollDown, Pane::Diagram) => Some(Action::ZoomDiagram(-1)),
            (MouseEventKind::ScrollDown, Pane::Image) => Some(Action::ZoomOut),
            _ => None,
        }
    }

    /// Every printable ASCII key, a non-ASCII one and every named key.
    fn all_codes() -> Vec<KeyCode> {
        let mut codes: Vec<KeyCode> = (' '..='~').chain(['é', 'ß']).map(KeyCode::Char).collect();
        codes.extend([
            KeyCode::Left,
            KeyCode::Right,
            KeyCode::Up,
            KeyCode::Down,
            KeyCode::Home,
            KeyCode::End,
            KeyCode::PageUp,
            KeyCode::PageDown,
            KeyCode::Tab,
            KeyCode::BackTab,
            KeyCode::Enter,
            KeyCode::Esc,
            KeyCode::Backspace,
            KeyCode::Delete,
            KeyCode::Insert,
            KeyCode::F(1),
            KeyCode::F(12),
            KeyCode::Null,
        ]);
        codes
    }

    #[test]
    fn every_key_does_what_it_did_before_the_table() {
        let c = KeyModifiers::CONTROL;
        let s = KeyModifiers::SHIFT;
        let a = KeyModifiers::ALT;
        let modifiers = [KeyModifiers::NONE, s, c, a, c | s, a | s, c | a];
        let mut handled = 0;
        for code in all_codes() {
            for &mods in &modifiers {
                let key = KeyEvent::new(code, mods);
                for help in [false, true] {
                    for focus in Pane::ALL {
                        let old = since_then(&key, old_key_action(&key, help, focus), help, focus);
                        let mode = if help { Mode::Help } else { Mode::Browsing };
                        assert_eq!(
                            key_action(&key, mode, focus),
                            old,
                            "{code:?} with {mods:?}, help {help}, focus {focus:?}"
                        );
                        handled += usize::from(!help && old.is_some());
                    }
                }
            }
        }
        assert!(
            handled > 40 * 5,
            "the oracle answers for many keys: {handled}"
        );
    }

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
    fn the_wheel_acts_on_the_pane_under_the_mouse_as_before() {
        for (input, kind) in [
            (Input::WheelUp, MouseEventKind::ScrollUp),
            (Input::WheelDown, MouseEventKind::ScrollDown),
        ] {
            for pane in Pane::ALL {
                for mode in Mode::ALL {
                    let command = keymap::mouse_command(input, mode).unwrap();
                    assert_eq!(in_pane(command, pane), old_wheel_action(kind, pane));
                }
            }
        }
        let click = keymap::mouse_command(Input::Click, Mode::Help);
        assert_eq!(
            click,
            Some(Command::Click),
            "a click picks, help open or not"
        );
    }
}
