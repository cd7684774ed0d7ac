//! raystep: a teaching-oriented, step-through Whitted ray tracer and debugger.
//!
//! This package is the top floor: the command line (`cli`) and the terminal
//! debugger (`tui`) over the workspace's libraries, `raystep-model` (the
//! lecture), `raystep-accel` (speed), `raystep-engine` (scenes, tracing,
//! recording) and `raystep-tools` (ray logs, compare, grading, diagrams).

pub mod cli;
pub mod tui;
