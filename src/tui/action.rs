//! What the user can ask for: the `Action`s that `event.rs` makes of keys
//! (and the main loop of time passing) and that `App::update` carries out.

use crate::mistakes::Mistake;
use crate::scene::Switch;
use crate::terms::Term;

use super::view::find::Find;
use super::view::stepper::{Breakpoint, Step};

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
    CycleView,
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
pub enum View {
    Image,
    Term(Term),
    Yours,
    ErrorMap,
}
