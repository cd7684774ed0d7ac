//! The Whitted tracer and the recorder interface through which it reports
//! everything it does.

mod recorder;
mod rules;
mod stats;
mod tracer;

pub use recorder::{
    Blocker, ChildTerm, DepthLimit, LightTerm, NoRecorder, NotCast, PruneRule, RayKind, Recorder,
    Refraction, ShadowOutcome, SurfaceHit,
};
pub use stats::RayStats;
pub use tracer::{trace, trace_in_row};
