//! Property tests of the loaders and the tracer, the ordinary-suite cousins
//! of the cargo-fuzz targets in `fuzz/`:
//! (a) mutated example scenes never panic a loader, and every error names a line;
//! (b) random valid TOML scenes trace to finite pixels and finite recordings,
//!     whose JSON holds no `null` where a number belongs.

use std::path::Path;

use proptest::prelude::*;
use raystep_engine::record::record_pixel;
use raystep_engine::scene::{self, Scene};
use serde_json::Value;

// ---------- (a) mutated scene text ----------

const TOML_SCENES: [&str; 7] = [
    include_str!("../../scenes/attenuation.toml"),
    include_str!("../../scenes/glass.toml"),
    include_str!("../../scenes/highlights.toml"),
    include_str!("../../scenes/mirrors.toml"),
    include_str!("../../scenes/polygons.toml"),
    include_str!("../../scenes/seven-rays.toml"),
    include_str!("../../scenes/shadows.toml"),
];

const NFF_SCENES: [&str; 5] = [
    include_str!("../../scenes/spd/balls-small.nff"),
    include_str!("../../scenes/spd/mount-small.nff"),
    include_str!("../../scenes/spd/rings-small.nff"),
    include_str!("../../scenes/spd/tetra-small.nff"),
    include_str!("../../scenes/spd/tree-small.nff"),
];

