//! How much of a log `compare --rays` holds, whatever the log: a student's
//! tracer with no depth limit logs paths thousands of steps deep (a
//! runaway recursion: P, P/R, P/R/R, ... 8000 deep took 2.6 GB), and one
//! with no ray budget a million rays of one pixel (2.1 GB). Rays that ours
//! can never cast are counted, not compared one by one:
//!
//! - a ray more than one level deeper than `max_depth` allows (ours never
//!   casts past depth `max_depth`, MODEL §5; the first level past it is
//!   kept, and each of its rays is the difference, "only yours");
//! - a shown pixel's rays past the most our tree can hold, `max_rays`
//!   rays and a shadow ray per light for each (MODEL §5), or past
//!   `HELD_RAYS` over all the shown pixels.
//!
//! And the catalogue's trees are recorded within `CATALOGUE_RAYS` rays
//! (`CatalogueBudget`): past it, the mistakes left are not tried, and the
//! report says so.

use crate::raylog::{LoggedRay, RayPath};
use raystep_engine::scene::Scene;

/// The rays held over all the shown pixels of a log: about 400 bytes
/// each with their alignment (docs/RAYLOG.md, "Memory").
pub const HELD_RAYS: usize = 1 << 18;

/// The rays of our trees recorded to try the catalogue, over a whole log.
pub const CATALOGUE_RAYS: usize = 1 << 20;

/// A shown pixel's rays that were counted, not held.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CountedOnly {
    /// Rays deeper than `max_depth + 1`, and the deepest one's depth.
    pub deeper: usize,
    pub deepest: usize,
    /// Rays past the most our tree can hold, or past `HELD_RAYS`.
    pub over: usize,
}

impl CountedOnly {
    pub fn total(&self) -> usize {
        self.deeper + self.over
    }
}

/// What a log's rays may take.
pub(crate) struct Holding {
    /// The most reflected and transmitted steps of a path held.
    branches: usize,
    /// The most rays held for one pixel.
    per_pixel: usize,
    /// Rays held so far over all the shown pixels.
    held: usize,
}

impl Holding {
    pub(crate) fn new(scene: &Scene) -> Self {
        let settings = &scene.settings;
        // Depth max_depth has max_depth - 1 steps: one level more is kept.
        let branches = settings.max_depth as usize;
        let per_pixel = (settings.max_rays as usize).saturating_mul(1 + scene.lights.len());
        Self {
            branches,
            per_pixel,
            held: 0,
        }
    }

    /// Whether `ray` is deeper than any held; counted in `counted` if so.
    pub(crate) fn too_deep(&self, ray: &LoggedRay, counted: &mut CountedOnly) -> bool {
        let branches = ray.path.branches();
        if branches <= self.branches {
            return false;
        }
        counted.deeper += 1;
        counted.deepest = counted.deepest.max(branches + 1);
        true
    }

    /// Whether one more ray of a pixel that holds `held` may be held; if
    /// not it is counted in `counted`.
    pub(crate) fn take(&mut self, held: usize, counted: &mut CountedOnly) -> bool {
        if held >= self.per_pixel || self.held >= HELD_RAYS {
            counted.over += 1;
            return false;
        }
        self.held += 1;
        true
    }

    /// `ray`'s path cut to the first level past ours: for a ray only
    /// counted, which is only yours either way (its ancestors' paths are
    /// never cast by ours).
    pub(crate) fn shallow(&self, ray: &mut LoggedRay) {
        if ray.path.branches() > self.branches {
            ray.path = RayPath::of(ray.path.steps[..=self.branches].to_vec());
        }
    }
}

/// The rays of our trees the catalogue may still record.
pub(crate) struct CatalogueBudget {
    left: usize,
    /// Whether a mistake was left untried.
    pub(crate) stopped: bool,
}

impl CatalogueBudget {
    pub(crate) fn new(rays: usize) -> Self {
        Self {
            left: rays,
            stopped: false,
        }
    }

    /// Whether another tree may be recorded; `false` (and stopped) once
    /// the budget is spent.
    pub(crate) fn allows(&mut self) -> bool {
        if self.left == 0 {
            self.stopped = true;
        }
        !self.stopped
    }

    /// A tree of `rays` rays was recorded.
    pub(crate) fn spend(&mut self, rays: usize) {
        self.left = self.left.saturating_sub(rays);
    }
}
