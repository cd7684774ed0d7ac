//! The scene being debugged: where it comes from, the last good file's
//! scene, the settings traced (the file's, with the user's toggles), the
//! file's watcher, a reload under way and why the last one failed.
//!
//! A reload reads and parses the file on a thread of its own and sends the
//! scene back: the keys are answered meanwhile, however slow the file
//! system (or whatever was put in the file's place), and `q` quits without
//! waiting for it.

use std::sync::Arc;
use std::sync::mpsc::{Receiver, TryRecvError, channel};
use std::time::{Duration, Instant};

use crate::tui::action::Action;
use crate::tui::source::{FileWatcher, SceneSource, merge_settings};
use raystep_engine::scene::{Scene, SceneError, Settings, SpecularModel, Switch};

use super::MAX_DEPTH;

/// How long the file must be quiet before a reload (editors write in bursts).
const RELOAD_DELAY: Duration = Duration::from_millis(150);

/// How a reload ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Reloaded {
    /// The new scene is in place: trace it with these settings (the file's
    /// with the user's toggles, `merge_settings`).
    Scene(Settings),
    /// The file is broken: the banner shows its error while the last good
    /// scene stays.
    Broken,
}

pub struct Session {
    source: SceneSource,
    /// The last good file's scene, with the file's own settings; shared with
    /// the render thread, never copied.
    scene: Arc<Scene>,
    /// The settings traced: the file's, with the user's toggles.
    settings: Settings,
    watcher: Option<FileWatcher>,
    reload_due: Option<Instant>,
    /// The reload under way: its scene (or error) comes back here.
    loading: Option<Receiver<Result<Scene, SceneError>>>,
    /// The banner: why the last reload failed.
    error: Option<String>,
}

impl Session {
    pub(super) fn new(source: SceneSource, scene: Scene) -> Session {
        Session {
            source,
            settings: scene.settings,
            scene: Arc::new(scene),
            watcher: None,
            reload_due: None,
            loading: None,
            error: None,
        }
    }

    /// Watches the scene file (the built-in scene has none); why not, when
    /// it cannot.
    pub(super) fn watch(&mut self) -> Option<String> {
        let path = self.source.path.as_ref()?;
        match FileWatcher::new(path) {
            Ok(watcher) => {
                self.watcher = Some(watcher);
                None
            }
            Err(e) => Some(format!(
                "cannot watch {} ({e}): press R to reload",
                path.display()
            )),
        }
    }

    /// On a tick: whether the file changed and has been quiet for
    /// `RELOAD_DELAY` since, so that it is time to reload.
    pub(super) fn reload_is_due(&mut self) -> bool {
        if self.watcher.as_ref().is_some_and(|w| w.changed()) {
            self.reload_due = Some(Instant::now() + RELOAD_DELAY);
        }
        if self.reload_due.is_some_and(|due| Instant::now() >= due) {
            self.reload_due = None;
            return true;
        }
        false
    }

    /// Whether a reload waits for the file to be quiet, or is under way.
    pub(crate) fn reload_waits(&self) -> bool {
        self.reload_due.is_some() || self.loading.is_some()
    }

    /// Starts loading the file again, beside the caller (with `sync`, on
    /// the caller's thread: tests). A reload under way is forgotten: the
    /// newer one tells what the file holds now.
    pub(super) fn start_reload(&mut self, sync: bool) {
        self.start_reload_with(SceneSource::load, sync);
    }

    /// `start_reload`, with `load` reading the file.
    fn start_reload_with(
        &mut self,
        load: impl FnOnce(&SceneSource) -> Result<Scene, SceneError> + Send + 'static,
        sync: bool,
    ) {
        let (send, receive) = channel();
        let source = self.source.clone();
        let job = move || {
            // The app may have quit, or started a newer reload: no one listens.
            let _ = send.send(load(&source));
        };
        if sync {
            job();
        } else if let Err(e) = std::thread::Builder::new().name("reload".into()).spawn(job) {
            self.error = Some(format!("cannot reload: {e}"));
            return;
        }
        self.loading = Some(receive);
    }

    /// The reload that has ended since the last call, if one has.
    pub(super) fn finished_reload(&mut self) -> Option<Reloaded> {
        let loaded = match self.loading.as_ref()?.try_recv() {
            Err(TryRecvError::Empty) => return None,
            Err(TryRecvError::Disconnected) => Err("the reload ended without a scene".into()),
            Ok(loaded) => loaded.map_err(|e| e.to_string()),
        };
        self.loading = None;
        Some(match loaded {
            Ok(file_scene) => {
                let settings =
                    merge_settings(&self.scene.settings, &file_scene.settings, &self.settings);
                self.scene = Arc::new(file_scene);
                self.error = None;
                Reloaded::Scene(settings)
            }
            Err(error) => {
                self.error = Some(error);
                Reloaded::Broken
            }
        })
    }

