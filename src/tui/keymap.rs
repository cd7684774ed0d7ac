//! Every key of the debugger in one table. Dispatch (`event.rs`), the `?`
//! help, the status line and the key table of docs/DEBUGGER.md all read `KEYMAP`, so they
//! cannot drift apart: a key that is not in a row does nothing.

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};

use super::action::{Action, Find, Pane, Picture};
use raystep_engine::record::stepping::{Breakpoint, Step};
use raystep_engine::scene::Switch;

/// How far Shift (or H J K L) moves the pixel cursor.
pub(crate) const BIG_STEP: i32 = 10;

/// One input a row answers to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Input {
    /// The key, whatever modifiers are held.
    Key(KeyCode),
    /// The key with Shift held (beats the same key without).
    Shift(KeyCode),
    /// The key with Ctrl held (beats the same key without).
    Ctrl(KeyCode),
    /// Any key that no other row of the context names.
    AnyKey,
    Click,
    WheelUp,
    WheelDown,
}

/// When a row applies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Context {
    Always,
    /// Neither the help nor the mistakes menu is open.
    Browsing,
    /// The help overlay is open.
    Help,
    /// The mistakes menu is open.
    Menu,
    /// The go-to prompt (`:`) is open in the status line.
    Prompt,
    /// `f` was pressed: the next key says what to find.
    Find,
}

/// What has the keys: the panes, the help overlay or the mistakes menu.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    Browsing,
    Help,
    Menu,
    Prompt,
    Find,
}

#[cfg(test)]
impl Mode {
    pub(crate) const ALL: [Mode; 5] = [
        Mode::Browsing,
        Mode::Help,
        Mode::Menu,
        Mode::Prompt,
        Mode::Find,
    ];
}

/// What an input asks for, before the pane it acts on is known.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Command {
    /// This action, whatever the pane.
    Do(Action),
    /// A step (dx, dy): the focused pane decides what moves (`event.rs`).
    Arrow(i32, i32),
    /// The first event, or the whole diagram when it has the focus.
    Home,
    /// Zoom in (1) or out (-1): the diagram when focused, else the image.
    Zoom(i32),
    /// Scroll the details by this many lines, when they have the focus.
    Page(i32),
    /// The wheel, down (1) or up (-1): acts on the pane under the mouse.
    Wheel(i32),
    /// Pick what is under the mouse.
    Click,
    /// The key's character, typed into the prompt.
    Type,
}

/// The status line's short form of a row: `rank` orders the hints.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Hint {
    pub(crate) rank: u8,
    pub(crate) keys: &'static str,
    pub(crate) what: &'static str,
}

/// One row: its inputs, each with its command, and the help text.
#[derive(Clone, Copy, Debug)]
pub struct Binding {
    pub context: Context,
    pub inputs: &'static [(Input, Command)],
    pub what: &'static str,
    pub(crate) hint: Option<Hint>,
}

const ROW: Binding = Binding {
    context: Context::Browsing,
    inputs: &[],
    what: "",
    hint: None,
};

const fn key(c: char) -> Input {
    Input::Key(KeyCode::Char(c))
}

const fn act(action: Action) -> Command {
    Command::Do(action)
}

const fn hint(rank: u8, keys: &'static str, what: &'static str) -> Option<Hint> {
    Some(Hint { rank, keys, what })
}

const B: i32 = BIG_STEP;

/// Every key, grouped as the help shows them: (group title, rows).
pub(crate) const KEYMAP: &[(&str, &[Binding])] = &[
    ("Pixel and view", PIXEL_AND_VIEW),
    ("Step through the trace", STEPPING),
    ("Teaching toggles (re-render at once)", TOGGLES),
    ("Other", OTHER),
    ("In this help", IN_HELP),
    ("In the mistakes menu", IN_MENU),
    ("In the go-to prompt (after :)", IN_PROMPT),
    ("Find across the image (after f)", IN_FIND),
];

