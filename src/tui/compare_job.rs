//! `--rays`: the pixel shown compared with your rays of it off the UI
//! thread. The comparison (the catalogue of mistakes included) takes
//! seconds on a pixel of 100,000 logged rays, so it runs on a thread of its
//! own and keys are answered meanwhile. One comparison runs at a time; a
//! newer request replaces any older one still waiting, and results come
//! back tagged with their generation, so a superseded one (the user has
//! moved on) is dropped and can never be shown.

use std::sync::mpsc::{Receiver, Sender, channel};
use std::sync::{Arc, Mutex};
use std::thread;

use raystep_engine::record::RayTree;
use raystep_engine::scene::Scene;
use raystep_model::mistakes::{Mistake, Mistakes};
use raystep_tools::divergence::{Consistent, OurRays, PixelReport, Tolerance, compare_pixel};
use raystep_tools::raylog::LoggedRay;

/// One pixel to compare.
pub(crate) struct Request {
    pub(crate) generation: u64,
    pub(crate) scene: Arc<Scene>,
    /// The pixel as traced now.
    pub(crate) tree: RayTree,
    /// Your rays of it.
    pub(crate) yours: Arc<Vec<LoggedRay>>,
    pub(crate) tolerance: Tolerance,
    /// The whole log's verdict on the pixel, which a pixel traced as the
    /// scene says takes when it differs.
    pub(crate) verdict: (Vec<Mistake>, Vec<Consistent>),
}

impl Request {
    /// The pixel traced beside your rays of it.
    fn compare(self) -> PixelReport {
        let traced_as_scene = self.tree.mistakes == Mistakes::NONE;
        let ours = OurRays::of(self.tree);
        let yours = Vec::clone(&self.yours);
        let mut report = compare_pixel(&self.scene, yours, &ours, &self.tolerance);
        // Traced as the scene says (no mistake turned on), the pixel has
        // the whole log's verdict: a name needs every logged pixel.
        if traced_as_scene && !report.matches {
            (report.mistakes, report.consistent) = self.verdict;
        }
        report
    }
}

/// A finished comparison, with the generation it was asked for.
type Compared = (u64, PixelReport);

/// Starts comparisons and collects their results.
pub(crate) struct Comparer {
    /// Compare on the caller's thread (tests): results are ready at once.
    sync: bool,
    /// The request waiting for the worker, replaced by a newer one.
    waiting: Arc<Mutex<Option<Request>>>,
    /// Wakes the worker (started at the first request).
    wake: Option<Sender<()>>,
    results: (Sender<Compared>, Receiver<Compared>),
}

impl Comparer {
    pub(crate) fn new(sync: bool) -> Comparer {
        Comparer {
            sync,
            waiting: Arc::new(Mutex::new(None)),
            wake: None,
            results: channel(),
        }
    }

    /// Compares `request`'s pixel, in place of any request still waiting.
    pub(crate) fn request(&mut self, request: Request) {
        if self.sync {
            let generation = request.generation;
            let _ = self.results.0.send((generation, request.compare()));
            return;
        }
        *self.waiting.lock().unwrap_or_else(|e| e.into_inner()) = Some(request);
        let wake = self.wake.get_or_insert_with(|| {
            let (wake, woken) = channel::<()>();
            let (waiting, results) = (self.waiting.clone(), self.results.0.clone());
            thread::Builder::new()
                .name("raystep-compare".into())
                .spawn(move || {
                    // Ends when the comparer is dropped (its sender with it).
                    while woken.recv().is_ok() {
                        let next = waiting.lock().unwrap_or_else(|e| e.into_inner()).take();
                        let Some(request) = next else { continue };
                        let generation = request.generation;
                        if results.send((generation, request.compare())).is_err() {
                            return;
                        }
                    }
                })
                .expect("cannot start the comparing thread");
            wake
        });
        let _ = wake.send(());
    }

    /// The results that came back, oldest first.
    pub(crate) fn poll(&self) -> Option<Compared> {
        self.results.1.try_recv().ok()
    }
}
