//! raystep: a teaching-oriented, step-through Whitted ray tracer and debugger.
//!
//! One engine renders whole images and records, for any pixel, the tree of
//! rays and illumination terms that produced its colour (see MODEL.md).

pub mod accel;
pub(crate) mod camera;
pub mod cli;
pub mod compare;
pub mod diagram;
pub mod divergence;
pub mod grade;
pub(crate) mod input_file;
pub mod math;
pub mod mistakes;
pub(crate) mod object;
pub(crate) mod output;
pub mod printable;
pub mod raylog;
pub mod record;
pub mod render;
pub mod scene;
pub mod shapes;
pub mod terms;
#[cfg(test)]
mod test_scenes;
pub mod trace;
pub mod tui;
