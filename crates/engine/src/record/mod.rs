//! Recording one pixel: the ray tree with every term, the execution-ordered
//! event list, and their text, JSON and Graphviz forms.

mod diff;
mod dot;
mod ellipsoid_words;
mod event_words;
mod explain;
mod fate;
mod finite;
mod json_stream;
mod lines;
mod numbers;
mod ray_tree;
mod shaping;
mod shared_words;
mod sources;
pub mod stepping;
mod text;
mod tree_recorder;
mod tree_words;

pub use diff::diff;
pub use dot::dot;
pub use event_words::describe_event;
pub use explain::{Said, Told, explain_lines};
pub use explain::{explain, explain_unwrapped};
pub use fate::LightFate;
pub(crate) use finite::{NonFinite, check_finite};
pub use json_stream::write_json;
pub use lines::{About, Line};
pub use numbers::{color, count, num, precise, root, vector};
pub use ray_tree::{Event, EventKind, Node, RayTree};
pub use ray_tree::{LightRecord, NearMiss, NodeId};
pub use shaping::{place, reach, shaping_events};
pub(crate) use shared_words::not_cast_line;
pub use shared_words::{kind_name, light_label, ray_header, weight_words};
pub use text::{Children, node_lines, text};
pub use tree_recorder::{NEAR_MISS_SCENE_LIMIT, TreeRecorder, record_pixel};
pub use tree_words::{light_summary, path_factor, ray_summary, share_of_pixel};