const PIXEL_AND_VIEW: &[Binding] = &[
    Binding {
        inputs: &[
            (Input::Key(KeyCode::Left), Command::Arrow(-1, 0)),
            (Input::Key(KeyCode::Right), Command::Arrow(1, 0)),
            (Input::Key(KeyCode::Up), Command::Arrow(0, -1)),
            (Input::Key(KeyCode::Down), Command::Arrow(0, 1)),
            (key('h'), Command::Arrow(-1, 0)),
            (key('j'), Command::Arrow(0, 1)),
            (key('k'), Command::Arrow(0, -1)),
            (key('l'), Command::Arrow(1, 0)),
        ],
        what: "move the pixel cursor; in other panes select, step, pan",
        hint: hint(2, "arrows", "pixel"),
        ..ROW
    },
    Binding {
        inputs: &[
            (Input::Shift(KeyCode::Left), act(Action::Move(-B, 0))),
            (Input::Shift(KeyCode::Right), act(Action::Move(B, 0))),
            (Input::Shift(KeyCode::Up), act(Action::Move(0, -B))),
            (Input::Shift(KeyCode::Down), act(Action::Move(0, B))),
            (key('H'), act(Action::Move(-B, 0))),
            (Input::Shift(KeyCode::Char('h')), act(Action::Move(-B, 0))),
            (key('J'), act(Action::Move(0, B))),
            (Input::Shift(KeyCode::Char('j')), act(Action::Move(0, B))),
            (key('K'), act(Action::Move(0, -B))),
            (Input::Shift(KeyCode::Char('k')), act(Action::Move(0, -B))),
            (key('L'), act(Action::Move(B, 0))),
            (Input::Shift(KeyCode::Char('l')), act(Action::Move(B, 0))),
        ],
        what: "move the pixel cursor 10 pixels, whatever the pane",
        ..ROW
    },
    Binding {
        context: Context::Always,
        inputs: &[(Input::Click, Command::Click)],
        what: "pick a pixel, a tree row or an event",
        ..ROW
    },
    Binding {
        context: Context::Always,
        inputs: &[
            (Input::WheelUp, Command::Wheel(-1)),
            (Input::WheelDown, Command::Wheel(1)),
        ],
        what: "zoom the image or diagram, step, select a ray, scroll",
        ..ROW
    },
    Binding {
        inputs: &[
            (key('+'), Command::Zoom(1)),
            (key('='), Command::Zoom(1)),
            (key('-'), Command::Zoom(-1)),
            (key('_'), Command::Zoom(-1)),
        ],
        what: "zoom in (+ =) / out (- _): the image or focused diagram",
        ..ROW
    },
    Binding {
        inputs: &[(key('0'), act(Action::FitDiagram))],
        what: "show the whole diagram again (Home too, diagram focused)",
        ..ROW
    },
    Binding {
        inputs: &[(key('v'), act(Action::CyclePicture))],
        what: "cycle the image: render, each term image, yours, error map",
        hint: hint(7, "v", "view"),
        ..ROW
    },
    Binding {
        inputs: &[
            (key('c'), act(Action::TogglePicture(Picture::Yours))),
            (key('E'), act(Action::TogglePicture(Picture::ErrorMap))),
        ],
        what: "with --compare: yours / error map at once (again: render)",
        ..ROW
    },
    Binding {
        inputs: &[(key('w'), act(Action::NextRegion))],
        what: "with --compare: next region that differs, largest first",
        ..ROW
    },
    Binding {
        inputs: &[
            (key('y'), act(Action::NextLoggedPixel(1))),
            (key('Y'), act(Action::NextLoggedPixel(-1))),
        ],
        what: "with --rays: next / previous pixel of your log, cycling",
        ..ROW
    },
    Binding {
        inputs: &[(key(':'), act(Action::OpenPrompt))],
        what: "go to a pixel: type X,Y then Enter",
        hint: hint(8, ":", "go to"),
        ..ROW
    },
    Binding {
        inputs: &[(key('f'), act(Action::StartFind))],
        what: "find across the image: then b, p, t, D, x or n (below)",
        ..ROW
    },
    Binding {
        inputs: &[(key('d'), act(Action::CyclePlane))],
        what: "diagram plane (camera frame): above, side, primary ray",
        ..ROW
    },
    Binding {
        inputs: &[
            (Input::Key(KeyCode::Tab), act(Action::FocusNext)),
            (Input::Key(KeyCode::BackTab), act(Action::FocusPrevious)),
        ],
        what: "next / previous pane (arrows act on it)",
        hint: hint(3, "Tab", "pane"),
        ..ROW
    },
    Binding {
        inputs: &[
            (Input::Key(KeyCode::Enter), act(Action::ToggleCollapse)),
            (key(' '), act(Action::ToggleCollapse)),
        ],
        what: "collapse / expand the selected ray in the tree",
        ..ROW
    },
    Binding {
        inputs: &[
            (Input::Key(KeyCode::PageUp), Command::Page(-10)),
            (Input::Key(KeyCode::PageDown), Command::Page(10)),
        ],
        what: "scroll the details 10 lines (in the details pane)",
        ..ROW
    },
];

