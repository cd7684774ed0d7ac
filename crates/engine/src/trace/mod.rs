//! The Whitted tracer and the recorder interface through which it reports
//! everything it does.

mod recorder;
mod rules;
#[cfg(test)]
mod shadow_cache_tests;
mod stats;
mod tracer;

pub use recorder::{Blocker, NoRecorder, NotCast, PruneRule, RayKind, Refraction};
pub use recorder::{ChildTerm, DepthLimit, LightTerm, Recorder, SurfaceHit};
pub use rules::Rules;
pub use stats::RayStats;
pub use tracer::{Nearest, refract, trace, trace_in_row};
