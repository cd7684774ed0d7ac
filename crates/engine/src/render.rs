//! Whole images: every pixel traced with the same `trace` the debugger
//! records, rows shared among threads. Each pixel depends only on the scene,
//! so the bytes are the same whatever the thread count.

use std::sync::atomic::{AtomicBool, Ordering};

use anyhow::{Context, Result};
use image::RgbImage;
use rayon::prelude::*;

use crate::scene::{Scene, Settings};
use crate::trace::{Nearest, NoRecorder, RayStats, Recorder, trace_in_row};
use raystep_accel::{PACKET, ShadowCache};
use raystep_model::camera::Viewport;
use raystep_model::math::{Interval, Ray};

/// A recorder that can follow a whole render: one per row, summed at the end.
pub trait RowRecorder: Recorder + Default + Send {
    /// How a render with this recorder finds its primary rays' hits: in
    /// packets only for a recorder that ignores the queries' cost.
    const PRIMARY_WALK: PrimaryWalk = PrimaryWalk::OneByOne;

    fn merge(&mut self, other: Self);
}

impl RowRecorder for NoRecorder {
    const PRIMARY_WALK: PrimaryWalk = PrimaryWalk::Packets;

    fn merge(&mut self, _other: Self) {}
}

impl RowRecorder for RayStats {
    fn merge(&mut self, other: Self) {
        self.add(&other);
    }
}

/// Renders the scene at its size, traced with `settings`. `row_done` is
/// called once per finished row (from any thread), for progress display.
pub fn render<R: RowRecorder>(
    scene: &Scene,
    settings: &Settings,
    row_done: &(dyn Fn() + Sync),
) -> (RgbImage, R) {
    render_at(scene, settings, (scene.width, scene.height), row_done)
}

/// Renders the scene at another size with the same field of view (a quick
/// preview; its pixels are not the scene's own).
pub fn render_at<R: RowRecorder>(
    scene: &Scene,
    settings: &Settings,
    size: (u32, u32),
    row_done: &(dyn Fn() + Sync),
) -> (RgbImage, R) {
    render_unless(scene, settings, size, row_done, &AtomicBool::new(false))
        .expect("a render nobody can cancel finishes")
}

/// Renders at `size` unless `cancel` is set: each row looks at the flag
/// before it starts, so a cancelled render stops within one row per thread,
/// and gives `None`. Uncancelled, the bytes are those of `render_at`.
pub fn render_unless<R: RowRecorder>(
    scene: &Scene,
    settings: &Settings,
    (width, height): (u32, u32),
    row_done: &(dyn Fn() + Sync),
    cancel: &AtomicBool,
) -> Option<(RgbImage, R)> {
    let mut image = RgbImage::new(width, height);
    let (pixels, _) = image.as_chunks_mut::<3>();
    let mistakes = settings.mistakes;
    let viewport = viewport(scene, settings, (width, height));
    let recorder = trace_rows(
        scene,
        &viewport,
        R::PRIMARY_WALK,
        pixels,
        row_done,
        cancel,
        |ray, nearest, cache, rec, pixel| {
            *pixel = mistakes.rgb8(trace_in_row(scene, settings, ray, nearest, cache, rec));
        },
    )?;
    Some((image, recorder))
}

/// Which primary ray each pixel of an image of `size` gets when `scene` is
/// traced with `settings`: the camera's, with the settings' pixel mistakes
/// (MODEL §8). Renders and recordings both ask here, so they agree.
pub fn viewport(scene: &Scene, settings: &Settings, (width, height): (u32, u32)) -> Viewport {
    scene
        .camera
        .viewport(width, height)
        .with_mistakes(settings.mistakes)
}

/// Whether a row's primary rays find their nearest hits together, in
/// packets (`Accel::closest_each`): the same hits, but the queries' cost is
/// not counted, so only where no recorder of the render counts it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PrimaryWalk {
    Packets,
    OneByOne,
}

/// The one row loop of whole images: `pixels` (a row of the viewport's width
/// each) shared among threads by rows, each row's primary rays handed to
/// `pixel` with their nearest hits in `scene` where `walk` finds them
/// together, the row's shadow cache and recorder; the recorders summed.
/// Each row looks at `cancel` before it starts; `None` when it was set.
pub fn trace_rows<T: Send, R: RowRecorder>(
    scene: &Scene,
    viewport: &Viewport,
    walk: PrimaryWalk,
    pixels: &mut [T],
    row_done: &(dyn Fn() + Sync),
    cancel: &AtomicBool,
    pixel: impl Fn(&Ray, Nearest<'_>, &mut ShadowCache, &mut R, &mut T) + Sync,
) -> Option<R> {
    // A primary ray's hit range is (EPS, inf) whatever the mistakes
    // (`Rules::hit_range`).
    let range = Interval::in_front();
    let row = |rays: &[Ray], cache: &mut ShadowCache, rec: &mut R, row: &mut [T]| {
        let mut found = [None; PACKET];
        for (rays, row) in rays.chunks(PACKET).zip(row.chunks_mut(PACKET)) {
            if walk == PrimaryWalk::Packets {
                scene
                    .accel
                    .closest_each(&scene.objects, rays, range, &mut found[..rays.len()]);
            }
            for ((ray, found), out) in rays.iter().zip(&found).zip(row) {
                let nearest = match walk {
                    PrimaryWalk::Packets => Nearest::Found(found),
                    PrimaryWalk::OneByOne => Nearest::ToFind,
                };
                pixel(ray, nearest, cache, rec, out);
            }
        }
    };
    let recorder = pixels
        .par_chunks_mut(viewport.width as usize)
        .enumerate()
        .map(|(y, pixels)| {
            let mut rec = R::default();
            if cancel.load(Ordering::Relaxed) {
                return rec;
            }
            let mut cache = ShadowCache::default();
            row(&viewport.row(y as u32), &mut cache, &mut rec, pixels);
            row_done();
            rec
        })
        .reduce(R::default, |mut a, b| {
            a.merge(b);
            a
        });
    (!cancel.load(Ordering::Relaxed)).then_some(recorder)
}

/// Runs `work` on a pool of `threads` threads, or on all cores when `None`.
pub fn with_threads<T: Send>(threads: Option<usize>, work: impl FnOnce() -> T + Send) -> Result<T> {
    match threads {
        None => Ok(work()),
        Some(n) => {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .context("cannot start threads")?;
            Ok(pool.install(work))
        }
    }
}