const STEPPING: &[Binding] = &[
    Binding {
        inputs: &[
            (key('n'), act(Action::Step(Step::Next))),
            (key('p'), act(Action::Step(Step::Previous))),
        ],
        what: "next / previous event",
        hint: hint(4, "n/p", "step"),
        ..ROW
    },
    Binding {
        inputs: &[(key('i'), act(Action::Step(Step::Into)))],
        what: "step into: on to the next ray cast",
        ..ROW
    },
    Binding {
        inputs: &[(key('o'), act(Action::Step(Step::Over)))],
        what: "step over: next event of this ray, skipping child rays",
        ..ROW
    },
    Binding {
        inputs: &[(key('u'), act(Action::Step(Step::Out)))],
        what: "step out: to where this ray returns to its parent",
        ..ROW
    },
    Binding {
        inputs: &[
            (key('g'), act(Action::Step(Step::Start))),
            (Input::Key(KeyCode::Home), Command::Home),
            (key('e'), act(Action::Step(Step::End))),
            (Input::Key(KeyCode::End), act(Action::Step(Step::End))),
        ],
        what: "go to the first event / run to the end",
        ..ROW
    },
    Binding {
        inputs: &[(key('b'), act(Action::RunTo(Breakpoint::BlockedShadow)))],
        what: "run to the next blocked shadow ray",
        hint: hint(5, "b", "blocked shadow"),
        ..ROW
    },
    Binding {
        inputs: &[
            (key('x'), act(Action::RunToObject)),
            (key('X'), act(Action::CycleBreakObject)),
        ],
        what: "run to the next hit on object X / choose X",
        ..ROW
    },
    Binding {
        inputs: &[(key('T'), act(Action::RunTo(Breakpoint::Tir)))],
        what: "run to the next total internal reflection",
        ..ROW
    },
    Binding {
        inputs: &[(key('D'), act(Action::FirstDivergence))],
        what: "with --rays: to the first divergence from your log",
        ..ROW
    },
];

const TOGGLES: &[Binding] = &[
    Binding {
        inputs: &[
            (key('s'), act(Action::Toggle(Switch::Shadows))),
            (key('r'), act(Action::Toggle(Switch::Reflection))),
            (key('t'), act(Action::Toggle(Switch::Transmission))),
            (key('a'), act(Action::Toggle(Switch::Ambient))),
        ],
        what: "shadows, reflection, transmission, ambient on/off",
        hint: hint(6, "s r t a", "toggles"),
        ..ROW
    },
    Binding {
        inputs: &[(key('m'), act(Action::ToggleSpecular))],
        what: "specular model: Blinn's N·H or Phong's R·V",
        ..ROW
    },
    Binding {
        inputs: &[(key('M'), act(Action::ToggleMistakeMenu))],
        what: "classic student mistakes: a menu to turn each on / off",
        ..ROW
    },
    Binding {
        inputs: &[
            (key('['), act(Action::Depth(-1))),
            (key(']'), act(Action::Depth(1))),
        ],
        what: "max depth down / up",
        ..ROW
    },
    Binding {
        inputs: &[(key('R'), act(Action::Reload))],
        what: "reload the scene file now (it also reloads on save)",
        ..ROW
    },
];

const OTHER: &[Binding] = &[
    Binding {
        inputs: &[(key('?'), act(Action::ToggleHelp))],
        what: "this help",
        hint: hint(0, "?", "help"),
        ..ROW
    },
    Binding {
        inputs: &[
            (key('q'), act(Action::Quit)),
            (Input::Key(KeyCode::Esc), act(Action::Quit)),
        ],
        what: "quit",
        hint: hint(1, "q", "quit"),
        ..ROW
    },
    Binding {
        context: Context::Always,
        inputs: &[(Input::Ctrl(KeyCode::Char('c')), act(Action::Quit))],
        what: "quit, also in this help",
        ..ROW
    },
    Binding {
        context: Context::Always,
        inputs: &[(Input::Ctrl(KeyCode::Char('z')), act(Action::Suspend))],
        what: "suspend: back to the shell until fg",
        ..ROW
    },
];

