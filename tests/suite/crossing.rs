//! The crossing test whole (edge by edge, in text, JSON and the 2-D SVG
//! figure) and the near misses of spheres.

use crate::support::{raystep, record, scene, stderr};
use raystep_engine::record::record_pixel;
use raystep_model::shapes::{RootChoice, Working};

/// polygons.toml's star; pixel (40, 54) lies between its two lower legs.
/// Its ray meets z = 0 at (-1.7963, 2.0002). Drop z: U = x, V = y. The
/// edges whose ends straddle y = 2.0002 are the lower legs' sides:
///   2→3 (-2.1114, 2.4826)→(-2.3084, 1.8314): x = -2.2573, U = -0.461, left
///   3→4 (-2.3084, 1.8314)→(-1.75, 2.22):     x = -2.0658, U = -0.270, left
///   4→5 (-1.75, 2.22)→(-1.1916, 1.8314):     x = -1.4342, U = +0.362, counts
///   5→6 (-1.1916, 1.8314)→(-1.3886, 2.4826): x = -1.2427, U = +0.554, counts
/// Every other edge lies above y = 2.2. Two crossings: even, outside.
const NOTCH: (u32, u32) = (40, 54);

fn polygons() -> raystep_engine::scene::Scene {
    raystep_engine::scene::load(std::path::Path::new("scenes/polygons.toml")).unwrap()
}

#[test]
fn the_notch_records_every_edge_of_the_crossing_test() {
    let scene = polygons();
    let tree = record_pixel(&scene, &scene.settings, NOTCH.0, NOTCH.1);
    assert!(tree.check_finite().is_ok());
    let json = tree.to_json();
    let near = &json["tree"]["near_misses"][0];
    assert_eq!(near["object"], "star");
    let figure = &near["crossing_figure"];
    assert_eq!(figure["dropped_axis"], "z");
    assert_eq!(figure["vertices"].as_array().unwrap().len(), 10);
    let straddling: Vec<(u64, u64, f64, bool)> = figure["edges"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|e| e["straddles"] == true)
        .map(|e| {
            (
                e["from"].as_u64().unwrap(),
                e["to"].as_u64().unwrap(),
                e["u"].as_f64().unwrap(),
                e["counts"].as_bool().unwrap(),
            )
        })
        .collect();
    let expected = [
        (2, 3, -0.461, false),
        (3, 4, -0.270, false),
        (4, 5, 0.362, true),
        (5, 6, 0.554, true),
    ];
    assert_eq!(straddling.len(), expected.len(), "{straddling:?}");
    for (got, want) in straddling.iter().zip(expected) {
        assert_eq!((got.0, got.1, got.3), (want.0, want.1, want.3));
        assert!((got.2 - want.2).abs() < 1e-3, "{got:?} vs {want:?}");
    }
    // The same count as the tracer's own test.
    let Working::Polygon(w) = tree.root().near_misses[0].working else {
        panic!("a polygon")
    };
    assert_eq!(w.crossing.unwrap().crossings, 2);
}

#[test]
fn inspect_and_explain_name_the_edges_that_crossed() {
    let pixel = format!("{},{}", NOTCH.0, NOTCH.1);
    let inspect = raystep(&["inspect", "scenes/polygons.toml", "--pixel", &pixel]);
    let text = String::from_utf8(inspect.stdout).unwrap();
    assert!(text.contains("edge 4→5: crosses +U at U = 0.362"), "{text}");
    assert!(
        text.contains("edge 3→4: crosses V = 0 at U = -0.2"),
        "{text}"
    );
    let explain = raystep(&["explain", "scenes/polygons.toml", "--pixel", &pixel]);
    // explain wraps at 100 columns: compare with its line breaks undone.
    let text = String::from_utf8(explain.stdout).unwrap();
    let text = text.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(
        text.contains("outside the polygon: 2 edge crossings of +U (edges 4→5 at U = 0.362"),
        "{text}"
    );
    assert!(text.contains(", 5→6 at U = 0.553"), "{text}");
}

const CAMERA: &str = "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\n";

fn unit_ball() -> raystep_engine::scene::Scene {
    scene(&format!(
        "{CAMERA}
        [materials.m]
        kd = 1
        [[object]]
        name = \"ball\"
        material = \"m\"
        sphere = {{ center = [0, 0, 0], radius = 1 }}"
    ))
}

#[test]
fn a_ray_through_a_spheres_box_past_the_sphere_is_a_near_miss() {
    // o = (0.9, 0.9, 5), d = (0, 0, -1): inside the box's x and y range
    // [-1, 1], so it crosses the box for t in [4, 6]. A = 1,
    // B = 2 d·(o - c) = -10, C = 0.81 + 0.81 + 25 - 1 = 25.62,
    // discriminant 100 - 102.48 = -2.48: no real roots. Closest approach at
    // t = -B / 2A = 5, distance sqrt(0.81 + 0.81) = 1.2728 > r = 1.
    let tree = record(&unit_ball(), [0.9, 0.9, 5.0], [0.0, 0.0, -1.0]);
    let root = tree.root();
    assert!(root.hit.is_none());
    assert_eq!(root.near_misses.len(), 1);
    let near = &root.near_misses[0];
    let Working::Sphere(w) = near.working else {
        panic!("a sphere")
    };
    assert!((w.discriminant + 2.48).abs() < 1e-9, "{}", w.discriminant);
    assert_eq!(w.choice, RootChoice::NoRealRoots);
    let c = near.closest_approach.unwrap();
    assert!((c.t - 5.0).abs() < 1e-12);
    assert!((c.distance - 1.62f64.sqrt()).abs() < 1e-12);
    assert_eq!(c.radius, 1.0);
    let text = raystep_engine::record::text(&tree);
    assert!(
        text.contains("no real roots: the ray passes the sphere by"),
        "{text}"
    );
    assert!(
        text.contains("comes within 1.2728 of the centre (at t = 5)"),
        "{text}"
    );
    // o = (1.5, 0, 5): outside the box's x range, never near: not listed.
    let tree = record(&unit_ball(), [1.5, 0.0, 5.0], [0.0, 0.0, -1.0]);
    assert!(tree.root().near_misses.is_empty());
}

