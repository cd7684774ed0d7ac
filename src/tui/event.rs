//! Terminal events become `Action`s here and nowhere else; the help overlay
//! lists the same bindings from `KEYS`, so the two cannot drift apart.

use crossterm::event::{
    Event, KeyCode, KeyEvent, KeyEventKind, KeyModifiers, MouseButton, MouseEventKind,
};

use super::app::{Action, App, Switch};
use super::layout::Pane;
use super::stepper::{Breakpoint, Step};

/// How far Shift (or HJKL) moves the pixel cursor.
pub const BIG_STEP: i32 = 10;

/// Every key, grouped for the help overlay: (keys, what they do).
pub const KEYS: &[(&str, &[(&str, &str)])] = &[
    (
        "Pixel and view",
        &[
            (
                "arrows, h j k l",
                "move the pixel cursor (in the image pane)",
            ),
            ("Shift+arrows, H J K L", "move the pixel cursor 10 pixels"),
            ("mouse click", "pick a pixel, a tree row or an event"),
            ("+  -", "zoom in / out (down to one pixel per half cell)"),
            (
                "v",
                "cycle the image: render, each term, shadow, rays, cost",
            ),
            ("d", "diagram plane: top, side, plane of the primary ray"),
            ("Tab  Shift+Tab", "next / previous pane (arrows act on it)"),
            ("Enter", "collapse / expand the selected ray in the tree"),
        ],
    ),
    (
        "Step through the trace",
        &[
            ("n  p", "next / previous event"),
            ("i", "step into: on to the next ray cast"),
            (
                "o",
                "step over: next event of this ray, skipping child rays",
            ),
            ("u", "step out: to where this ray returns to its parent"),
            ("g  e", "go to the first event / run to the end"),
            ("b", "run to the next blocked shadow ray"),
            ("x  X", "run to the next hit on object X / choose X"),
            ("T", "run to the next total internal reflection"),
        ],
    ),
    (
        "Teaching toggles (re-render at once)",
        &[
            (
                "s  r  t  a",
                "shadows, reflection, transmission, ambient on/off",
            ),
            ("m", "specular model: Blinn's N·H or Phong's R·V"),
            ("[  ]", "max depth down / up"),
            ("R", "reload the scene file now (it also reloads on save)"),
        ],
    ),
    (
        "Other",
        &[
            ("?", "this help"),
            ("q  Esc", "quit (Esc first closes this help)"),
        ],
    ),
];

/// The action for a terminal event, if it means one.
pub fn action(event: &Event, app: &App) -> Option<Action> {
    match event {
        Event::Key(key) if key.kind != KeyEventKind::Release => key_action(key, app),
        Event::Mouse(mouse) => {
            let pane = app.panes().pane_at(mouse.column, mouse.row);
            match (mouse.kind, pane) {
                (MouseEventKind::Down(MouseButton::Left), _) => {
                    Some(Action::Click(mouse.column, mouse.row))
                }
                (MouseEventKind::ScrollDown, Some(Pane::Steps)) => Some(Action::Step(Step::Next)),
                (MouseEventKind::ScrollUp, Some(Pane::Steps)) => Some(Action::Step(Step::Previous)),
                (MouseEventKind::ScrollDown, Some(Pane::Tree)) => Some(Action::SelectRow(1)),
                (MouseEventKind::ScrollUp, Some(Pane::Tree)) => Some(Action::SelectRow(-1)),
                (MouseEventKind::ScrollDown, Some(Pane::Details)) => Some(Action::ScrollDetails(3)),
                (MouseEventKind::ScrollUp, Some(Pane::Details)) => Some(Action::ScrollDetails(-3)),
                (MouseEventKind::ScrollUp, Some(Pane::Image)) => Some(Action::ZoomIn),
                (MouseEventKind::ScrollDown, Some(Pane::Image)) => Some(Action::ZoomOut),
                _ => None,
            }
        }
        Event::Resize(width, height) => Some(Action::Resize(*width, *height)),
        _ => None,
    }
}

fn key_action(key: &KeyEvent, app: &App) -> Option<Action> {
    let ctrl = key.modifiers.contains(KeyModifiers::CONTROL);
    if ctrl && key.code == KeyCode::Char('c') {
        return Some(Action::Quit);
    }
    if app.help {
        return Some(match key.code {
            KeyCode::Char('q') => Action::Quit,
            KeyCode::Down | KeyCode::Char('j') => Action::ScrollHelp(1),
            KeyCode::Up | KeyCode::Char('k') => Action::ScrollHelp(-1),
            _ => Action::CloseHelp,
        });
    }
    let shift = key.modifiers.contains(KeyModifiers::SHIFT);
    if let Some(action) = arrow_action(key.code, shift, app.focus) {
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
        KeyCode::PageDown if app.focus == Pane::Details => Action::ScrollDetails(10),
        KeyCode::PageUp if app.focus == Pane::Details => Action::ScrollDetails(-10),
        _ => return None,
    })
}

/// Arrows and h j k l act on the focused pane; elsewhere they move the pixel.
fn arrow_action(code: KeyCode, shift: bool, focus: Pane) -> Option<Action> {
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
