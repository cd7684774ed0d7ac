//! The image-wide find (`f` then a key) off the UI thread: the pixels are
//! recorded one by one in reading order on a thread of their own, so keys
//! are answered while it runs. Dropping the job cancels it (at its next
//! pixel) and drops its result with the channel, so a stale find can never
//! move the cursor.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};
use std::sync::mpsc::{Receiver, channel};
use std::thread;

use crate::tui::action::Find;
use crate::tui::view::find;
use raystep_engine::record::{RayTree, record_pixel};
use raystep_engine::scene::{Scene, Settings};

/// The first pixel after the start that has what was looked for.
pub(crate) struct Found {
    pub(crate) pixel: (u32, u32),
    pub(crate) tree: RayTree,
    /// Its first matching event.
    pub(crate) event: usize,
}

/// A running find.
pub(crate) struct FindJob {
    /// The row of the pixel being recorded, for "row N of H".
    row: Arc<AtomicU32>,
    cancel: Arc<AtomicBool>,
    /// `Some(found)` or `None` (nothing in the image) once the scan ends.
    result: Receiver<Option<Found>>,
}

impl FindJob {
    /// Scans the image after `from` for `what` (`object`: the breakpoint
    /// object, see `find::first_event`): on the caller's thread when `sync` (tests), else on its own.
    pub(crate) fn start(
        scene: Arc<Scene>,
        settings: Settings,
        (what, object): (Find, Option<usize>),
        from: (u32, u32),
        sync: bool,
    ) -> FindJob {
        let row = Arc::new(AtomicU32::new(from.1));
        let cancel = Arc::new(AtomicBool::new(false));
        let (sender, result) = channel();
        let (job_row, job_cancel) = (row.clone(), cancel.clone());
        let job = move || {
            let size = (scene.width, scene.height);
            let mut found = None;
            for (x, y) in find::reading_order(from, size) {
                if job_cancel.load(Ordering::Relaxed) {
                    return;
                }
                job_row.store(y, Ordering::Relaxed);
                let tree = record_pixel(&scene, &settings, x, y);
                if let Some(event) = find::first_event(&tree, what, object) {
                    found = Some(Found {
                        pixel: (x, y),
                        tree,
                        event,
                    });
                    break;
                }
            }
            let _ = sender.send(found);
        };
        if sync {
            job();
        } else {
            thread::Builder::new()
                .name("raystep-find".into())
                .spawn(job)
                .expect("cannot start the find thread");
        }
        FindJob {
            row,
            cancel,
            result,
        }
    }

    /// The scan's outcome once it has ended: `Some(None)` when no pixel has it.
    pub(crate) fn poll(&self) -> Option<Option<Found>> {
        self.result.try_recv().ok()
    }

    /// The row being scanned, from 0.
    pub(crate) fn row(&self) -> u32 {
        self.row.load(Ordering::Relaxed)
    }
}

impl Drop for FindJob {
    fn drop(&mut self) {
        self.cancel.store(true, Ordering::Relaxed);
    }
}
