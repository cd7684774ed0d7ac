//! Recording one pixel: the ray tree with every term, the execution-ordered
//! event list, and their text, JSON and Graphviz forms.

mod explain;
mod finite;
mod recorder;
mod text;
mod tree;

pub use explain::explain;
pub use finite::{NonFinite, check_finite};
pub use recorder::{NEAR_MISS_SCENE_LIMIT, TreeRecorder, record_pixel};
pub use text::{
    color, dot, fraction, kind_name, light_lines, node_lines, not_cast_line, num, text, vector,
    working_lines,
};
pub use tree::{
    BlockerRecord, Event, EventKind, HitRecord, LightRecord, NearMiss, Node, NodeId, RayTree,
    ShadowRecord,
};