const IN_HELP: &[Binding] = &[
    Binding {
        context: Context::Help,
        inputs: &[
            (Input::Key(KeyCode::Up), act(Action::ScrollHelp(-1))),
            (Input::Key(KeyCode::Down), act(Action::ScrollHelp(1))),
            (key('k'), act(Action::ScrollHelp(-1))),
            (key('j'), act(Action::ScrollHelp(1))),
        ],
        what: "scroll this help",
        ..ROW
    },
    Binding {
        context: Context::Help,
        inputs: &[(Input::AnyKey, act(Action::CloseHelp))],
        what: "close this help (q and Esc too)",
        ..ROW
    },
];

const IN_MENU: &[Binding] = &[
    Binding {
        context: Context::Menu,
        inputs: &[
            (Input::Key(KeyCode::Up), act(Action::MenuMove(-1))),
            (Input::Key(KeyCode::Down), act(Action::MenuMove(1))),
            (key('k'), act(Action::MenuMove(-1))),
            (key('j'), act(Action::MenuMove(1))),
        ],
        what: "select a mistake",
        ..ROW
    },
    Binding {
        context: Context::Menu,
        inputs: &[
            (key(' '), act(Action::MenuToggle)),
            (Input::Key(KeyCode::Enter), act(Action::MenuToggle)),
        ],
        what: "turn the selected mistake on / off (re-renders at once)",
        ..ROW
    },
    Binding {
        context: Context::Menu,
        inputs: &[
            (Input::Key(KeyCode::Esc), act(Action::CloseMistakeMenu)),
            (key('M'), act(Action::ToggleMistakeMenu)),
        ],
        what: "close the menu",
        ..ROW
    },
];

const IN_PROMPT: &[Binding] = &[
    Binding {
        context: Context::Prompt,
        inputs: &[(Input::Key(KeyCode::Enter), act(Action::PromptSubmit))],
        what: "go to the pixel typed",
        ..ROW
    },
    Binding {
        context: Context::Prompt,
        inputs: &[(Input::Key(KeyCode::Esc), act(Action::PromptCancel))],
        what: "close the prompt, staying on the pixel",
        ..ROW
    },
    Binding {
        context: Context::Prompt,
        inputs: &[(Input::Key(KeyCode::Backspace), act(Action::PromptBackspace))],
        what: "delete the last character",
        ..ROW
    },
    Binding {
        context: Context::Prompt,
        inputs: &[(Input::AnyKey, Command::Type)],
        what: "type it (digits and a comma: 120,40)",
        ..ROW
    },
];

const IN_FIND: &[Binding] = &[
    Binding {
        context: Context::Find,
        inputs: &[(key('b'), act(Action::Find(Find::BlockedShadow)))],
        what: "the next pixel with a blocked shadow ray",
        ..ROW
    },
    Binding {
        context: Context::Find,
        inputs: &[(key('p'), act(Action::Find(Find::PartialShadow)))],
        what: "the next pixel with a partly blocked shadow (0 < S < 1)",
        ..ROW
    },
    Binding {
        context: Context::Find,
        inputs: &[(key('t'), act(Action::Find(Find::Tir)))],
        what: "the next pixel with a total internal reflection",
        ..ROW
    },
    Binding {
        context: Context::Find,
        inputs: &[(key('D'), act(Action::Find(Find::DepthLimit)))],
        what: "the next pixel with a ray cut by the depth limit",
        ..ROW
    },
    Binding {
        context: Context::Find,
        inputs: &[(key('x'), act(Action::Find(Find::BreakObject)))],
        what: "the next pixel whose rays hit object X (as x)",
        ..ROW
    },
    Binding {
        context: Context::Find,
        inputs: &[(key('n'), act(Action::Find(Find::NearMiss)))],
        what: "the next pixel with a near miss, polygon or sphere (or X)",
        ..ROW
    },
    Binding {
        context: Context::Find,
        inputs: &[(Input::AnyKey, act(Action::CancelFind))],
        what: "cancel the find",
        ..ROW
    },
];

/// Every row, in the help's order.
pub fn rows() -> impl Iterator<Item = &'static Binding> {
    KEYMAP.iter().flat_map(|(_, rows)| rows.iter())
}

