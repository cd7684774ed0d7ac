//! The lecture: rays and their arithmetic, the shapes and how a ray meets
//! each, the pinhole camera, the objects a scene is made of, and the
//! catalogue of mistakes students make (docs/MODEL.md).
//!
//! This crate is what a student reads beside the slides: no speed trick
//! (those are in `raystep-accel`), no terminal, no file system.

pub mod camera;
pub mod math;
pub mod mistakes;
pub mod object;
pub mod shapes;
