//! The Whitted tracer and the recorder interface through which it reports
//! everything it does.

mod recorder;
mod rules;
mod stats;
mod tracer;

pub use recorder::SurfaceHit;
pub use recorder::{Blocker, NoRecorder, NotCast, PruneRule, RayKind, Refraction};
pub(crate) use recorder::{ChildTerm, DepthLimit, LightTerm, Recorder};
pub use rules::Rules;
pub use stats::RayStats;
pub use tracer::{refract, trace};
pub(crate) use tracer::{trace_found_in_row, trace_in_row};
