//! The engine: one tracer for whole images and for a pixel's recorded ray
//! tree (docs/MODEL.md).
//!
//! Scenes are read from TOML or NFF with their meshes (`scene`, every
//! input through `input_file`), traced by the Whitted tracer (`trace`),
//! rendered row by row (`render`, `terms` for one term's image) and, for a
//! pixel, recorded as a tree of rays and terms with its explanations
//! (`record`). A recorded tree is the render's own arithmetic, so it can
//! never disagree with the image.

pub mod input_file;
pub mod printable;
pub mod record;
pub mod render;
pub mod scene;
pub mod terms;
#[cfg(any(test, feature = "test-scenes"))]
pub mod test_scenes;
pub mod trace;
