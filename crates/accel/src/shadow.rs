//! The shadow query: every crossing of a shadow segment, with the object
//! that blocked the same light last time tried first. In a shadow,
//! neighbouring points of a row are usually blocked by the same object, and
//! one primitive test then settles S = 0 (MODEL §4) without the walk. Only
//! the cost changes, never S.

use std::ops::ControlFlow;

use super::{Accel, Cost};
use raystep_model::math::{Interval, Ray};
use raystep_model::object::Object;

/// The last opaque blocker found for each light, kept along a row of pixels.
#[derive(Clone, Debug, Default)]
pub struct ShadowCache {
    blockers: Vec<Option<usize>>,
}

impl ShadowCache {
    #[inline]
    fn blocker(&self, light: usize) -> Option<usize> {
        self.blockers.get(light).copied().flatten()
    }

    #[inline]
    fn remember(&mut self, light: usize, object: usize) {
        if self.blockers.len() <= light {
            self.blockers.resize(light + 1, None);
        }
        self.blockers[light] = Some(object);
    }

    /// The light reached the last point: past the edge of a shadow, its
    /// blocker is not worth trying on the next pixels.
    #[inline]
    fn forget(&mut self, light: usize) {
        if let Some(blocker) = self.blockers.get_mut(light) {
            *blocker = None;
        }
    }
}

impl Accel {
    /// `crossings` of the segment `range` towards light `light`, where
    /// `visit` breaks at an opaque crossing (which settles S = 0). With a
    /// `cache`, the object `visit` last broke at for this light is tried
    /// first, and the query remembers where `visit` breaks, or forgets the
    /// light when it does not. Without one (a recording, which lists every
    /// blocker), the crossings come exactly as `crossings` gives them.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub fn shadow_crossings(
        &self,
        objects: &[Object],
        ray: &Ray,
        range: Interval,
        light: usize,
        cache: Option<&mut ShadowCache>,
        cost: &mut Cost,
        visit: &mut impl FnMut(usize, f64) -> ControlFlow<()>,
    ) {
        let Some(cache) = cache else {
            self.crossings(objects, ray, range, cost, visit);
            return;
        };
        if let Some(object) = cache.blocker(light) {
            cost.primitives += 1;
            let roots = match self.positions[object] {
                u32::MAX => objects[object].shape.roots(ray, range),
                position => self.shapes[position as usize].roots(objects, object, ray, range),
            };
            if let Some(&t) = roots.as_slice().first() {
                // It was opaque when remembered, so `visit` breaks again.
                let _ = visit(object, t);
                return;
            }
        }
        let mut blocker = None;
        let mut remembering = |object, t| {
            let flow = visit(object, t);
            if flow.is_break() {
                blocker = Some(object);
            }
            flow
        };
        // Passed by reference: moved in by value, the closure's fields were
        // written one at a time and at once read back two at a time to be
        // copied, a read the CPU cannot serve from its pending writes, so it
        // waited on every shadow ray (tree -13 %).
        self.crossings(objects, ray, range, cost, &mut remembering);
        match blocker {
            Some(object) => cache.remember(light, object),
            None => cache.forget(light),
        }
    }
}
