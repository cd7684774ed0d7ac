//! Whole-image renders off the UI thread. One render runs at a time; a newer
//! request cancels it and waits as `pending`, replacing any older waiting
//! one, so pressing a toggle five times costs one render and a row or so of
//! each cancelled one. Quitting cancels the running render rather than wait
//! for it. Results come back over a channel tagged with their generation,
//! and the app drops stale ones.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};
use std::sync::mpsc::{Receiver, Sender, channel};
use std::thread;
use std::time::{Duration, Instant};

use image::RgbImage;

use raystep_engine::render::render_unless;
use raystep_engine::scene::{Scene, Settings};
use raystep_engine::terms::{TermImages, render_terms_unless};
use raystep_engine::trace::NoRecorder;

/// What to render: the image alone, or every term (which includes the image).
#[derive(Clone)]
pub(crate) struct Request {
    pub(crate) generation: u64,
    pub(crate) scene: Arc<Scene>,
    /// The settings to trace with: the scene's own or the user's toggles.
    pub(crate) settings: Settings,
    pub(crate) terms: bool,
}

/// A finished render.
pub(crate) enum Output {
    Image(RgbImage),
    Terms(TermImages),
    /// Stopped early by a newer request or by quitting: nothing to show.
    Cancelled,
}

pub(crate) struct Finished {
    pub(crate) generation: u64,
    pub(crate) output: Result<Output, String>,
    pub(crate) elapsed: Duration,
}

/// How far the running render is, for the progress indicator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Progress {
    pub(crate) rows_done: u32,
    pub(crate) rows: u32,
}

struct Running {
    rows_done: Arc<AtomicU32>,
    rows: u32,
    /// Set to stop the render at its next row.
    cancel: Arc<AtomicBool>,
}

