//! The shadow query's row cache (`raystep_accel::ShadowCache`) on a real
//! scene: its tests need a scene's objects and materials, which the accel
//! crate below the engine cannot build.

use std::ops::ControlFlow;
use std::path::Path;

use glam::DVec3;
use raystep_accel::{Cost, ShadowCache};
use raystep_model::math::{EPS, Interval, Ray};

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
