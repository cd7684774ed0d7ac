//! Recording one pixel: the ray tree with every term, the execution-ordered
//! event list, and their text, JSON and Graphviz forms.

mod diff;
mod dot;
mod explain;
mod finite;
mod lines;
mod numbers;
mod recorder;
mod shaping;
mod sources;
mod text;
mod tree;

pub use diff::diff;
pub use dot::dot;
pub use explain::{Said, Told, explain, explain_lines, explain_unwrapped};
pub use finite::{NonFinite, check_finite};
pub use lines::{About, Line, Piece, Row, Word};
pub use numbers::{along, color, count, fraction, num, root, vector};
pub use recorder::{NEAR_MISS_SCENE_LIMIT, TreeRecorder, record_pixel};
pub use shaping::{Shaping, place, reach, shaping_events};
pub use sources::{Source, brightness, sources};
pub use text::{
    Children, kind_name, light_label, light_lines, node_lines, not_cast_line, not_cast_reason,
    ray_header, text, working_lines,
};
pub use tree::{
    BlockerRecord, ClosestApproach, Event, EventKind, HitRecord, LightRecord, MaterialFactors,
    NearMiss, Node, NodeId, RayTree, ShadowRecord,
};
