//! Whole-image renders off the UI thread. One render runs at a time; a newer
//! request waits as `pending` and replaces any older waiting one, so pressing
//! a toggle five times costs at most two renders. Results come back over a
//! channel tagged with their generation, and the app drops stale ones.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Arc;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::mpsc::{Receiver, Sender, channel};
use std::thread;
use std::time::{Duration, Instant};

use image::RgbImage;

use crate::render::{render, render_at};
use crate::scene::Scene;
use crate::terms::{TermImages, render_terms};
use crate::trace::NoRecorder;

/// What to render: the image alone, or every term (which includes the image).
#[derive(Clone)]
pub struct Request {
    pub generation: u64,
    pub scene: Arc<Scene>,
    pub terms: bool,
}

/// A finished render.
pub enum Output {
    Image(RgbImage),
    Terms(TermImages),
}

pub struct Finished {
    pub generation: u64,
    pub output: Result<Output, String>,
    pub elapsed: Duration,
}

/// How far the running render is, for the progress indicator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Progress {
    pub rows_done: u32,
    pub rows: u32,
}

struct Running {
    rows_done: Arc<AtomicU32>,
    rows: u32,
}

/// Starts renders and collects their results.
pub struct Renderer {
    /// Render on the caller's thread (tests): results are ready at once.
    sync: bool,
    sender: Sender<Finished>,
    receiver: Receiver<Finished>,
    /// Quick low-resolution images sent ahead of a large render.
    previews: (Sender<Preview>, Receiver<Preview>),
    running: Option<Running>,
    pending: Option<Request>,
}

impl Renderer {
    pub fn new(sync: bool) -> Self {
        let (sender, receiver) = channel();
        Self {
            sync,
            sender,
            receiver,
            previews: channel(),
            running: None,
            pending: None,
        }
    }

    /// Renders `request` now, or after the running render ends.
    pub fn request(&mut self, request: Request) {
        if self.running.is_some() {
            self.pending = Some(request);
        } else {
            self.start(request);
        }
    }

    pub fn progress(&self) -> Option<Progress> {
        self.running.as_ref().map(|r| Progress {
            rows_done: r.rows_done.load(Ordering::Relaxed),
            rows: r.rows,
        })
    }

    pub fn busy(&self) -> bool {
        self.running.is_some() || self.pending.is_some()
    }

    /// A preview that came in, if any. It is sent before its render's result,
    /// so draining previews before results never shows a stale one.
    pub fn poll_preview(&mut self) -> Option<Preview> {
        self.previews.1.try_recv().ok()
    }

    /// A finished render, if any; starts the pending one when the last ends.
    pub fn poll(&mut self) -> Option<Finished> {
        let finished = self.receiver.try_recv().ok()?;
        self.running = None;
        if let Some(next) = self.pending.take() {
            self.start(next);
        }
        Some(finished)
    }

    /// Blocks until a render finishes (tests and benchmarks).
    pub fn wait(&mut self) -> Option<Finished> {
        self.running.as_ref()?;
        let finished = self.receiver.recv().ok()?;
        self.running = None;
        if let Some(next) = self.pending.take() {
            self.start(next);
        }
        Some(finished)
    }

    fn start(&mut self, request: Request) {
        let rows_done = Arc::new(AtomicU32::new(0));
        self.running = Some(Running {
            rows_done: rows_done.clone(),
            rows: request.scene.height,
        });
        let sender = self.sender.clone();
        let previews = self.previews.0.clone();
        let preview = !self.sync && !request.terms;
        let job = move || {
            let started = Instant::now();
            if preview && let Some(image) = preview_image(&request.scene) {
                let _ = previews.send(Preview {
                    generation: request.generation,
                    image,
                });
            }
            let output = catch_unwind(AssertUnwindSafe(|| run(&request, &rows_done)))
                .map_err(|payload| panic_message(payload.as_ref()));
            let elapsed = started.elapsed();
            let _ = sender.send(Finished {
                generation: request.generation,
                output,
                elapsed,
            });
        };
        if self.sync {
            job();
        } else {
            thread::Builder::new()
                .name("raystep-render".into())
                .spawn(job)
                .expect("cannot start the render thread");
        }
    }
}

/// A render sent ahead of a large image, scaled up to its size.
pub struct Preview {
    pub generation: u64,
    pub image: RgbImage,
}

/// Images with more pixels than this get a preview first.
const PREVIEW_ABOVE: u32 = 60_000;
/// About how many pixels a preview traces: a terminal's worth.
const PREVIEW_PIXELS: u32 = 20_000;

/// The scene rendered at about terminal resolution and scaled up (nearest
/// neighbour) to its own size, or `None` when the scene is small anyway.
fn preview_image(scene: &Scene) -> Option<RgbImage> {
    let (width, height) = (scene.width, scene.height);
    if width * height <= PREVIEW_ABOVE {
        return None;
    }
    let step = ((width * height) as f64 / PREVIEW_PIXELS as f64)
        .sqrt()
        .ceil() as u32;
    let (small_w, small_h) = (width.div_ceil(step), height.div_ceil(step));
    let small = catch_unwind(AssertUnwindSafe(|| {
        render_at::<NoRecorder>(scene, small_w, small_h, &|| {}).0
    }))
    .ok()?;
    Some(RgbImage::from_fn(width, height, |x, y| {
        *small.get_pixel((x / step).min(small_w - 1), (y / step).min(small_h - 1))
    }))
}

fn run(request: &Request, rows_done: &AtomicU32) -> Output {
    let tick = || {
        rows_done.fetch_add(1, Ordering::Relaxed);
    };
    if request.terms {
        Output::Terms(render_terms(&request.scene, &tick))
    } else {
        Output::Image(render::<NoRecorder>(&request.scene, &tick).0)
    }
}

/// A render thread's panic as a message for the status line.
fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    let text = payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown panic".into());
    format!("the render failed: {text}")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn seven_rays(width: u32, height: u32) -> Scene {
        let text = crate::cli::DEFAULT_SCENE;
        let scene = crate::scene::parse(std::path::Path::new("seven-rays.toml"), text).unwrap();
        scene.with_size(width, height).unwrap()
    }

    #[test]
    fn large_images_get_a_preview_of_their_own_size() {
        // 400 x 300 = 120,000 pixels > 60,000: step = ceil(sqrt(120,000 / 20,000))
        // = ceil(2.45) = 3, so the preview traces 134 x 100 and each of its
        // pixels fills a 3 x 3 block.
        let scene = seven_rays(400, 300);
        let preview = preview_image(&scene).unwrap();
        assert_eq!(preview.dimensions(), (400, 300));
        assert_eq!(preview.get_pixel(0, 0), preview.get_pixel(2, 2));
        let small = render_at::<NoRecorder>(&scene, 134, 100, &|| {}).0;
        assert_eq!(preview.get_pixel(123, 77), small.get_pixel(41, 25));
    }

    #[test]
    fn small_images_need_no_preview() {
        assert!(preview_image(&seven_rays(161, 121)).is_none());
    }
}