#[test]
fn a_sphere_behind_a_ray_starting_in_its_box_is_a_near_miss() {
    // o = (0.8, 0.8, 0.8), inside the box, |o| = 1.386 > 1; d = (1, 1, 1)
    // away from the centre. A = 3, B = 2 * 2.4 = 4.8, C = 1.92 - 1 = 0.92,
    // discriminant 23.04 - 11.04 = 12, roots (-4.8 ± 3.4641) / 6 =
    // -1.3774 and -0.2227: both behind.
    let tree = record(&unit_ball(), [0.8, 0.8, 0.8], [1.0, 1.0, 1.0]);
    let near = &tree.root().near_misses[0];
    let Working::Sphere(w) = near.working else {
        panic!("a sphere")
    };
    assert_eq!(w.choice, RootChoice::BothBehind);
    assert!((w.t1.unwrap() + 0.2227).abs() < 1e-4);
    // A ray that hits the ball has no near miss.
    let tree = record(&unit_ball(), [0.0, 0.0, 5.0], [0.0, 0.0, -1.0]);
    assert!(tree.root().near_misses.is_empty());
}

/// Writes the crossing figure of polygons.toml's pixel and returns its text.
fn crossing_svg(dir: &std::path::Path, pixel: (u32, u32)) -> String {
    let out = dir.join("crossing.svg");
    let output = raystep(&[
        "diagram",
        "scenes/polygons.toml",
        "--pixel",
        &format!("{},{}", pixel.0, pixel.1),
        "--plane",
        "crossing",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    std::fs::read_to_string(out).unwrap()
}

fn count_class(doc: &roxmltree::Document, class: &str) -> usize {
    doc.descendants()
        .filter(|n| n.attribute("class") == Some(class))
        .count()
}

#[test]
fn the_crossing_figure_marks_each_crossing() {
    let dir = tempfile::tempdir().unwrap();
    // The notch: 2 crossings counted (4→5, 5→6), 2 left of the point.
    let svg = crossing_svg(dir.path(), NOTCH);
    let doc = roxmltree::Document::parse(&svg).expect("well-formed XML");
    assert_eq!(count_class(&doc, "crossing"), 2);
    assert_eq!(count_class(&doc, "left-crossing"), 2);
    assert_eq!(count_class(&doc, "counted-edge"), 2);
    // The +U half-line (the ray's colour, 2.5 wide) is drawn after the
    // polygon's fill, so it shows inside the polygon.
    let order: Vec<&str> = doc.descendants().map(|n| n.tag_name().name()).collect();
    let polygon = order.iter().position(|&t| t == "polygon").unwrap();
    let half_line = doc
        .descendants()
        .position(|n| n.has_tag_name("line") && n.attribute("stroke-width") == Some("2.5"))
        .unwrap();
    assert!(polygon < half_line, "the fill would hide the half-line");
    let texts: Vec<&str> = doc.descendants().filter_map(|n| n.text()).collect();
    for expected in [
        "2 crossings: even, outside",
        "1: edge 4→5",
        "2: edge 5→6",
        "U = x",
        "V = y",
    ] {
        assert!(texts.contains(&expected), "no {expected:?} in {texts:?}");
    }
    assert!(
        texts
            .iter()
            .any(|t| t.starts_with("dropped z: U = x, V = y"))
    );
    // Passed by: the origin is where the ray meets the plane, not a hit.
    assert!(texts.contains(&"plane point"), "{texts:?}");
    assert!(!texts.contains(&"hit point"), "{texts:?}");
    // The lower left leg (32, 52), a hit: by polygons.toml's header, the
    // half-line crosses the leg's own edge 3→4 and both edges of the right
    // leg (4→5, 5→6): 3, inside; edge 2→3 meets V = 0 left of the point.
    let svg = crossing_svg(dir.path(), (32, 52));
    let doc = roxmltree::Document::parse(&svg).unwrap();
    assert_eq!(count_class(&doc, "crossing"), 3);
    assert_eq!(count_class(&doc, "left-crossing"), 1);
    assert!(svg.contains("3 crossings: odd, inside"));
    assert!(svg.contains(">hit point</text>"));
}

#[test]
fn the_crossing_figure_is_pinned() {
    let dir = tempfile::tempdir().unwrap();
    let svg = crossing_svg(dir.path(), NOTCH);
    snapshot!("polygons_40_54_crossing", svg);
}

#[test]
fn no_polygon_means_no_crossing_figure() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("none.svg");
    let output = raystep(&[
        "diagram",
        "scenes/glass.toml",
        "--pixel",
        "1,1",
        "--plane",
        "crossing",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(!output.status.success());
    assert!(stderr(&output).contains("no ray of its tree hits a polygon or patch"));
    assert!(!out.exists());
}
