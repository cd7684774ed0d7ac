//! The ray diagram, for `raystep diagram` and the debugger's diagram pane:
//! a pixel's rays, the objects they meet or pass by, the eye and the lights,
//! cut by a plane in the camera's frame. `projection.rs` is the plane and
//! the projection onto it, `rays.rs` the rays projected (by kind and by the
//! step-through), `outline.rs` the objects' outlines; `assembly.rs`
//! assembles the whole diagram from them once, and the media only draw it: `svg/` writes the figure of `raystep
//! diagram` (and the crossing test's figure), the debugger's pane
//! (`tui/pane/diagram.rs`) paints it in Braille. Nothing here knows the
//! debugger.

mod assembly;
mod outline;
mod projection;
mod rays;
pub mod svg;

pub use assembly::Diagram;
pub use assembly::Shadows;
pub use assembly::{Anchor, LegendRow, Named, ObjectOutline, Role};
pub use outline::Outline;
pub use projection::{DiagramPlane, magnified_centre};
pub use rays::Progress;
pub use rays::{Segment, Stroke};
