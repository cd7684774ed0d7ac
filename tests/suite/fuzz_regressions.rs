//! Inputs the cargo-fuzz targets (`fuzz/`) found, minimized, each pinned so
//! that it stays fixed. Each regression asserts that its input reaches the
//! path it pins: a scene that must trace loads (a load error fails the
//! test, it does not pass it) and records finite pixels that went where the
//! input leads; a mesh that must be refused is refused at its line.

use std::path::Path;

use raystep_engine::record::{RayTree, record_pixel};
use raystep_engine::scene::{self, Scene};

/// The scene `text` (the format from `name`'s extension), which must load:
/// a regression that needs a trace is not passed by a load error.
fn load(name: &str, text: &str) -> Scene {
    scene::parse(Path::new(name), text).unwrap_or_else(|error| panic!("{name} must load: {error}"))
}

/// The recording of every pixel of `scene` (at most 8x8), row by row, each
/// checked to be finite in its colour and in every number it records.
fn trace_every_pixel(scene: &Scene) -> Vec<RayTree> {
    assert!(
        scene.width * scene.height <= 64,
        "a regression's image is small"
    );
    let mut trees = Vec::new();
    for y in 0..scene.height {
        for x in 0..scene.width {
            let tree = record_pixel(scene, &scene.settings, x, y);
            assert!(
                tree.color().is_finite(),
                "pixel ({x}, {y}) is {}",
                tree.color()
            );
            if let Err(error) = tree.check_finite() {
                panic!("pixel ({x}, {y}): {error}");
            }
            trees.push(tree);
        }
    }
    trees
}

/// Found by hand while checking the trace target can fail (the fuzzer, with
/// max_depth clamped to 8, found nothing in 577k runs): the primary ray of a
/// 1x1 image hits the plane exactly at the light, so L = normalize(0) was NaN
/// and so were N·L, the diffuse term and the pixel. MODEL §4 now takes a
/// light within EPS of the point as at the point.
#[test]
fn light_exactly_at_the_hit_point() {
    let scene = load(
        "lit.toml",
        "[camera]\neye = [0, 5, 0]\nlook_at = [0, 0, 0]\nup = [0, 0, 1]\n\
         [image]\nwidth = 1\nheight = 1\n[materials.m]\nkd = 1\n\
         [[light]]\nposition = [0, 0, 0]\n\
         [[object]]\nmaterial = \"m\"\nplane = { normal = [0, 1, 0], point = [0, 0, 0] }\n",
    );
    let trees = trace_every_pixel(&scene);
    let root = trees[0].root();
    // The path pinned: the plane is hit at the light's own position.
    let hit = root.hit.as_ref().expect("the primary ray hits the plane");
    assert_eq!((hit.object_index, hit.t), (0, 5.0));
    assert_eq!(hit.point, glam::DVec3::ZERO);
    let light = &root.lights[0];
    assert!(light.at_point, "the light is at the hit point: {light:?}");
}

/// The mesh loaders' finds (fuzz target `mesh_loaders`), minimized: each is
/// refused at its line, or loads without the polyline, never a panic (the
/// first one overflowed inside tobj in a build with overflow checks).
#[test]
fn mesh_loader_finds() {
    use raystep_engine::scene::mesh::load_bytes;
    let five_points = "v 552.8 0.0   0.0\nv   0.0 0.0   0.0\nv   0.0 0.0 559.2\n\
                       v 549.6 0.0 559.2\nv 549.6 0.0 559.2\nvt 132.0 0\n";
    // An `l` line of three points with a texture index far out of range:
    // tobj read it as a triangle and computed -194 + 1 texture coordinates.
    // A polyline is no surface: it is left out, and nothing else is there,
    // so the mesh is refused, saying why (issue 41: never an empty render).
    let polyline = format!("{five_points}l 02/-194 -2/-2 00\n");
    let error = load_bytes(Path::new("f.obj"), polyline.as_bytes()).unwrap_err();
    assert_eq!(
        error.message,
        "f.obj: the mesh has no triangles to show: it has 5 `v` line(s) and no `f` line \
         (its `l` lines are polylines, not surfaces)"
    );
    // A polyline beside a face: only the face's triangle is read.
    let beside = format!("{five_points}l 1 2 3 4\nf 1 2 3\n");
    assert_eq!(
        load_bytes(Path::new("f.obj"), beside.as_bytes()).unwrap(),
        1
    );
    // U+000B is whitespace to tobj: `f` is its keyword here too, and its
    // index out of range is found at its line and column.
    let tab = format!("{five_points}f\u{b}-9 1 2\n");
    let error = load_bytes(Path::new("f.obj"), tab.as_bytes()).unwrap_err();
    let at = error.location.as_ref().expect("a line and column");
    assert_eq!((at.line, at.column), (7, 3), "{error}");
}
