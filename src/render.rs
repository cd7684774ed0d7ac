//! Whole images: every pixel traced with the same `trace` the debugger
//! records, rows shared among threads. Each pixel depends only on the scene,
//! so the bytes are the same whatever the thread count.

use std::sync::atomic::{AtomicBool, Ordering};

use anyhow::{Context, Result};
use image::RgbImage;
use rayon::prelude::*;

use crate::accel::{PACKET, ShadowCache};
use crate::camera::Viewport;
use crate::math::{Interval, Ray};
use crate::scene::{Scene, Settings};
use crate::trace::{NoRecorder, RayStats, Recorder, trace_found_in_row, trace_in_row};

/// A recorder that can follow a whole render: one per row, summed at the end.
pub trait RowRecorder: Recorder + Default + Send {
    /// Whether a render's primary rays may be traced in packets
    /// (`Accel::closest_each`): the same colours, but the query's cost is
    /// not counted, so only for a recorder that ignores it.
    const PACKETS: bool = false;

    fn merge(&mut self, other: Self);
}

impl RowRecorder for NoRecorder {
    const PACKETS: bool = true;

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
pub(crate) fn render_at<R: RowRecorder>(
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
pub(crate) fn render_unless<R: RowRecorder>(
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
    let recorder = if R::PACKETS {
        // A primary ray's hit range is (EPS, inf) whatever the mistakes
        // (`Rules::hit_range`).
        let range = Interval::in_front();
        for_each_row(
            &viewport,
            pixels,
            row_done,
            cancel,
            |rays, cache, rec, row| {
                let mut found = [None; PACKET];
                for (rays, row) in rays.chunks(PACKET).zip(row.chunks_mut(PACKET)) {
                    let found = &mut found[..rays.len()];
                    scene.accel.closest_each(&scene.objects, rays, range, found);
                    for ((ray, &found), pixel) in rays.iter().zip(&*found).zip(row) {
                        let color = trace_found_in_row(scene, settings, ray, found, cache, rec);
                        *pixel = mistakes.rgb8(color);
                    }
                }
            },
        )?
    } else {
        trace_rows(
            &viewport,
            pixels,
            row_done,
            cancel,
            |ray, cache, rec, pixel| {
                *pixel = mistakes.rgb8(trace_in_row(scene, settings, ray, cache, rec));
            },
        )?
    };
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

/// The one row loop of whole images: `pixels` (a row of the viewport's width
/// each) shared among threads by rows, each row's primary rays handed to
/// `pixel` with the row's shadow cache and recorder, the recorders summed.
/// Each row looks at `cancel` before it starts; `None` when it was set.
pub(crate) fn trace_rows<T: Send, R: RowRecorder>(
    viewport: &Viewport,
    pixels: &mut [T],
    row_done: &(dyn Fn() + Sync),
    cancel: &AtomicBool,
    pixel: impl Fn(&Ray, &mut ShadowCache, &mut R, &mut T) + Sync,
) -> Option<R> {
    for_each_row(
        viewport,
        pixels,
        row_done,
        cancel,
        |rays, cache, rec, row| {
            for (ray, out) in rays.iter().zip(row) {
                pixel(ray, cache, rec, out);
            }
        },
    )
}

/// `trace_rows` with the whole row's primary rays and pixels handed to `row`.
fn for_each_row<T: Send, R: RowRecorder>(
    viewport: &Viewport,
    pixels: &mut [T],
    row_done: &(dyn Fn() + Sync),
    cancel: &AtomicBool,
    row: impl Fn(&[Ray], &mut ShadowCache, &mut R, &mut [T]) + Sync,
) -> Option<R> {
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
