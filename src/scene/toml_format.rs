//! Native scene files (placeholder).
use std::path::Path;

use super::{SceneDescription, SceneError};

pub fn parse(path: &Path, _text: &str) -> Result<SceneDescription, SceneError> {
    Err(SceneError::plain(format!("{}: not written yet", path.display())))
}
