//! One engine: a recorded tree never disagrees with the image, and the image
//! is the same whatever the thread count.

use std::path::{Path, PathBuf};

use raystep_engine::record::record_pixel;
use raystep_engine::render::{render, with_threads};
use raystep_engine::scene::{Scene, load};
use raystep_engine::trace::{NoRecorder, RayStats, trace};
use raystep_model::math::to_rgb8;

use crate::support::top_level_toml_scenes;

fn example_scenes() -> Vec<PathBuf> {
    let paths = top_level_toml_scenes();
    assert!(paths.len() >= 7, "the example scenes are there");
    paths
}

fn small(path: &Path) -> Scene {
    load(path).unwrap().with_size(32, 24).unwrap()
}

#[test]
fn every_recorded_pixel_equals_the_rendered_pixel_bit_for_bit() {
    let mut misses = 0;
    for path in example_scenes() {
        let scene = small(&path);
        let (image, _) = render::<NoRecorder>(&scene, &scene.settings, &|| {});
        let viewport = scene.camera.viewport(scene.width, scene.height);
        for y in 0..scene.height {
            for x in 0..scene.width {
                let tree = record_pixel(&scene, &scene.settings, x, y);
                let plain = trace(
                    &scene,
                    &scene.settings,
                    &viewport.primary_ray(x, y),
                    &mut NoRecorder,
                );
                assert_eq!(
                    tree.color().to_array().map(f64::to_bits),
                    plain.to_array().map(f64::to_bits)
                );
                assert_eq!(
                    to_rgb8(tree.color()),
                    image.get_pixel(x, y).0,
                    "{} ({x}, {y})",
                    path.display()
                );
                // The stored terms add up to a hit's colour; a miss returns
                // the scene's background (MODEL §5), which it has no terms for.
                for (id, node) in tree.nodes.iter().enumerate() {
                    let expected = match tree.sum_of_terms(id) {
                        Some(sum) => sum,
                        None => {
                            misses += 1;
                            scene.settings.background
                        }
                    };
                    assert_eq!(
                        node.color,
                        expected,
                        "{} ({x}, {y}) node {id}",
                        path.display()
                    );
                }
            }
        }
    }
    assert!(misses > 0, "some rays miss, so the background is checked");
}

#[test]
fn one_thread_and_all_threads_give_the_same_bytes() {
    let mut paths = example_scenes();
    paths.push(Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/spd/gears-small.nff"));
    for path in paths.iter().filter(|p| p.exists()) {
        let scene = load(path).unwrap().with_size(64, 48).unwrap();
        let one = with_threads(Some(1), || {
            render::<NoRecorder>(&scene, &scene.settings, &|| {}).0
        })
        .unwrap();
        let all = with_threads(None, || {
            render::<NoRecorder>(&scene, &scene.settings, &|| {}).0
        })
        .unwrap();
        let three = with_threads(Some(3), || {
            render::<NoRecorder>(&scene, &scene.settings, &|| {}).0
        })
        .unwrap();
        assert_eq!(one.as_raw(), all.as_raw(), "{}", path.display());
        assert_eq!(one.as_raw(), three.as_raw(), "{}", path.display());
    }
}

#[test]
fn the_shadow_cache_changes_no_colour_and_no_count() {
    // The render keeps the last opaque blocker per light along a row; tracing
    // each pixel on its own (a fresh cache) must give the same bytes and the
    // same ray counts. The SPD rings are full of self-shadowing.
    let rings = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/spd/rings-small.nff");
    let mut paths = example_scenes();
    paths.push(rings);
    for path in paths.iter().filter(|p| p.exists()) {
        let scene = load(path).unwrap().with_size(48, 36).unwrap();
        let (image, stats) = render::<RayStats>(&scene, &scene.settings, &|| {});
        let viewport = scene.camera.viewport(scene.width, scene.height);
        let mut alone = RayStats::default();
        for y in 0..scene.height {
            for x in 0..scene.width {
                let mut pixel = RayStats::default();
                let color = trace(
                    &scene,
                    &scene.settings,
                    &viewport.primary_ray(x, y),
                    &mut pixel,
                );
                alone.add(&pixel);
                assert_eq!(
                    to_rgb8(color),
                    image.get_pixel(x, y).0,
                    "{} ({x}, {y})",
                    path.display()
                );
            }
        }
        // Only the cost may differ: that is what the cache is for.
        assert_eq!(counts(stats), counts(alone), "{}", path.display());
        if path.ends_with("rings-small.nff") {
            assert!(
                stats.shadow_opaque > 100,
                "the cache is exercised: {stats:?}"
            );
        }
    }
}

/// The ray counts of MODEL §7 alone, without what the queries cost.
fn counts(mut stats: RayStats) -> RayStats {
    stats.closest_nodes = 0;
    stats.closest_primitives = 0;
    stats.shadow_nodes = 0;
    stats.shadow_primitives = 0;
    stats
}

#[test]
fn the_stats_count_the_cost_the_trees_record() {
    // The stats add up the cost the tracer reports for each query; the ray
    // tree of the same pixel stores those same costs, ray by ray. Closest-hit
    // queries are the same query in both. A recording walks every shadow
    // segment to its end to list all blockers, while a render stops at the
    // first opaque one: the render's shadow cost is at most the tree's.
    let mut paths = example_scenes();
    paths.push(Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/spd/tetra-small.nff"));
    for path in paths.iter().filter(|p| p.exists()) {
        let scene = small(path);
        let viewport = scene.camera.viewport(scene.width, scene.height);
        let (mut closest, mut shadow) = ((0u64, 0u64), (0u64, 0u64));
        let mut stats = RayStats::default();
        for y in 0..scene.height {
            for x in 0..scene.width {
                trace(
                    &scene,
                    &scene.settings,
                    &viewport.primary_ray(x, y),
                    &mut stats,
                );
                let tree = record_pixel(&scene, &scene.settings, x, y);
                for node in &tree.nodes {
                    closest.0 += u64::from(node.cost.nodes);
                    closest.1 += u64::from(node.cost.primitives);
                    for light in &node.lights {
                        if let Some(record) = &light.shadow {
                            shadow.0 += u64::from(record.cost.nodes);
                            shadow.1 += u64::from(record.cost.primitives);
                        }
                    }
                }
            }
        }
        let name = path.display();
        assert_eq!(
            (stats.closest_nodes, stats.closest_primitives),
            closest,
            "{name}"
        );
        assert!(stats.shadow_nodes <= shadow.0, "{name}");
        assert!(stats.shadow_primitives <= shadow.1, "{name}");
        // Every primary ray tests at least the root (one node per query).
        assert!(stats.closest_nodes >= stats.primary, "{name}: {stats:?}");
    }
}
