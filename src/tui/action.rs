//! What the user can ask for: the `Action`s that `event.rs` makes of keys
//! (and the main loop of time passing) and that `App::update` carries out,
//! with the words they are made of (a pane, a step, a breakpoint, what to
//! find, what the image pane shows). The key table (`keymap.rs`) speaks
//! only this vocabulary.

use raystep_engine::record::stepping::{Breakpoint, Step};
use raystep_engine::scene::Switch;
use raystep_engine::terms::Term;
use raystep_model::mistakes::Mistake;

/// Something the user asked for, or a tick of the clock.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Action {
    Quit,
    /// Ctrl+Z: back to the shell until `fg`. The main loop carries it out
    /// (it is the terminal's, not the app's); the state stays as it is.
    Suspend,
    ToggleHelp,
    CloseHelp,
    ScrollHelp(i32),
    FocusNext,
    FocusPrevious,
    /// Move the pixel cursor by image pixels.
    Move(i32, i32),
    Pick(u32, u32),
    /// A mouse click on a screen cell.
    Click(u16, u16),
    ZoomIn,
    ZoomOut,
    Step(Step),
    RunTo(Breakpoint),
    /// Run to the next hit on the breakpoint object (the selected ray's object).
    RunToObject,
    CycleBreakObject,
    /// Move the ray tree's selection by rows.
    SelectRow(i32),
    ToggleCollapse,
    ScrollDetails(i32),
    Toggle(Switch),
    ToggleSpecular,
    Depth(i32),
    /// What the image pane shows next: the render, each term, yours, the error map.
    CyclePicture,
    /// With a comparison: this picture (yours or the error map), or the
    /// render again when it is already shown.
    TogglePicture(Picture),
    /// Open the mistakes menu, or close it when open.
    ToggleMistakeMenu,
    CloseMistakeMenu,
    /// Move the mistakes menu's selection by rows.
    MenuMove(i32),
    /// Turn the menu's selected mistake on or off.
    MenuToggle,
    ToggleMistake(Mistake),
    /// With a comparison: the cursor to the next region's pixel.
    NextRegion,
    /// With a ray log: the cursor to the next (1) or previous (-1) pixel
    /// of the log, cycling.
    NextLoggedPixel(i32),
    /// With a ray log: to the event where the pixel's first divergence
    /// from the log is made.
    FirstDivergence,
    CyclePlane,
    /// Pan the diagram by quarters of what it shows (arrows, diagram focused).
    PanDiagram(i32, i32),
    /// Zoom the diagram in (> 0) or out by steps.
    ZoomDiagram(i32),
    /// Show the whole diagram again.
    FitDiagram,
    /// Open the go-to prompt in the status line (`:`).
    OpenPrompt,
    /// A character typed into the prompt.
    PromptChar(char),
    PromptBackspace,
    /// Go to the pixel the prompt names (Enter).
    PromptSubmit,
    PromptCancel,
    /// `f`: the next key names what to find across the image.
    StartFind,
    CancelFind,
    /// The cursor to the next pixel, in reading order, whose recording has it.
    Find(Find),
    Reload,
    Resize(u16, u16),
    /// Time passed: take in finished renders, reload a changed scene file.
    /// The main loop sends one after every wait, event or not.
    Tick,
}

/// What the image pane shows: the render, one term image, or (when
/// comparing) the student's image or FLIP's error map.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Picture {
    Render,
    Term(Term),
    Yours,
    ErrorMap,
}

/// The panes, in the order Tab visits them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pane {
    Image,
    Tree,
    Steps,
    Details,
    Diagram,
}

impl Pane {
    pub const ALL: [Pane; 5] = [
        Pane::Image,
        Pane::Tree,
        Pane::Steps,
        Pane::Details,
        Pane::Diagram,
    ];

    pub(crate) fn next(self) -> Pane {
        let i = Pane::ALL.iter().position(|&p| p == self).unwrap_or(0);
        Pane::ALL[(i + 1) % Pane::ALL.len()]
    }

    pub(crate) fn previous(self) -> Pane {
        let i = Pane::ALL.iter().position(|&p| p == self).unwrap_or(0);
        Pane::ALL[(i + Pane::ALL.len() - 1) % Pane::ALL.len()]
    }
}

/// What `f` looks for in each pixel's recording.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Find {
    BlockedShadow,
    /// A shadow ray blocked only by transparent surfaces: 0 < S < 1.
    PartialShadow,
    Tir,
    /// A ray whose hit the depth limit kept from casting a child it would
    /// have cast (the recording's `depth_limit`, as the tracer reported it).
    DepthLimit,
    /// A hit on the breakpoint object (`x`'s).
    BreakObject,
    /// A near miss: a ray crossed a polygon's plane inside its bounding box
    /// but outside the polygon (an even crossing count), e.g. a notch, or a
    /// sphere's bounding box without hitting the sphere (no real roots, or
    /// both roots behind); any recorded `near_misses` entry counts. Of
    /// the breakpoint object only, once one is chosen.
    NearMiss,
}
