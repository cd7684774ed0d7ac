//! raystep's own render of the scene at the student's size: the bytes, and
//! the object each pixel's primary ray hits (the report names them).

use std::sync::atomic::AtomicBool;

use image::RgbImage;

use raystep_accel::Cost;
use raystep_engine::render::{PrimaryWalk, trace_rows, viewport};
use raystep_engine::scene::{Scene, Settings};
use raystep_engine::trace::{NoRecorder, Recorder, SurfaceHit, trace_in_row};
use raystep_model::math::Color;

pub(crate) struct Reference {
    pub(crate) image: RgbImage,
    /// The object each primary ray hits, `BACKGROUND` for none: 4 bytes a
    /// pixel, where `Option<usize>` took 16.
    objects: Vec<u32>,
}

/// In `Reference::objects`, a primary ray that hits nothing.
const BACKGROUND: u32 = u32::MAX;

impl Reference {
    /// The object the primary ray of (x, y) hits, `None` for the background.
    pub(crate) fn object_at(&self, x: u32, y: u32) -> Option<usize> {
        let object = self.objects[(y * self.image.width() + x) as usize];
        (object != BACKGROUND).then_some(object as usize)
    }
}

/// Renders `scene` traced with `settings` at its own size.
pub(crate) fn render(scene: &Scene, settings: &Settings) -> Reference {
    let (width, height) = (scene.width, scene.height);
    // Bytes and object side by side, 8 bytes a pixel: the colours in f64
    // and the objects as `Option<usize>` took 40.
    let mut pixels = vec![([0u8; 3], BACKGROUND); width as usize * height as usize];
    // Only the colour and the first object are kept: the query's cost
    // does not matter, so the primary rays go in packets as a render's do.
    trace_rows::<_, NoRecorder>(
        scene,
        &viewport(scene, settings, (width, height)),
        PrimaryWalk::Packets,
        &mut pixels,
        &|| {},
        &AtomicBool::new(false),
        |ray, nearest, cache, _, pixel| {
            let mut first = FirstHit::default();
            let color = trace_in_row(scene, settings, ray, nearest, cache, &mut first);
            let object = first.object.flatten().map_or(BACKGROUND, |o| {
                u32::try_from(o).expect("a scene has fewer than 2^32 - 1 objects")
            });
            *pixel = (settings.mistakes.rgb8(color), object);
        },
    )
    .expect("a render nobody can cancel finishes");
    let image = RgbImage::from_raw(width, height, pixels.iter().flat_map(|p| p.0).collect())
        .expect("3 bytes for each pixel");
    let objects = pixels.iter().map(|p| p.1).collect();
    Reference { image, objects }
}

/// The primary ray's object: the first hit or miss the tracer reports.
#[derive(Default)]
struct FirstHit {
    object: Option<Option<usize>>,
}

impl Recorder for FirstHit {
    fn hit(&mut self, hit: &SurfaceHit, _cost: Cost) {
        self.object.get_or_insert(Some(hit.object));
    }

    fn miss(&mut self, _background: Color, _cost: Cost) {
        self.object.get_or_insert(None);
    }
}
