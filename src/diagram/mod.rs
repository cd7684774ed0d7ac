//! The ray diagram, for `raystep diagram` and the debugger's diagram pane:
//! a pixel's rays, the objects they meet or pass by, the eye and the lights,
//! cut by a plane in the camera's frame. `projection.rs` projects the scene
//! onto the plane, `assembly.rs` assembles the whole diagram from it once,
//! and the media only draw it: `svg/` writes the figure of `raystep
//! diagram` (and the crossing test's figure), the debugger's pane
//! (`tui/pane/diagram.rs`) paints it in Braille. Nothing here knows the
//! debugger.

mod assembly;
mod projection;
pub mod svg;

pub use assembly::{
    Anchor, Diagram, FacesAway, HitMark, Label, LegendRow, LightMark, Named, ObjectOutline,
    PassedMark, Role,
};
pub use projection::{
    BlockerMark, CurrentRay, DiagramPlane, Outline, Progress, Segment, Stroke, magnified_centre,
};

#[cfg(test)]
pub(crate) use assembly::tests::pebble;
