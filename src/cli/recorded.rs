//! What `inspect`, `explain` and `diagram` start from: the scene loaded
//! at its size, the pixel recorded (with `--mistake`), and with `--set` or
//! `--diff-against` the recording it is compared with.

use anyhow::{Result, bail};

use super::{PixelArgs, load_scene};
use raystep_engine::record::{RayTree, record_pixel};
use raystep_engine::scene::{self, Scene};

/// The pixel's recording, and for `--set` or `--diff-against` the one it
/// is compared with and what that was.
pub(super) struct Recorded {
    pub(super) scene: Scene,
    pub(super) tree: RayTree,
    before: Option<(RayTree, String)>,
}

impl Recorded {
    /// What changed against the recording before, as a closing section.
    pub(super) fn what_changed(&self) -> String {
        match &self.before {
            None => String::new(),
            Some((before, what)) => format!(
                "\nWhat changed against {what}:\n{}",
                raystep_engine::record::diff(before, &self.tree)
            ),
        }
    }
}

/// Loads the scene and records the pixel, refusing one outside the image;
/// with `--set`, the changed scene, and the scene as written beside it.
pub(super) fn record(args: &PixelArgs) -> Result<Recorded> {
    let mut scene = load_scene(Some(&args.scene), args.size)?;
    let (x, y) = args.pixel;
    if x >= scene.width || y >= scene.height {
        bail!(
            "pixel ({x}, {y}) is outside the {}x{} image: x must be below {} and y below {}",
            scene.width,
            scene.height,
            scene.width,
            scene.height
        );
    }
    let before = match &args.diff_against {
        Some(original) => {
            let other = scene::builtin::load_file_or_builtin(Some(original))?
                .with_size(scene.width, scene.height)?;
            Some((other, original.display().to_string()))
        }
        None if !args.set.is_empty() => Some((scene.clone(), "the scene as written".to_string())),
        None => None,
    };
    for assignment in &args.set {
        scene::overrides::apply(&mut scene, assignment).map_err(anyhow::Error::msg)?;
    }
    let record = |scene: &Scene| -> Result<RayTree> {
        Ok(record_pixel(scene, &args.mistakes.settings(scene)?, x, y))
    };
    // The scene's own recording first: its refusal names its profile.
    let tree = record(&scene)?;
    let before = match before {
        Some((other, what)) => Some((record(&other)?, what)),
        None => None,
    };
    Ok(Recorded {
        tree,
        scene,
        before,
    })
}
