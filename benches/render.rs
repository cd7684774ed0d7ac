//! Criterion benchmarks: what recording costs, and how fast one pixel is
//! picked. Run with `cargo bench --bench render`.

use std::path::Path;

use criterion::{Criterion, criterion_group, criterion_main};
use raystep_engine::record::record_pixel;
use raystep_engine::render::render;
use raystep_engine::scene::{Scene, load};
use raystep_engine::trace::{NoRecorder, RayStats};

fn scene(relative: &str, size: u32) -> Option<Scene> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(relative);
    path.exists()
        .then(|| load(&path).unwrap().with_size(size, size).unwrap())
}

fn recorders(c: &mut Criterion) {
    for (name, relative) in [
        ("seven-rays", "scenes/seven-rays.toml"),
        ("teapot", "scenes/spd/teapot.nff"),
        ("gears", "scenes/spd/gears.nff"),
    ] {
        let Some(scene) = scene(relative, 128) else {
            continue;
        };
        let mut group = c.benchmark_group(format!("render 128x128 {name}"));
        group.sample_size(20);
        group.bench_function("recording off (NoRecorder)", |b| {
            b.iter(|| render::<NoRecorder>(&scene, &scene.settings, &|| {}))
        });
        group.bench_function("ray counts on (RayStats)", |b| {
            b.iter(|| render::<RayStats>(&scene, &scene.settings, &|| {}))
        });
        group.finish();
    }
}

fn pick_pixel(c: &mut Criterion) {
    for (name, relative, x, y) in [
        ("teapot", "scenes/spd/teapot.nff", 256, 256),
        ("gears", "scenes/spd/gears.nff", 256, 300),
    ] {
        let Some(scene) = scene(relative, 512) else {
            continue;
        };
        c.bench_function(&format!("record one pixel {name}"), |b| {
            b.iter(|| record_pixel(&scene, &scene.settings, x, y))
        });
    }
}

criterion_group!(benches, recorders, pick_pixel);
criterion_main!(benches);
