//! Where the scene comes from: a file (watched for changes) or the built-in
//! seven-rays scene, and the teaching settings that survive a reload.

use std::path::{Path, PathBuf};
use std::sync::mpsc::{Receiver, channel};

use notify::{EventKind, RecursiveMode, Watcher as _};

use raystep_engine::scene::builtin::{self, load_file_or_builtin};
use raystep_engine::scene::{Scene, SceneError, Settings};

/// The scene file, or `None` for the built-in scene, and the size it is
/// traced at when not its own (a compared image's).
#[derive(Clone, Debug)]
pub(crate) struct SceneSource {
    pub(crate) path: Option<PathBuf>,
    pub(crate) size: Option<(u32, u32)>,
}

impl SceneSource {
    /// The name shown in the header.
    pub(crate) fn name(&self) -> String {
        match &self.path {
            Some(path) => path.display().to_string(),
            None => builtin::NAME.to_string(),
        }
    }

    pub(crate) fn load(&self) -> Result<Scene, SceneError> {
        let scene = load_file_or_builtin(self.path.as_deref())?;
        match self.size {
            Some((width, height)) => scene.with_size(width, height),
            None => Ok(scene),
        }
    }
}

/// Settings after a reload: the teaching switches and the mistakes stay as
/// the user set them, but for a mistake the file's profile does not offer
/// (`Profile::offers`: switched off, it has no meaning there);
/// the specular model and max depth follow the file only where the file
/// changed them, so an edit to `max_depth` takes effect and a toggle is kept.
pub(crate) fn merge_settings(
    old_file: &Settings,
    new_file: &Settings,
    current: &Settings,
) -> Settings {
    let mut merged = *new_file;
    merged.switches = current.switches;
    merged.mistakes = (current.mistakes.iter())
        .filter(|&m| new_file.profile.offers(m))
        .collect();
    if new_file.specular == old_file.specular {
        merged.specular = current.specular;
    }
    if new_file.max_depth == old_file.max_depth {
        merged.max_depth = current.max_depth;
    }
    merged
}

/// Watches a scene file. It watches the file's directory, so editors that
/// save by writing a new file and renaming it over the old one are seen too.
pub(crate) struct FileWatcher {
    _watcher: notify::RecommendedWatcher,
    changes: Receiver<()>,
}

impl FileWatcher {
    pub(crate) fn new(path: &Path) -> notify::Result<Self> {
        let name = path.file_name().map(|n| n.to_os_string());
        let dir = match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let (sender, changes) = channel();
        let mut watcher =
            notify::recommended_watcher(move |event: notify::Result<notify::Event>| {
                let Ok(event) = event else { return };
                let relevant = matches!(
                    event.kind,
                    EventKind::Create(_) | EventKind::Modify(_) | EventKind::Remove(_)
                );
                if relevant
                    && event
                        .paths
                        .iter()
                        .any(|p| p.file_name().map(|n| n.to_os_string()) == name)
                {
                    let _ = sender.send(());
                }
            })?;
        watcher.watch(&dir, RecursiveMode::NonRecursive)?;
        Ok(Self {
            _watcher: watcher,
            changes,
        })
    }

    /// Whether the file changed since the last call.
    pub(crate) fn changed(&self) -> bool {
        let mut changed = false;
        while self.changes.try_recv().is_ok() {
            changed = true;
        }
        changed
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use raystep_engine::scene::Profile;
    use raystep_model::mistakes::Mistake;

    #[test]
    fn a_reload_keeps_the_mistakes_turned_on() {
        let file = Settings::default();
        let mut current = file;
        current.mistakes = current.mistakes.with(Mistake::ShadowAcne);
        let merged = merge_settings(&file, &file, &current);
        assert!(merged.mistakes.contains(Mistake::ShadowAcne));
        assert_eq!(merged.mistakes.iter().count(), 1);
    }

    #[test]
    fn a_reload_into_cse167_switches_off_the_mistakes_it_does_not_offer() {
        // The lecture file with eta-inverted and shadow-acne on, edited to
        // `profile = "cse167"`: no refraction there (MODEL §11), so
        // eta-inverted goes; shadow-acne stays.
        let old = Settings::default();
        let mut new = old;
        new.profile = Profile::Cse167;
        let mut current = old;
        current.mistakes = (current.mistakes)
            .with(Mistake::ShadowAcne)
            .with(Mistake::EtaInverted);
        let merged = merge_settings(&old, &new, &current);
        assert_eq!(merged.profile, Profile::Cse167);
        assert_eq!(
            merged.mistakes.iter().collect::<Vec<_>>(),
            [Mistake::ShadowAcne]
        );
    }
}
