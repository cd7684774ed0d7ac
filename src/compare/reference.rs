//! raystep's own render of the scene at the student's size: the bytes, and
//! the object each pixel's primary ray hits (the report names them).

use std::sync::atomic::AtomicBool;

use image::RgbImage;

use crate::accel::Cost;
use crate::math::Color;
use crate::render::{trace_rows, viewport};
use crate::scene::{Scene, Settings};
use crate::trace::{NoRecorder, Recorder, SurfaceHit, trace_in_row};

pub(crate) struct Reference {
    pub(crate) image: RgbImage,
    /// The object each primary ray hits, `None` for the background.
    pub(crate) objects: Vec<Option<usize>>,
}

impl Reference {
    pub(crate) fn object_at(&self, x: u32, y: u32) -> Option<usize> {
        self.objects[(y * self.image.width() + x) as usize]
    }
}

/// Renders `scene` traced with `settings` at its own size.
pub(crate) fn render(scene: &Scene, settings: &Settings) -> Reference {
    let (width, height) = (scene.width, scene.height);
    let mut pixels = vec![(Color::ZERO, None); width as usize * height as usize];
    trace_rows::<_, NoRecorder>(
        &viewport(scene, settings, (width, height)),
        &mut pixels,
        &|| {},
        &AtomicBool::new(false),
        |ray, cache, _, pixel| {
            let mut first = FirstHit::default();
            let color = trace_in_row(scene, settings, ray, cache, &mut first);
            *pixel = (color, first.object.flatten());
        },
    )
    .expect("a render nobody can cancel finishes");
    let image = RgbImage::from_fn(width, height, |x, y| {
        image::Rgb(settings.mistakes.rgb8(pixels[(y * width + x) as usize].0))
    });
    Reference {
        image,
        objects: pixels.into_iter().map(|p| p.1).collect(),
    }
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
