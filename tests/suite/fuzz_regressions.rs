//! Inputs the cargo-fuzz targets (`fuzz/`) found, minimized, each pinned so
//! that it stays fixed: loading gives a scene or an error naming a line,
//! never a panic, and a loaded scene records finite pixels.

use std::path::Path;

use raystep_engine::record::record_pixel;
use raystep_engine::scene;

/// Loads `text` (the format from `name`'s extension); if it loads, records
/// every pixel (of a 4x4 image, unless the scene's own is at most 8x8) and
/// checks that each number is finite.
fn load_and_trace(name: &str, text: &str) {
    let scene = match scene::parse(Path::new(name), text) {
        Ok(scene) => scene,
        Err(error) => {
            assert!(error.location.is_some(), "no line in: {error}");
            let _ = error.to_string();
            return;
        }
    };
    let scene = if scene.width * scene.height <= 64 {
        scene
    } else {
        scene.with_size(4, 4).unwrap()
    };
    for y in 0..scene.height {
        for x in 0..scene.width {
            let tree = record_pixel(&scene, &scene.settings, x, y);
            assert!(
                tree.color().is_finite(),
                "pixel ({x}, {y}) is {}",
                tree.color()
            );
            if let Err(error) = tree.check_finite() {
                panic!("pixel ({x}, {y}): {error}");
            }
        }
    }
}

/// Found by hand while checking the trace target can fail (the fuzzer, with
/// max_depth clamped to 8, found nothing in 577k runs): the primary ray of a
/// 1x1 image hits the plane exactly at the light, so L = normalize(0) is NaN
/// and so are N·L, the diffuse term and the pixel.
#[test]
fn light_exactly_at_the_hit_point() {
    load_and_trace(
        "lit.toml",
        "[camera]\neye = [0, 5, 0]\nlook_at = [0, 0, 0]\nup = [0, 0, 1]\n\
         [image]\nwidth = 1\nheight = 1\n[materials.m]\nkd = 1\n\
         [[light]]\nposition = [0, 0, 0]\n\
         [[object]]\nmaterial = \"m\"\nplane = { normal = [0, 1, 0], point = [0, 0, 0] }\n",
    );
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
    // A polyline is no surface: it is left out, and nothing else is there.
    let polyline = format!("{five_points}l 02/-194 -2/-2 00\n");
    assert_eq!(
        load_bytes(Path::new("f.obj"), polyline.as_bytes()).unwrap(),
        0
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
