//! The renders a comparison needs that depend on the scene alone: raystep's
//! own image (with the object under each pixel), the scene at twice the
//! size (what it shows inside each pixel, for anti-aliasing) and the scene
//! rendered under each set of mistakes the ranking tries. Made once per scene and shared by
//! every image compared with it: `grade` compares a whole class against one
//! set, and students who made the same mistake share the renders of the
//! combinations the ranking tries on top of it.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, PoisonError};

use image::RgbImage;

use super::reference::{self, Reference};
use super::{metrics, sub_pixel};
use raystep_engine::render::{render, render_at, viewport};
use raystep_engine::scene::Scene;
use raystep_engine::trace::{NoRecorder, trace};
use raystep_model::mistakes::Mistakes;

/// The most the mistaken renders kept may take, in bytes: 300 renders of a
/// 320 x 240 scene, 7 of the largest image compared. Past it a render is
/// made each time it is asked for: memory stays bounded whatever the image's
/// size, at the price of rendering again (a comparison asks for at most 3
/// renders twice).
const MAX_KEPT_BYTES: usize = 96 << 20;

/// One scene's renders, at the scene's size and with its settings.
pub(crate) struct SceneRenders<'a> {
    scene: &'a Scene,
    reference: Reference,
    /// Each set of mistakes rendered so far.
    mistaken: Mutex<HashMap<Mistakes, Arc<RgbImage>>>,
    /// The render at twice the size, once asked for.
    fine: Mutex<Option<Arc<RgbImage>>>,
}

impl<'a> SceneRenders<'a> {
    /// Renders the reference now; the mistaken renders as they are asked for.
    pub(crate) fn new(scene: &'a Scene) -> Self {
        SceneRenders {
            scene,
            reference: reference::render(scene, &scene.settings),
            mistaken: Mutex::new(HashMap::new()),
            fine: Mutex::new(None),
        }
    }

    pub(crate) fn scene(&self) -> &'a Scene {
        self.scene
    }

    pub(crate) fn reference(&self) -> &Reference {
        &self.reference
    }

    /// The scene rendered under `mistakes`, rendered the first time it is
    /// asked for, and kept while the renders kept fit in `MAX_KEPT_BYTES`. The lock is not held while rendering: a render runs on
    /// rayon's threads, which meanwhile may take up another comparison that
    /// asks for the same render, and would wait on itself. So two threads
    /// may both render it; the first render stored is kept, and both are
    /// the same bytes (a render depends on the scene alone).
    pub(crate) fn mistaken(&self, mistakes: Mistakes) -> Arc<RgbImage> {
        if let Some(image) = self.stored().get(&mistakes) {
            return Arc::clone(image);
        }
        let mut settings = self.scene.settings;
        settings.mistakes = mistakes;
        let image = Arc::new(render::<NoRecorder>(self.scene, &settings, &|| {}).0);
        let mut stored = self.stored();
        let kept: usize = stored.values().map(|i| i.as_raw().len()).sum();
        if !stored.contains_key(&mistakes) && kept + image.as_raw().len() > MAX_KEPT_BYTES {
            return image;
        }
        Arc::clone(stored.entry(mistakes).or_insert(image))
    }

    /// The scene at twice its size, with its settings: pixel (2x + i, 2y + j)
    /// is the ray through (x + (2i + 1) / 4, y + (2j + 1) / 4) of the image,
    /// a quarter point of pixel (x, y). Rendered the first time it is asked
    /// for, without holding the lock (as `mistaken`).
    pub(crate) fn fine(&self) -> Arc<RgbImage> {
        let stored = || self.fine.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some(image) = stored().as_ref() {
            return Arc::clone(image);
        }
        let size = (2 * self.scene.width, 2 * self.scene.height);
        let image =
            Arc::new(render_at::<NoRecorder>(self.scene, &self.scene.settings, size, &|| {}).0);
        Arc::clone(stored().get_or_insert(image))
    }

    /// What raystep's rays through pixel (x, y), `sub_pixel::BESIDE_CENTRE`
    /// away from its centre, see, as bytes: with the scene's settings and
    /// its size, as the reference's own rays.
    pub(crate) fn beside_centre(&self, x: u32, y: u32) -> [[u8; 3]; 4] {
        let (scene, settings) = (self.scene, &self.scene.settings);
        let viewport = viewport(scene, settings, (scene.width, scene.height));
        sub_pixel::BESIDE_CENTRE.map(|offset| {
            let ray = viewport.ray_beside(x, y, offset);
            settings
                .mistakes
                .rgb8(trace(scene, settings, &ray, &mut NoRecorder))
        })
    }

    /// How many sets of mistakes have been rendered.
    #[cfg(test)]
    pub(crate) fn rendered(&self) -> usize {
        self.stored().len()
    }

    fn stored(&self) -> std::sync::MutexGuard<'_, HashMap<Mistakes, Arc<RgbImage>>> {
        // A panic elsewhere cannot leave the map half-changed: keep using it.
        self.mistaken.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

impl metrics::InsidePixels for SceneRenders<'_> {
    fn fine(&self) -> Arc<RgbImage> {
        SceneRenders::fine(self)
    }

    fn beside_centre(&self, x: u32, y: u32) -> [[u8; 3]; 4] {
        SceneRenders::beside_centre(self, x, y)
    }
}
