//! Ray logs (docs/RAYLOG.md): one JSON object per ray of a pixel, as a
//! student's tracer prints them and as raystep prints its own tree, so the
//! two can be set side by side.

mod json;
mod line;
mod logged_ray;
mod path;
mod read;
mod seen;
mod write;

pub use logged_ray::{Hit, LoggedRay, uniform};
pub use path::{RayPath, Step};
pub use read::{MAX_LINE_BYTES, RaylogError, RaylogReader};
pub use write::rays_with_nodes;
pub use write::{raylog, rays_of};

/// The largest ray log file read (standard input, `-`, is a stream and has
/// none): about three million rays, each read and compared in turn in
/// bounded memory (a million lines take 344 MB and 1.2 s, BENCHMARKS.md).
pub const LOG_CAP: raystep_engine::input_file::Cap = raystep_engine::input_file::Cap {
    bytes: 1 << 30,
    of: "a ray log",
};