/// The command for `key`, from the rows that apply: the most specific input
/// wins (Ctrl+ or Shift+ a key, then the key, then any key).
pub(crate) fn key_command(key: &KeyEvent, mode: Mode) -> Option<Command> {
    lookup(mode, |input| input.fit(key))
}

/// The command for a mouse input (`Click`, `WheelUp`, `WheelDown`).
pub(crate) fn mouse_command(mouse: Input, mode: Mode) -> Option<Command> {
    lookup(mode, |input| (input == mouse).then_some(1))
}

fn lookup(mode: Mode, fit: impl Fn(Input) -> Option<u8>) -> Option<Command> {
    rows()
        .filter(|row| row.context.applies(mode))
        .flat_map(|row| row.inputs)
        .filter_map(|&(input, command)| Some((fit(input)?, command)))
        .max_by_key(|&(fit, _)| fit)
        .map(|(_, command)| command)
}

impl Context {
    pub fn applies(self, mode: Mode) -> bool {
        match self {
            Context::Always => true,
            Context::Browsing => mode == Mode::Browsing,
            Context::Help => mode == Mode::Help,
            Context::Menu => mode == Mode::Menu,
            Context::Prompt => mode == Mode::Prompt,
            Context::Find => mode == Mode::Find,
        }
    }
}

impl Input {
    /// How closely this input names `key`: `None` not at all, higher is closer.
    fn fit(self, key: &KeyEvent) -> Option<u8> {
        let held = |m| key.modifiers.contains(m);
        match self {
            Input::Ctrl(code) => (key.code == code && held(KeyModifiers::CONTROL)).then_some(2),
            Input::Shift(code) => (key.code == code && held(KeyModifiers::SHIFT)).then_some(2),
            Input::Key(code) => (key.code == code).then_some(1),
            Input::AnyKey => Some(0),
            Input::Click | Input::WheelUp | Input::WheelDown => None,
        }
    }

    /// The input as the help and docs/DEBUGGER.md name it (Shift+h is `H`).
    pub fn name(self) -> String {
        match self {
            Input::Key(code) => code_name(code),
            Input::Shift(KeyCode::Char(c)) => c.to_uppercase().to_string(),
            Input::Shift(code) => format!("Shift+{}", code_name(code)),
            Input::Ctrl(KeyCode::Char(c)) => format!("Ctrl+{}", c.to_uppercase()),
            Input::Ctrl(code) => format!("Ctrl+{}", code_name(code)),
            Input::AnyKey => "any other key".into(),
            Input::Click => "mouse click".into(),
            Input::WheelUp | Input::WheelDown => "mouse wheel".into(),
        }
    }
}

fn code_name(code: KeyCode) -> String {
    match code {
        KeyCode::Char(' ') => "Space".into(),
        KeyCode::Char(c) => c.to_string(),
        KeyCode::BackTab => "Shift+Tab".into(),
        code => format!("{code:?}"),
    }
}

impl Binding {
    /// The row's keys as the help and docs/DEBUGGER.md show them: each name once, the
    /// four arrows as `arrows`.
    pub fn keys(&self) -> String {
        let mut names: Vec<String> = self.inputs.iter().map(|(i, _)| i.name()).collect();
        for prefix in ["", "Shift+"] {
            let arrows = ["Left", "Right", "Up", "Down"].map(|a| format!("{prefix}{a}"));
            if arrows.iter().all(|a| names.contains(a)) {
                for name in &mut names {
                    if arrows.contains(name) {
                        *name = format!("{prefix}arrows");
                    }
                }
            }
        }
        let mut keys: Vec<String> = Vec::new();
        for name in names {
            if !keys.contains(&name) {
                keys.push(name);
            }
        }
        keys.join(" ")
    }
}

/// The status line's hints, in their order.
pub(crate) fn hints() -> Vec<Hint> {
    let mut hints: Vec<Hint> = rows().filter_map(|row| row.hint).collect();
    hints.sort_by_key(|h| h.rank);
    hints
}

/// What the arrows and + - 0 do while the diagram has the focus.
pub(crate) const DIAGRAM_HINTS: [Hint; 3] = [
    Hint {
        rank: 2,
        keys: "arrows",
        what: "pan diagram",
    },
    Hint {
        rank: 2,
        keys: "+/-",
        what: "zoom",
    },
    Hint {
        rank: 2,
        keys: "0",
        what: "fit",
    },
];