/// One edit of a file's bytes; positions are taken modulo the current length.
#[derive(Clone, Debug)]
enum Mutation {
    FlipBit(usize, u8),
    Delete(usize, usize),
    Insert(usize, Vec<u8>),
    DuplicateLine(usize),
    DeleteLine(usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    // Bytes that matter to both grammars, so insertions make near-misses of
    // valid syntax rather than only noise.
    let token = prop::sample::select(vec![
        "=",
        "[",
        "]",
        "{",
        "}",
        ",",
        "\"",
        "\n",
        "#",
        "-",
        ".",
        "e",
        "9",
        "0",
        "1e308",
        "nan",
        "inf",
        "-1",
        "p 3",
        "s ",
        "c ",
        "f ",
        "v\n",
        "[[object]]",
        "[camera]",
        "max_depth",
        "radius",
        "ior",
        "é",
    ]);
    prop_oneof![
        (any::<usize>(), 0u8..8).prop_map(|(at, bit)| Mutation::FlipBit(at, bit)),
        (any::<usize>(), 1usize..16).prop_map(|(at, n)| Mutation::Delete(at, n)),
        (any::<usize>(), token).prop_map(|(at, t)| Mutation::Insert(at, t.as_bytes().to_vec())),
        any::<usize>().prop_map(Mutation::DuplicateLine),
        any::<usize>().prop_map(Mutation::DeleteLine),
    ]
}

/// The byte range of line `index` (modulo the line count), newline included.
fn line_range(bytes: &[u8], index: usize) -> std::ops::Range<usize> {
    let starts: Vec<usize> = std::iter::once(0)
        .chain(
            bytes
                .iter()
                .enumerate()
                .filter(|(_, b)| **b == b'\n')
                .map(|(i, _)| i + 1),
        )
        .filter(|&s| s < bytes.len())
        .collect();
    let line = index % starts.len().max(1);
    let start = starts.get(line).copied().unwrap_or(0);
    let end = starts.get(line + 1).copied().unwrap_or(bytes.len());
    start..end
}

fn apply(bytes: &mut Vec<u8>, mutation: &Mutation) {
    if bytes.is_empty() {
        return;
    }
    let len = bytes.len();
    match mutation {
        Mutation::FlipBit(at, bit) => bytes[at % len] ^= 1 << bit,
        Mutation::Delete(at, n) => {
            let start = at % len;
            bytes.drain(start..(start + n).min(len));
        }
        Mutation::Insert(at, token) => {
            let at = at % (len + 1);
            bytes.splice(at..at, token.iter().copied());
        }
        Mutation::DuplicateLine(line) => {
            let range = line_range(bytes, *line);
            let copy = bytes[range.clone()].to_vec();
            bytes.splice(range.end..range.end, copy);
        }
        Mutation::DeleteLine(line) => {
            bytes.drain(line_range(bytes, *line));
        }
    }
}

/// Loads the mutated text: it may fail, but never panic, and its error must
/// point at a line of the file.
fn check_loader(name: &str, original: &str, mutations: &[Mutation]) {
    let mut bytes = original.as_bytes().to_vec();
    for m in mutations {
        apply(&mut bytes, m);
    }
    let text = String::from_utf8_lossy(&bytes);
    if let Err(error) = scene::parse(Path::new(name), &text) {
        let shown = error.to_string();
        let location = error
            .location
            .as_ref()
            .unwrap_or_else(|| panic!("the error names no line: {shown}\n--- text ---\n{text}"));
        let lines = text.lines().count().max(1);
        assert!(
            (1..=lines + 1).contains(&location.line),
            "line {} of a {lines}-line file: {shown}",
            location.line
        );
        assert!(shown.starts_with(&format!("{name}:{}:", location.line)));
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn mutated_toml_never_panics_and_errors_name_a_line(
        which in 0..TOML_SCENES.len(),
        mutations in prop::collection::vec(mutation(), 1..5),
    ) {
        check_loader("mutated.toml", TOML_SCENES[which], &mutations);
    }

    #[test]
    fn mutated_nff_never_panics_and_errors_name_a_line(
        which in 0..NFF_SCENES.len(),
        mutations in prop::collection::vec(mutation(), 1..5),
    ) {
        check_loader("mutated.nff", NFF_SCENES[which], &mutations);
    }
}

// ---------- (b) random valid scenes trace to finite numbers ----------

fn coord() -> impl Strategy<Value = f64> {
    -100.0..100.0f64
}

fn point() -> impl Strategy<Value = [f64; 3]> {
    [coord(), coord(), coord()]
}

fn colour() -> impl Strategy<Value = [f64; 3]> {
    [0.0..2.0f64, 0.0..2.0f64, 0.0..2.0f64]
}

/// A direction of length between 0.5 and 2 (so never zero).
fn direction() -> impl Strategy<Value = [f64; 3]> {
    [-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64].prop_filter("not too short", |v| {
        let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        l > 0.5
    })
}

fn vector(v: [f64; 3]) -> String {
    format!("[{:?}, {:?}, {:?}]", v[0], v[1], v[2])
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn length(a: [f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

fn camera() -> impl Strategy<Value = String> {
    (point(), point(), direction(), 10.0..120.0f64)
        .prop_filter("a camera with a frame", |(eye, at, up, _)| {
            let forward = sub(*at, *eye);
            length(forward) > 1.0 && length(cross(forward, *up)) > 0.2 * length(forward)
        })
        .prop_map(|(eye, at, up, fov)| {
            format!(
                "[camera]\neye = {}\nlook_at = {}\nup = {}\nfov = {fov:?}\n\n[image]\nwidth = 8\nheight = 6\n",
                vector(eye),
                vector(at),
                vector(up)
            )
        })
}

fn settings() -> impl Strategy<Value = String> {
    let attenuation = || [0.5..2.0f64, 0.0..0.2f64, 0.0..0.01f64];
    (colour(), colour(), attenuation(), attenuation(), 1u32..=6, any::<bool>()).prop_map(
        |(background, ambient, lights, rays, depth, phong)| {
            format!(
                "[settings]\nbackground = {}\nambient = {}\nlight_attenuation = {}\nray_attenuation = {}\nmax_depth = {depth}\nspecular = \"{}\"\n",
                vector(background),
                vector(ambient),
                vector(lights),
                vector(rays),
                if phong { "phong" } else { "blinn" }
            )
        },
    )
}

fn material(index: usize) -> impl Strategy<Value = String> {
    let unit = || 0.0..1.0f64;
    (colour(), unit(), unit(), unit(), 1.0..2.5f64, 1.0..200.0f64, unit()).prop_map(
        move |(color, kd, ks, kt, ior, n, ka)| {
            format!(
                "[materials.m{index}]\ncolor = {}\nkd = {kd:?}\nks = {ks:?}\nkt = {kt:?}\nior = {ior:?}\nn = {n:?}\nka = {ka:?}\n",
                vector(color)
            )
        },
    )
}

fn light() -> impl Strategy<Value = String> {
    (point(), colour()).prop_map(|(position, color)| {
        format!(
            "[[light]]\nposition = {}\ncolor = {}\n",
            vector(position),
            vector(color)
        )
    })
}

/// A triangle whose vertices are far from collinear.
fn triangle() -> impl Strategy<Value = [[f64; 3]; 3]> {
    [point(), point(), point()].prop_filter("not degenerate", |[a, b, c]| {
        length(cross(sub(*b, *a), sub(*c, *a))) > 1.0
    })
}

/// One shape of the kind `kind` (0 to 5), as an inline table.
fn shape(kind: usize) -> BoxedStrategy<String> {
    let radius = || 0.1..50.0f64;
    let axis =
        || (point(), point()).prop_filter("distinct ends", |(a, b)| length(sub(*a, *b)) > 0.1);
    match kind {
        0 => (point(), radius())
            .prop_map(|(c, r)| format!("sphere = {{ center = {}, radius = {r:?} }}", vector(c)))
            .boxed(),
        1 => (direction(), point())
            .prop_map(|(n, p)| {
                format!(
                    "plane = {{ normal = {}, point = {} }}",
                    vector(n),
                    vector(p)
                )
            })
            .boxed(),
        2 => triangle()
            .prop_map(|[a, b, c]| {
                format!(
                    "polygon = {{ vertices = [{}, {}, {}] }}",
                    vector(a),
                    vector(b),
                    vector(c)
                )
            })
            .boxed(),
        3 => (triangle(), [direction(), direction(), direction()])
            .prop_map(|([a, b, c], [na, nb, nc])| {
                format!(
                    "patch = {{ vertices = [{}, {}, {}], normals = [{}, {}, {}] }}",
                    vector(a),
                    vector(b),
                    vector(c),
                    vector(na),
                    vector(nb),
                    vector(nc)
                )
            })
            .boxed(),
        4 => (axis(), radius())
            .prop_map(|((b, a), r)| {
                format!(
                    "cylinder = {{ base = {}, apex = {}, radius = {r:?} }}",
                    vector(b),
                    vector(a)
                )
            })
            .boxed(),
        // An apex radius is 0 (a pointed cone) or in the loader's range
        // (0.001 and up): one drawn from 0..50 fell below 0.001 about once
        // in 50,000 cones, and the test blamed the generator.
        _ => (axis(), radius(), prop_oneof![Just(0.0), 0.001..50.0f64])
            .prop_map(|((b, a), rb, ra)| {
                format!(
                    "cone = {{ base = {}, base_radius = {rb:?}, apex = {}, apex_radius = {ra:?} }}",
                    vector(b),
                    vector(a)
                )
            })
            .boxed(),
    }
}

const MATERIALS: usize = 3;

/// An object of shape kind `kind`, with one of the materials.
fn object(kind: usize) -> impl Strategy<Value = String> {
    (shape(kind), 0..MATERIALS)
        .prop_map(|(shape, m)| format!("[[object]]\nmaterial = \"m{m}\"\n{shape}\n"))
}

/// A whole valid scene: one object of every shape kind plus up to three more.
fn valid_scene() -> impl Strategy<Value = String> {
    let every_kind: Vec<_> = (0..6).map(object).collect();
    let extra = prop::collection::vec((0usize..6).prop_flat_map(object), 0..4);
    let materials: Vec<_> = (0..MATERIALS).map(material).collect();
    (
        camera(),
        settings(),
        materials,
        prop::collection::vec(light(), 1..4),
        every_kind,
        extra,
    )
        .prop_map(|(camera, settings, materials, lights, objects, extra)| {
            [vec![camera, settings], materials, lights, objects, extra]
                .concat()
                .join("\n")
        })
}

/// Keys whose value is an `Option` in the recording, so may be `null` in
/// its JSON; a `null` anywhere else is a number that was not finite.
const OPTIONAL_KEYS: [&str; 14] = [
    "hit",
    "refraction",
    "reflected",
    "transmitted",
    "shadow",
    "s",
    "fan_triangle",
    "barycentric",
    "crossing",
    "t",
    "direction",
    "distance",
    // A sphere's roots, absent for a near miss with no real roots.
    "t0",
    "t1",
];

/// The path of the first `null` that stands where a number belongs.
fn misplaced_null(value: &Value, path: &str) -> Option<String> {
    match value {
        Value::Array(items) => items.iter().enumerate().find_map(|(i, v)| {
            let path = format!("{path}[{i}]");
            if v.is_null() {
                Some(path)
            } else {
                misplaced_null(v, &path)
            }
        }),
        Value::Object(map) => map.iter().find_map(|(k, v)| {
            let path = format!("{path}.{k}");
            match v {
                Value::Null if OPTIONAL_KEYS.contains(&k.as_str()) => None,
                Value::Null => Some(path),
                _ => misplaced_null(v, &path),
            }
        }),
        _ => None,
    }
}

/// Records a few pixels and checks every number of each recording.
fn check_traces(scene: &Scene, text: &str) {
    for (x, y) in [(0, 0), (7, 5), (4, 3), (2, 4)] {
        let tree = record_pixel(scene, &scene.settings, x, y);
        let color = tree.color();
        assert!(color.is_finite(), "pixel ({x}, {y}) is {color}\n{text}");
        if let Err(error) = tree.check_finite() {
            panic!("pixel ({x}, {y}): {error}\n{text}");
        }
        let json = tree.to_json();
        if let Some(path) = misplaced_null(&json, "recording") {
            panic!("pixel ({x}, {y}): {path} is null\n{text}");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn valid_scenes_trace_to_finite_recordings(text in valid_scene()) {
        let scene = scene::parse(Path::new("random.toml"), &text)
            .unwrap_or_else(|e| panic!("the generator wrote an invalid scene: {e}\n{text}"));
        check_traces(&scene, &text);
    }
}

/// The null check itself can fail: a recording's JSON with a NaN in it
/// (serde_json writes it as `null`) is caught, at the path of the NaN.
#[test]
fn a_nan_in_the_json_is_caught_as_a_misplaced_null() {
    let json = serde_json::json!({
        "tree": { "hit": null, "color": [0.5, f64::NAN, 0.25], "weight": 1.0 }
    });
    assert_eq!(
        misplaced_null(&json, "recording"),
        Some("recording.tree.color[1]".to_string())
    );
    let json = serde_json::json!({ "tree": { "hit": null, "f_att": f64::INFINITY } });
    assert_eq!(
        misplaced_null(&json, "recording"),
        Some("recording.tree.f_att".to_string())
    );
}