/// Starts renders and collects their results.
pub(crate) struct Renderer {
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
    pub(crate) fn new(sync: bool) -> Self {
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

    /// Renders `request` now, or as soon as the running render, cancelled
    /// because this one supersedes it, has stopped.
    pub(crate) fn request(&mut self, request: Request) {
        if let Some(running) = &self.running {
            running.cancel.store(true, Ordering::Relaxed);
            self.pending = Some(request);
        } else {
            self.start(request);
        }
    }

    /// Drops the pending request and stops the running render at its next
    /// row, without waiting for it.
    pub(crate) fn cancel(&mut self) {
        self.pending = None;
        if let Some(running) = &self.running {
            running.cancel.store(true, Ordering::Relaxed);
        }
    }

    pub(crate) fn progress(&self) -> Option<Progress> {
        self.running.as_ref().map(|r| Progress {
            rows_done: r.rows_done.load(Ordering::Relaxed),
            rows: r.rows,
        })
    }

    pub(crate) fn busy(&self) -> bool {
        self.running.is_some() || self.pending.is_some()
    }

    /// A preview that came in, if any. It is sent before its render's result,
    /// so draining previews before results never shows a stale one.
    pub(crate) fn poll_preview(&mut self) -> Option<Preview> {
        self.previews.1.try_recv().ok()
    }

    /// A finished render, if any; starts the pending one when the last ends.
    pub(crate) fn poll(&mut self) -> Option<Finished> {
        let finished = self.receiver.try_recv().ok()?;
        self.running = None;
        if let Some(next) = self.pending.take() {
            self.start(next);
        }
        Some(finished)
    }

    /// Blocks until a render finishes (the unit tests).
    #[cfg(test)]
    pub(crate) fn wait(&mut self) -> Option<Finished> {
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
        let cancel = Arc::new(AtomicBool::new(false));
        self.running = Some(Running {
            rows_done: rows_done.clone(),
            rows: request.scene.height,
            cancel: cancel.clone(),
        });
        let sender = self.sender.clone();
        let previews = self.previews.0.clone();
        let preview = !self.sync && !request.terms;
        let job = move || {
            let started = Instant::now();
            if preview
                && let Some(image) = preview_image(&request.scene, &request.settings, &cancel)
            {
                let _ = previews.send(Preview {
                    generation: request.generation,
                    image,
                });
            }
            let output = catch_unwind(AssertUnwindSafe(|| run(&request, &rows_done, &cancel)))
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

/// A dropped renderer (the app quit) leaves no render running behind it.
impl Drop for Renderer {
    fn drop(&mut self) {
        self.cancel();
    }
}

/// A render sent ahead of a large image, scaled up to its size.
pub(crate) struct Preview {
    pub(crate) generation: u64,
    pub(crate) image: RgbImage,
}

/// Images with more pixels than this get a preview first.
const PREVIEW_ABOVE: u32 = 60_000;
/// About how many pixels a preview traces: a terminal's worth.
const PREVIEW_PIXELS: u32 = 20_000;

/// The scene rendered at about terminal resolution and scaled up (nearest
/// neighbour) to its own size, or `None` when the scene is small anyway or
/// the render was cancelled.
fn preview_image(scene: &Scene, settings: &Settings, cancel: &AtomicBool) -> Option<RgbImage> {
    let (width, height) = (scene.width, scene.height);
    if width * height <= PREVIEW_ABOVE {
        return None;
    }
    let step = ((width * height) as f64 / PREVIEW_PIXELS as f64)
        .sqrt()
        .ceil() as u32;
    let (small_w, small_h) = (width.div_ceil(step), height.div_ceil(step));
    let (small, _) = catch_unwind(AssertUnwindSafe(|| {
        render_unless::<NoRecorder>(scene, settings, (small_w, small_h), &|| {}, cancel)
    }))
    .ok()
    .flatten()?;
    Some(RgbImage::from_fn(width, height, |x, y| {
        *small.get_pixel((x / step).min(small_w - 1), (y / step).min(small_h - 1))
    }))
}

fn run(request: &Request, rows_done: &AtomicU32, cancel: &AtomicBool) -> Output {
    let tick = || {
        rows_done.fetch_add(1, Ordering::Relaxed);
    };
    let (scene, settings) = (&request.scene, &request.settings);
    let output = if request.terms {
        render_terms_unless::<NoRecorder>(scene, settings, &tick, cancel)
            .map(|(terms, _)| Output::Terms(terms))
    } else {
        let size = (scene.width, scene.height);
        render_unless::<NoRecorder>(scene, settings, size, &tick, cancel)
            .map(|(image, _)| Output::Image(image))
    };
    output.unwrap_or(Output::Cancelled)
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
        let scene = raystep_engine::scene::builtin::load_file_or_builtin(None).unwrap();
        scene.with_size(width, height).unwrap()
    }

    #[test]
    fn large_images_get_a_preview_of_their_own_size() {
        // 400 x 300 = 120,000 pixels > 60,000: step = ceil(sqrt(120,000 / 20,000))
        // = ceil(2.45) = 3, so the preview traces 134 x 100 and each of its
        // pixels fills a 3 x 3 block.
        let scene = seven_rays(400, 300);
        let preview = preview_image(&scene, &scene.settings, &AtomicBool::new(false)).unwrap();
        assert_eq!(preview.dimensions(), (400, 300));
        assert_eq!(preview.get_pixel(0, 0), preview.get_pixel(2, 2));
        let small = raystep_engine::render::render_at::<NoRecorder>(
            &scene,
            &scene.settings,
            (134, 100),
            &|| {},
        )
        .0;
        assert_eq!(preview.get_pixel(123, 77), small.get_pixel(41, 25));
    }

    #[test]
    fn a_cancelled_render_stops_within_a_row_per_thread() {
        // Four threads; the fifth finished row sets the flag. Each of the
        // other three may be inside a row then and finishes it; every row
        // after looks at the flag first. So at most 5 + 3 = 8 of 2000 rows.
        let scene = seven_rays(200, 2000);
        let rows = AtomicU32::new(0);
        let cancel = AtomicBool::new(false);
        let tick = || {
            if rows.fetch_add(1, Ordering::Relaxed) + 1 == 5 {
                cancel.store(true, Ordering::Relaxed);
            }
        };
        let result = raystep_engine::render::with_threads(Some(4), || {
            render_unless::<NoRecorder>(&scene, &scene.settings, (200, 2000), &tick, &cancel)
        })
        .unwrap();
        assert!(result.is_none());
        let traced = rows.load(Ordering::Relaxed);
        assert!((5..=8).contains(&traced), "{traced} rows traced");
    }

    #[test]
    fn a_term_render_cancelled_before_it_starts_traces_nothing() {
        let rows = AtomicU32::new(0);
        let tick = || {
            rows.fetch_add(1, Ordering::Relaxed);
        };
        let scene = seven_rays(161, 121);
        let result = render_terms_unless::<NoRecorder>(
            &scene,
            &scene.settings,
            &tick,
            &AtomicBool::new(true),
        );
        assert!(result.is_none());
        assert_eq!(rows.load(Ordering::Relaxed), 0);
    }

    #[test]
    fn a_newer_request_cancels_the_running_render() {
        // 4000 x 3000 pixels take seconds; the newer small one, milliseconds.
        let mut renderer = Renderer::new(false);
        let request = |generation, scene: Scene| Request {
            generation,
            settings: scene.settings,
            scene: Arc::new(scene),
            terms: false,
        };
        renderer.request(request(1, seven_rays(4000, 3000)));
        let deadline = Instant::now() + Duration::from_secs(30);
        while renderer.progress().is_some_and(|p| p.rows_done == 0) {
            assert!(Instant::now() < deadline, "the big render never started");
            thread::sleep(Duration::from_millis(5));
        }
        renderer.request(request(2, seven_rays(161, 121)));
        let first = renderer.wait().unwrap();
        assert_eq!(first.generation, 1);
        assert!(matches!(first.output, Ok(Output::Cancelled)));
        let second = renderer.wait().unwrap();
        assert_eq!(second.generation, 2);
        let Ok(Output::Image(image)) = second.output else {
            panic!("the newer render did not finish");
        };
        assert_eq!(image.dimensions(), (161, 121));
    }

    #[test]
    fn small_images_need_no_preview() {
        assert!(
            preview_image(
                &seven_rays(161, 121),
                &Default::default(),
                &AtomicBool::new(false)
            )
            .is_none()
        );
    }
}
