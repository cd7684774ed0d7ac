//! What a call of the page answers.

use serde_json::Value;

/// JSON for the page to read, text or bytes to show or download as they
/// are (an SVG, a PNG).
#[derive(Debug)]
pub enum Reply {
    Json(Value),
    Text(String),
    Bytes(Vec<u8>),
}
