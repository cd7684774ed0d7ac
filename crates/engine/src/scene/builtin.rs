//! The scene shown when none is named: the seven-rays scene, compiled in so
//! the binary runs from anywhere. The CLI and the debugger both choose
//! between a file and this scene here, so they name it the same way.

use std::path::Path;

use super::{Scene, SceneError};

/// The name shown for the built-in scene (headers, error messages).
pub const NAME: &str = "seven-rays.toml (built in)";
/// The built-in scene's TOML text.
pub const TEXT: &str = include_str!("../../../../scenes/seven-rays.toml");

/// The scene at `path`, or the built-in one when no path is given.
pub fn load_file_or_builtin(path: Option<&Path>) -> Result<Scene, SceneError> {
    match path {
        Some(path) => super::load(path),
        None => super::parse(Path::new(NAME), TEXT),
    }
}
