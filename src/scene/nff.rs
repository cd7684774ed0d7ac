//! NFF import (placeholder).
use std::path::Path;

use super::{SceneDescription, SceneError};

pub fn parse(path: &Path, _text: &str) -> Result<SceneDescription, SceneError> {
    Err(SceneError::plain(format!("{}: NFF import is not written yet", path.display())))
}