/// The hints with `focus` on `pane`: in the diagram the arrows pan it.
pub(crate) fn hints_in(pane: Pane) -> Vec<Hint> {
    let hints = hints();
    if pane != Pane::Diagram {
        return hints;
    }
    let arrows = hints.iter().position(|h| h.keys == "arrows");
    let (before, after) = hints.split_at(arrows.unwrap_or(hints.len()));
    let mut shown = before.to_vec();
    shown.extend(DIAGRAM_HINTS);
    shown.extend(after.iter().skip(1));
    shown
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(keys: &str) -> &'static Binding {
        rows().find(|r| r.keys() == keys).unwrap_or_else(|| {
            let all: Vec<String> = rows().map(Binding::keys).collect();
            panic!("no row {keys:?} in {all:?}")
        })
    }

    #[test]
    fn labels_name_every_input_once() {
        // By hand from the rows: four arrows collapse to `arrows`, Shift+h
        // and H are one key, both wheel directions are one wheel.
        row("arrows h j k l");
        row("Shift+arrows H J K L");
        row("+ = - _");
        row("Tab Shift+Tab");
        row("Enter Space");
        row("PageUp PageDown");
        row("g Home e End");
        row("mouse wheel");
        row("Ctrl+C");
        row("Ctrl+Z");
        row("Up Down k j");
        row("any other key");
        row("Space Enter");
        row("Esc M");
    }

    #[test]
    fn no_two_rows_claim_the_same_input_at_once() {
        let inputs: Vec<(Context, Input)> = rows()
            .flat_map(|r| r.inputs.iter().map(move |&(i, _)| (r.context, i)))
            .collect();
        for (n, &(ca, a)) in inputs.iter().enumerate() {
            for &(cb, b) in &inputs[n + 1..] {
                let together = Mode::ALL.iter().any(|&m| ca.applies(m) && cb.applies(m));
                // Ctrl+x and Shift+x would tie for a key with both held.
                let tie = match (a, b) {
                    (Input::Ctrl(x), Input::Shift(y)) | (Input::Shift(x), Input::Ctrl(y)) => x == y,
                    _ => a == b,
                };
                assert!(!(together && tie), "{a:?} ({ca:?}) and {b:?} ({cb:?})");
            }
        }
    }

    #[test]
    fn every_hint_names_keys_of_its_row() {
        for row in rows() {
            let Some(hint) = row.hint else { continue };
            let keys = row.keys();
            for key in hint.keys.split([' ', '/']) {
                assert!(keys.split(' ').any(|k| k == key), "{key} not in {keys}");
            }
        }
        let order: Vec<&str> = hints().iter().map(|h| h.keys).collect();
        assert_eq!(
            order,
            ["?", "q", "arrows", "Tab", "n/p", "b", "s r t a", "v", ":"]
        );
    }

    #[test]
    fn the_most_specific_input_wins() {
        let key = |code, mods| KeyEvent::new(code, mods);
        let ctrl_c = key(KeyCode::Char('c'), KeyModifiers::CONTROL);
        // Ctrl+C beats the help's "any other key".
        assert_eq!(key_command(&ctrl_c, Mode::Help), Some(act(Action::Quit)));
        assert_eq!(key_command(&ctrl_c, Mode::Menu), Some(act(Action::Quit)));
        // Ctrl+Z too, and it beats the prompt's typing (`z` types a z).
        let ctrl_z = key(KeyCode::Char('z'), KeyModifiers::CONTROL);
        for mode in Mode::ALL {
            let suspend = Some(act(Action::Suspend));
            assert_eq!(key_command(&ctrl_z, mode), suspend, "{mode:?}");
        }
        let shift_h = key(KeyCode::Char('h'), KeyModifiers::SHIFT);
        assert_eq!(
            key_command(&shift_h, Mode::Browsing),
            Some(act(Action::Move(-10, 0)))
        );
        let ctrl_h = key(KeyCode::Char('h'), KeyModifiers::CONTROL);
        assert_eq!(
            key_command(&ctrl_h, Mode::Browsing),
            Some(Command::Arrow(-1, 0))
        );
        assert_eq!(
            key_command(&key(KeyCode::F(5), KeyModifiers::NONE), Mode::Browsing),
            None
        );
    }
}
