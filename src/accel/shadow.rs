//! The shadow query: every crossing of a shadow segment, with the object
//! that blocked the same light last time tried first. In a shadow,
//! neighbouring points of a row are usually blocked by the same object, and
//! one primitive test then settles S = 0 (MODEL §4) without the walk. Only
//! the cost changes, never S.

use std::ops::ControlFlow;

use super::{Accel, Cost};
use crate::math::{Interval, Ray};
use crate::object::Object;

/// The last opaque blocker found for each light, kept along a row of pixels.
#[derive(Clone, Debug, Default)]
pub(crate) struct ShadowCache {
    blockers: Vec<Option<usize>>,
}

impl ShadowCache {
    fn blocker(&self, light: usize) -> Option<usize> {
        self.blockers.get(light).copied().flatten()
    }

    fn remember(&mut self, light: usize, object: usize) {
        if self.blockers.len() <= light {
            self.blockers.resize(light + 1, None);
        }
        self.blockers[light] = Some(object);
    }

    /// The light reached the last point: past the edge of a shadow, its
    /// blocker is not worth trying on the next pixels.
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
    pub(crate) fn shadow_crossings(
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

#[cfg(test)]
mod tests {
    use std::path::Path;

    use glam::DVec3;

    use super::*;
    use crate::math::EPS;
    use crate::scene::{Scene, parse};

    /// S and the primitives tested for the shadow segment from `point` to
    /// the light at `light`, through the query the tracer uses.
    fn shadow(scene: &Scene, cache: &mut ShadowCache, point: DVec3, light: DVec3) -> (f64, u32) {
        let offset = light - point;
        let ray = Ray::new(point, offset / offset.length());
        let (mut s, mut cost) = (1.0, Cost::default());
        let mut visit = |object, _t| {
            let kt = scene.material_of(object).kt;
            s *= kt;
            if kt == 0.0 {
                ControlFlow::Break(())
            } else {
                ControlFlow::Continue(())
            }
        };
        let segment = Interval::new(EPS, offset.length());
        let objects = &scene.objects;
        (scene.accel).shadow_crossings(
            objects,
            &ray,
            segment,
            0,
            Some(cache),
            &mut cost,
            &mut visit,
        );
        (s, cost.primitives)
    }

    #[test]
    fn a_row_tries_the_last_opaque_blocker_first_until_the_light_comes_back() {
        // A floor y = 0 (a plane: tested by every query), a light at (0, 4, 0)
        // and an opaque ball of radius 0.5 at (0, 2, 0) between them.
        let scene = parse(
            Path::new("test.toml"),
            r#"[camera]
            eye = [0, 5, 0]
            look_at = [0, 0, 0]
            up = [0, 0, 1]
            [materials.white]
            kd = 1
            [[light]]
            position = [0, 4, 0]
            [[object]]
            material = "white"
            plane = { normal = [0, 1, 0], point = [0, 0, 0] }
            [[object]]
            material = "white"
            sphere = { center = [0, 2, 0], radius = 0.5 }"#,
        )
        .unwrap();
        let light = DVec3::new(0.0, 4.0, 0.0);
        // Points (x, 0, 0) of the floor, queried along one row.
        let along_a_row = |xs: &[f64]| {
            let mut cache = ShadowCache::default();
            xs.iter()
                .map(|&x| shadow(&scene, &mut cache, DVec3::new(x, 0.0, 0.0), light))
                .collect::<Vec<_>>()
        };
        // x = 0: the shadow ray goes straight up through the ball. It tests
        // the plane (starting on it, t = 0 is not a crossing) and the ball,
        // met at t = 1.5: S = 0, two primitives; the ball is remembered.
        // x = 0.1: the ball is tried first and met: S = 0, one primitive.
        // x = 3: towards (-3, 4, 0) / 5, the ray passes the ball's height
        // (y 1.5 to 2.5) at x 1.875 to 1.125, outside its box: the ball is
        // tried first and missed, then the plane: S = 1, two primitives, and
        // the ball is forgotten.
        // x = 3.2: likewise lit, and only the plane is tested: one primitive.
        assert_eq!(
            along_a_row(&[0.0, 0.1, 3.0, 3.2]),
            [(0.0, 2), (0.0, 1), (1.0, 2), (1.0, 1)]
        );
        // Alone, the lit points test the plane only.
        assert_eq!(along_a_row(&[3.0]), [(1.0, 1)]);
    }
}