    /// For a teaching toggle (`Toggle`, `ToggleSpecular`, `Depth`,
    /// `ToggleMistake`): the settings it asks for, if it changes them, and
    /// what the status line says. `None` for any other action.
    pub(super) fn toggled(&self, action: Action) -> Option<(Option<Settings>, String)> {
        let mut settings = self.settings;
        let on_off = |on: bool| if on { "on" } else { "off" };
        let message = match action {
            Action::Toggle(Switch::Transmission) if !settings.profile.refracts() => {
                let message = format!(
                    "transmission has no meaning under the {} profile: it casts no transmitted ray (MODEL §11)",
                    settings.profile.name()
                );
                return Some((None, message));
            }
            Action::Toggle(switch) => {
                let state = on_off(settings.switches.flip(switch));
                format!("{} {state}", switch.name())
            }
            Action::ToggleSpecular => {
                use SpecularModel::{Blinn, Phong};
                let (model, message) = if settings.specular == Blinn {
                    (Phong, "specular: Phong's R·V")
                } else {
                    (Blinn, "specular: Blinn's N·H")
                };
                settings.specular = model;
                message.into()
            }
            Action::Depth(delta) => {
                let depth = settings.max_depth as i64 + delta as i64;
                if !(1..=MAX_DEPTH as i64).contains(&depth) {
                    let message = format!(
                        "max depth stays {}: it goes from 1 to {MAX_DEPTH}",
                        settings.max_depth
                    );
                    return Some((None, message));
                }
                settings.max_depth = depth as u32;
                format!("max depth {depth}")
            }
            Action::ToggleMistake(mistake) => {
                let profile = settings.profile;
                if let Some(why) = profile.why_not_offered(mistake) {
                    return Some((None, format!("mistake {mistake} {why}")));
                }
                settings.mistakes = settings.mistakes.toggled(mistake);
                let state = on_off(settings.mistakes.contains(mistake));
                format!("mistake {mistake} {state}")
            }
            _ => return None,
        };
        Some((Some(settings), message))
    }

    pub(super) fn set_settings(&mut self, settings: Settings) {
        self.settings = settings;
    }

    /// The scene's file (or the built-in scene) and the size it is traced at.
    pub(crate) fn source(&self) -> &SceneSource {
        &self.source
    }

    /// The last good file's scene, with the file's own settings.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The scene, shared with a background job.
    pub(super) fn shared_scene(&self) -> Arc<Scene> {
        self.scene.clone()
    }

    /// The settings traced: the file's, with the user's toggles.
    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// The banner: why the last reload failed.
    pub fn error(&self) -> Option<&str> {
        self.error.as_deref()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The built-in scene's session.
    fn session() -> Session {
        let source = SceneSource {
            path: None,
            size: None,
        };
        let scene = source.load().unwrap();
        Session::new(source, scene)
    }

    #[test]
    fn a_reload_that_hangs_holds_nothing_up() {
        let mut session = session();
        let (release, held) = channel::<()>();
        let started = Instant::now();
        // A file system that does not answer until released.
        session.start_reload_with(
            move |source| {
                let _ = held.recv();
                source.load()
            },
            false,
        );
        for _ in 0..10 {
            assert!(session.finished_reload().is_none());
        }
        assert!(session.reload_waits(), "the loop keeps polling");
        assert!(started.elapsed() < Duration::from_millis(100));
        release.send(()).unwrap();
        let deadline = Instant::now() + Duration::from_secs(10);
        let finished = loop {
            if let Some(finished) = session.finished_reload() {
                break finished;
            }
            assert!(Instant::now() < deadline, "the reload ends once released");
            std::thread::sleep(Duration::from_millis(5));
        };
        assert!(
            matches!(finished, Reloaded::Scene(_)),
            "the scene came back"
        );
        assert!(!session.reload_waits());
    }

    #[test]
    fn a_newer_reload_replaces_one_under_way() {
        let mut session = session();
        let (_never, held) = channel::<()>();
        session.start_reload_with(
            move |source| {
                let _ = held.recv();
                source.load()
            },
            false,
        );
        session.start_reload_with(|_| Err(SceneError::plain("the newer file is broken")), true);
        assert_eq!(session.finished_reload(), Some(Reloaded::Broken));
        assert_eq!(session.error(), Some("the newer file is broken"));
    }
}
