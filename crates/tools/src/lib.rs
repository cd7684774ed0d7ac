//! Tools on the engine: what a student's own work is checked with and a
//! class is graded with.
//!
//! A student's ray log is read (`raylog`) and compared ray by ray with the
//! engine's recording, down to the first divergence and its words
//! (`divergence`); a student's image is compared with the reference and
//! the mistakes that would make it (`compare`); a class's submissions are
//! graded (`grade`); a pixel's rays are drawn as SVG figures (`diagram`).
//! Output files are written without damaging anything (`output`).

pub mod compare;
pub mod diagram;
pub mod divergence;
// A grade's partial credit is a share of FLIP's error.
#[cfg(feature = "flip")]
pub mod grade;
pub mod output;
pub mod raylog;
